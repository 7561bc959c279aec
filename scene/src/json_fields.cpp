// Shared pieces of the JSON config readers.
#include "json_fields.h"

#include <fstream>

namespace hexlod::scene {

std::string lineAndColumn(std::string_view text, size_t byte) {
    size_t line = 1, column = 1;
    for (size_t i = 0; i + 1 < byte && i < text.size(); ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return std::to_string(line) + ":" + std::to_string(column);
}

LodProfile readLodProfile(const Json& value, const std::string& path, LodProfile lod) {
    Fields fields(value, path);
    lod.maxScreenSpaceError = fields.number("max_screen_space_error", lod.maxScreenSpaceError, 0.01, 1000.0);
    // The band must leave room between its edges: at 1 a cell could never switch back.
    lod.hysteresis = fields.number("hysteresis", lod.hysteresis, 0.0, 0.95);
    if (const Json* errors = fields.find("geometric_error")) {
        const std::string at = fields.at("geometric_error");
        if (!errors->is_array() || errors->size() != 5) Fields::fail(at, "expected 5 numbers, LOD0 to LOD4");
        for (size_t i = 0; i < 5; ++i) {
            lod.geometricError[i] =
                Fields::checkedNumber((*errors)[i], at + "[" + std::to_string(i) + "]", 0.0, 1e6);
            // A finer LOD must not claim a larger error than a coarser one, or selection flips.
            if (i > 0 && lod.geometricError[i] > lod.geometricError[i - 1]) {
                Fields::fail(at, "errors must not grow from LOD0 to LOD4");
            }
        }
    }
    fields.finish();
    return lod;
}

bool loadLodProfile(const std::string& path, LodProfile& out, std::string& error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = "cannot open LOD profile '" + path + "'";
        return false;
    }
    std::ostringstream text;
    text << in.rdbuf();
    const std::string content = text.str();
    Json document;
    try {
        document = Json::parse(content);
    } catch (const Json::parse_error& e) {
        error = path + ":" + lineAndColumn(content, e.byte) + ": not valid JSON";
        return false;
    }
    try {
        out = readLodProfile(document, "", out);
    } catch (const ConfigError& e) {
        error = path + ": " + e.what();
        return false;
    }
    return true;
}

} // namespace hexlod::scene
