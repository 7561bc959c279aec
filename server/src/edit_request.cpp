#include "hexlod/server/edit_request.h"

#include "hexlod/server/http_types.h"

#include <cmath>
#include <limits>

namespace hexlod::server {
namespace {

using Json = nlohmann::json;

bool fail(EditError& error, std::string field, std::string message) {
    error = {std::move(field), std::move(message)};
    return false;
}

std::string typeName(const Json& j) {
    return j.is_number()    ? "a number"
           : j.is_string()  ? "a string"
           : j.is_boolean() ? "a boolean"
           : j.is_null()    ? "null"
           : j.is_array()   ? "an array"
                            : "an object";
}

bool readSelector(const Json& selector, EditSpec& out, EditError& error) {
    if (!selector.is_object())
        return fail(error, "selector", "expected an object, got " + typeName(selector));
    if (selector.size() != 1)
        return fail(error, "selector",
                    "expected exactly one of \"buildings\", \"cell\" or \"grammar\", got " +
                        std::to_string(selector.size()) + " members");
    const auto member = selector.begin();
    const std::string kind = member.key();
    const Json& value = member.value();
    const std::string field = "selector." + kind;
    if (kind == "buildings") {
        if (!value.is_array() || value.empty())
            return fail(error, field, "expected a non-empty array of building ids");
        cells::BuildingIds ids;
        for (size_t i = 0; i < value.size(); ++i) {
            const Json& id = value[i];
            if (!id.is_number_unsigned() || id.get<uint64_t>() > std::numeric_limits<uint32_t>::max())
                return fail(error, field + "[" + std::to_string(i) + "]",
                            "expected a building id (a whole number in [0, 4294967295]), got " +
                                jsonText(id));
            ids.ids.push_back(id.get<uint32_t>());
        }
        out.selector = std::move(ids);
    } else if (kind == "cell") {
        if (!value.is_array() || value.size() != 2) return fail(error, field, "expected [q, r]");
        int32_t qr[2];
        for (size_t i = 0; i < 2; ++i) {
            const Json& c = value[i];
            if (!c.is_number_integer() || c.get<int64_t>() < std::numeric_limits<int32_t>::min() ||
                c.get<int64_t>() > std::numeric_limits<int32_t>::max())
                return fail(error, field + "[" + std::to_string(i) + "]",
                            "expected a 32-bit whole number, got " + jsonText(c));
            qr[i] = static_cast<int32_t>(c.get<int64_t>());
        }
        out.selector = cells::HexCoord{qr[0], qr[1]};
    } else if (kind == "grammar") {
        if (value.is_string() && !value.get<std::string>().empty()) {
            out.selector = cells::GrammarName{value.get<std::string>()};
        } else if (value.is_number_unsigned() &&
                   value.get<uint64_t>() <= std::numeric_limits<uint32_t>::max()) {
            out.selector = cells::GrammarIndex{value.get<uint32_t>()};
        } else {
            return fail(error, field, "expected a grammar name or index, got " + jsonText(value));
        }
    } else {
        return fail(error, field, "unknown selector (expected \"buildings\", \"cell\" or \"grammar\")");
    }
    out.selectorJson = selector;
    return true;
}

bool readParams(const Json& params, EditSpec& out, EditError& error) {
    if (!params.is_object())
        return fail(error, "params", "expected an object of name: number, got " + typeName(params));
    if (params.empty()) return fail(error, "params", "no parameter values given");
    if (params.size() > kMaxParamsPerEdit)
        return fail(error, "params", "more than " + std::to_string(kMaxParamsPerEdit) + " parameters");
    out.params.clear();
    for (const auto& [name, value] : params.items()) {
        const std::string field = "params." + name;
        if (name.empty()) return fail(error, "params", "empty parameter name");
        if (!value.is_number()) return fail(error, field, "expected a number, got " + typeName(value));
        const double v = value.get<double>();
        if (!std::isfinite(v)) return fail(error, field, "expected a finite number");
        out.params[name] = v;
    }
    out.paramsJson = params;
    return true;
}

} // namespace

bool editFromJson(const Json& selector, const Json& params, EditSpec& out, EditError& error) {
    return readSelector(selector, out, error) && readParams(params, out, error);
}

bool parseEditBody(std::string_view body, EditSpec& out, EditError& error) {
    Json j;
    try {
        j = Json::parse(body.begin(), body.end());
    } catch (const Json::exception& e) {
        // nlohmann's messages open with "[json.exception.parse_error.101] ": keep what follows.
        const std::string what = e.what();
        const size_t start = what.find("] ");
        return fail(error, "",
                    "the body is not valid JSON: " +
                        (start == std::string::npos ? what : what.substr(start + 2)));
    }
    if (!j.is_object()) return fail(error, "", "expected a JSON object, got " + typeName(j));
    for (const auto& [key, value] : j.items())
        if (key != "selector" && key != "params" && key != "comment")
            return fail(error, key, "unknown member (expected \"selector\", \"params\" and \"comment\")");
    if (!j.contains("selector")) return fail(error, "selector", "is required");
    if (!j.contains("params")) return fail(error, "params", "is required");
    if (j.contains("comment")) {
        const Json& comment = j["comment"];
        if (!comment.is_string())
            return fail(error, "comment", "expected a string, got " + typeName(comment));
        if (comment.get<std::string>().size() > kMaxCommentBytes)
            return fail(error, "comment", "longer than " + std::to_string(kMaxCommentBytes) + " bytes");
        out.comment = comment.get<std::string>();
    }
    return editFromJson(j["selector"], j["params"], out, error);
}

bool checkSelector(const cells::BatchCatalog& catalog, const EditSpec& edit, EditError& error) {
    const size_t buildings = catalog.scene().buildingOrigins.size();
    if (const auto* ids = std::get_if<cells::BuildingIds>(&edit.selector)) {
        for (size_t i = 0; i < ids->ids.size(); ++i)
            if (ids->ids[i] >= buildings)
                return fail(error, "selector.buildings[" + std::to_string(i) + "]",
                            "building id " + std::to_string(ids->ids[i]) +
                                " is not in the scene (ids run from 0 to " +
                                std::to_string(buildings == 0 ? 0 : buildings - 1) + ")");
    } else if (const auto* cell = std::get_if<cells::HexCoord>(&edit.selector)) {
        if (catalog.index().batchesOf(*cell).empty())
            return fail(error, "selector.cell",
                        "cell [" + std::to_string(cell->q) + ", " + std::to_string(cell->r) +
                            "] holds no building");
    } else if (const auto* name = std::get_if<cells::GrammarName>(&edit.selector)) {
        for (uint32_t g = 0; g < catalog.index().grammarCount(); ++g)
            if (catalog.grammar(g).name == name->name) return true;
        return fail(error, "selector.grammar", "grammar '" + name->name + "' is not in the scene");
    } else if (const auto* index = std::get_if<cells::GrammarIndex>(&edit.selector)) {
        if (index->index >= catalog.index().grammarCount())
            return fail(error, "selector.grammar",
                        "grammar index " + std::to_string(index->index) + " is not in the scene (" +
                            std::to_string(catalog.index().grammarCount()) + " grammars)");
    }
    return true;
}

std::string fieldOfCatalogError(const std::string& message) {
    // What the catalog says of a selection that checkSelector let through (a grammar whose
    // members are all gone, say) is the selector's fault, not the parameters'.
    for (const char* selection : {"holds no building", "is not in the scene"})
        if (message.find(selection) != std::string::npos) return "selector";
    const std::string prefix = "parameter '";
    if (message.rfind(prefix, 0) != 0) return "params";
    const size_t end = message.find('\'', prefix.size());
    return end == std::string::npos ? "params"
                                    : "params." + message.substr(prefix.size(), end - prefix.size());
}

} // namespace hexlod::server
