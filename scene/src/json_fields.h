// Strict reading of JSON configs (scenes, camera paths, LOD profiles): every field is checked
// for type and range, and a field nobody reads is an error naming it, so a typo never turns
// into a silently ignored setting. Errors carry the field's path ("lod.geometric_error[2]").
#pragma once

#include "hexlod/scene/scene_config.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace hexlod::scene {

using Json = nlohmann::json;

// Thrown with the field path and the problem; parseSceneConfig turns it into `error`.
struct ConfigError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Reads one JSON object, remembering which keys were read so that anything left over (a
// typo such as "cel_size") is an error naming it instead of a silently ignored setting.
class Fields {
public:
    Fields(const Json& object, std::string path) : object_(object), path_(std::move(path)) {
        if (!object_.is_object()) fail(path_.empty() ? "top level" : path_, "expected an object");
    }

    [[noreturn]] static void fail(const std::string& path, const std::string& message) {
        throw ConfigError(path + ": " + message);
    }
    std::string at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

    const Json* find(const std::string& key) {
        read_.insert(key);
        const auto it = object_.find(key);
        return it == object_.end() ? nullptr : &*it;
    }
    const Json& require(const std::string& key) {
        const Json* value = find(key);
        if (!value) fail(at(key), "is required");
        return *value;
    }

    double number(const std::string& key, double fallback, double lo, double hi) {
        const Json* value = find(key);
        return value ? checkedNumber(*value, at(key), lo, hi) : fallback;
    }
    uint64_t whole(const std::string& key, uint64_t fallback, uint64_t hi) {
        const Json* value = find(key);
        return value ? checkedWhole(*value, at(key), hi) : fallback;
    }
    std::string text(const std::string& key, const std::string& fallback) {
        const Json* value = find(key);
        if (!value) return fallback;
        if (!value->is_string() || value->get<std::string>().empty())
            fail(at(key), "expected a non-empty string");
        return value->get<std::string>();
    }

    void finish() const {
        for (const auto& [key, value] : object_.items()) {
            if (!read_.count(key)) fail(at(key), "unknown field (see docs/scene.md)");
        }
    }

    static double checkedNumber(const Json& value, const std::string& path, double lo, double hi) {
        if (!value.is_number()) fail(path, "expected a number");
        const double v = value.get<double>();
        if (!std::isfinite(v) || v < lo || v > hi) {
            std::ostringstream range;
            range << "must be a finite number in [" << lo << ", " << hi << "], got " << value.dump();
            fail(path, range.str());
        }
        return v;
    }
    static uint64_t checkedWhole(const Json& value, const std::string& path, uint64_t hi) {
        if (!value.is_number_integer() || value.get<int64_t>() < 0 || value.get<uint64_t>() > hi) {
            fail(path, "expected a whole number in [0, " + std::to_string(hi) + "], got " + value.dump());
        }
        return value.get<uint64_t>();
    }

private:
    const Json& object_;
    std::string path_;
    std::set<std::string> read_;
};

// Parses a config's JSON text. False with "<file>:<line>:<column>: not valid JSON" for a
// syntax error, and "<file>:<line>:<column>: a number is out of range" for one too large for
// a double (1e999), which nlohmann reports by another exception than syntax errors.
bool parseJsonText(std::string_view text, const std::string& file, Json& out, std::string& error);

// Reads an LOD profile object at `path` over `fallback`.
LodProfile readLodProfile(const Json& value, const std::string& path, LodProfile fallback);

} // namespace hexlod::scene
