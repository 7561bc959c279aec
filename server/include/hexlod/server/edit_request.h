// The body of POST /api/v1/edits (docs/protocol.md) turned into a catalog selector and
// parameter values, with errors that name the JSON field at fault ("params.floor_h",
// "selector.buildings[3]"). The same code reads journal entries back at start, so an entry
// replays exactly as it was accepted.
#pragma once

#include "hexlod/cells/batch_catalog.h"

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>

namespace hexlod::server {

struct EditSpec {
    cells::Selector selector;
    scene::ParameterMap params;
    nlohmann::json selectorJson; // as given, for the journal and the history
    nlohmann::json paramsJson;
    std::string comment;
};

struct EditError {
    std::string field; // JSON path of the offending member, "" for the whole body
    std::string message;
    std::string text() const { return field.empty() ? message : field + ": " + message; }
};

inline constexpr size_t kMaxCommentBytes = 1024;
inline constexpr size_t kMaxParamsPerEdit = 256;

// Checks the body's JSON shape and types: one selector form, a non-empty object of finite
// numbers, an optional comment string, nothing else.
bool parseEditBody(std::string_view body, EditSpec& out, EditError& error);
bool editFromJson(const nlohmann::json& selector, const nlohmann::json& params, EditSpec& out,
                  EditError& error);

// Checks that the selector names buildings, a cell or a grammar the scene holds. Parameter
// names and ranges are the catalog's to check (BatchCatalog::setParams).
bool checkSelector(const cells::BatchCatalog& catalog, const EditSpec& edit, EditError& error);

// The field a setParams error is about: "params.<name>" when it names a parameter, "selector"
// when the selection is at fault, else "params".
std::string fieldOfCatalogError(const std::string& message);

} // namespace hexlod::server
