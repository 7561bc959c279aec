// Shared pieces of the JSON config readers.
#include "json_fields.h"

#include <fstream>

namespace hexlod::scene {

namespace {

// "line:column" of a byte offset.
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

} // namespace

bool parseJsonText(std::string_view text, const std::string& file, Json& out, std::string& error) {
    try {
        out = Json::parse(text.begin(), text.end());
        return true;
    } catch (const Json::parse_error& e) {
        error = file + ":" + lineAndColumn(text, e.byte) + ": not valid JSON";
    } catch (const Json::out_of_range& e) {
        // No offset comes with it, only the number ("number overflow parsing '1e999'"): the
        // position given is where those characters first appear, which is the number itself
        // unless the same characters came earlier inside a string.
        const std::string what = e.what();
        const size_t open = what.find("parsing '"), close = what.rfind('\'');
        const std::string number =
            open != std::string::npos && close > open + 9 ? what.substr(open + 9, close - open - 9) : "";
        const size_t at = number.empty() ? std::string_view::npos : text.find(number);
        error = file + (at == std::string_view::npos ? "" : ":" + lineAndColumn(text, at + 1)) +
                ": a number is out of range (" + (number.empty() ? "too large" : number) +
                " does not fit a double)";
    }
    return false;
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
    lod.treeGeometricError = fields.number("tree_geometric_error", lod.treeGeometricError, 0.0, 1e6);
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
    if (!parseJsonText(content, path, document, error)) return false;
    try {
        out = readLodProfile(document, "", out);
    } catch (const ConfigError& e) {
        error = path + ": " + e.what();
        return false;
    }
    return true;
}

} // namespace hexlod::scene
