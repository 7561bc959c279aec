// Camera path parsing and interpolation.
#include "hexlod/scene/camera_path.h"

#include "json_fields.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace hexlod::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxCoordinate = 1e9; // a billion metres: beyond any city, within double precision

glm::dvec3 readVector(const Json& value, const std::string& path) {
    if (!value.is_array() || value.size() != 3) Fields::fail(path, "expected 3 finite numbers");
    glm::dvec3 v;
    for (int i = 0; i < 3; ++i) {
        v[i] = Fields::checkedNumber(value[size_t(i)], path + "[" + std::to_string(i) + "]", -kMaxCoordinate,
                                     kMaxCoordinate);
    }
    return v;
}

// Uniform Catmull-Rom through p1 (t = 0) and p2 (t = 1), with p0 and p3 as neighbours.
glm::dvec3 catmullRom(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, const glm::dvec3& p3,
                      double t) {
    const double t2 = t * t, t3 = t2 * t;
    return 0.5 * ((2.0 * p1) + (-p0 + p2) * t + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2 +
                  (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * t3);
}

} // namespace

CameraPose usablePose(CameraPose pose) {
    const bool finiteForward = std::isfinite(pose.forward.x) && std::isfinite(pose.forward.y) &&
                               std::isfinite(pose.forward.z) && glm::length(pose.forward) > 0.0;
    pose.forward = finiteForward ? glm::normalize(pose.forward) : glm::dvec3(0, 1, 0);
    glm::dvec3 up = pose.up;
    if (!(std::isfinite(up.x) && std::isfinite(up.y) && std::isfinite(up.z))) up = glm::dvec3(0, 0, 1);
    up -= glm::dot(up, pose.forward) * pose.forward;
    if (glm::length(up) < 1e-6) {
        up = std::abs(pose.forward.z) > 0.9999 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
        up -= glm::dot(up, pose.forward) * pose.forward;
    }
    pose.up = glm::normalize(up);
    pose.fovY = std::clamp(std::isfinite(pose.fovY) ? pose.fovY : 1.0, 1e-4, kPi - 1e-4);
    return pose;
}

CameraPose CameraPath::at(double time, const glm::dvec3& origin) const {
    const size_t n = keyframes.size();
    size_t segment = 0;
    double t = 0.0;
    if (n > 1) {
        time = std::clamp(time, keyframes.front().time, keyframes.back().time);
        while (segment + 2 < n && time > keyframes[segment + 1].time) ++segment;
        const double span = keyframes[segment + 1].time - keyframes[segment].time;
        t = span > 0.0 ? (time - keyframes[segment].time) / span : 0.0;
    }
    const CameraKeyframe& a = keyframes[segment];
    const CameraKeyframe& b = keyframes[std::min(segment + 1, n - 1)];
    glm::dvec3 position, target;
    if (interpolation == PathInterpolation::Linear || n < 3) {
        position = a.position + (b.position - a.position) * t;
        target = a.target + (b.target - a.target) * t;
    } else {
        // End segments mirror their outer neighbour so the spline still passes every keyframe.
        const CameraKeyframe& before = keyframes[segment > 0 ? segment - 1 : 0];
        const CameraKeyframe& after = keyframes[std::min(segment + 2, n - 1)];
        position = catmullRom(before.position, a.position, b.position, after.position, t);
        target = catmullRom(before.target, a.target, b.target, after.target, t);
    }
    CameraPose pose;
    pose.position = position + origin;
    pose.fovY = a.fovY + (b.fovY - a.fovY) * t;
    glm::dvec3 forward = target - position;
    pose.forward = glm::length(forward) > 0.0 ? glm::normalize(forward) : glm::dvec3(0.0, 1.0, 0.0);
    // World z is up, unless the camera looks straight along it.
    glm::dvec3 up(0.0, 0.0, 1.0);
    if (std::abs(glm::dot(up, pose.forward)) > 0.9999) up = glm::dvec3(0.0, 1.0, 0.0);
    pose.up = glm::normalize(up - glm::dot(up, pose.forward) * pose.forward);
    return pose;
}

std::vector<CameraPose> CameraPath::sample(uint32_t frames, const glm::dvec3& origin) const {
    std::vector<CameraPose> poses;
    poses.reserve(frames);
    const double start = keyframes.front().time, span = duration();
    for (uint32_t f = 0; f < frames; ++f) {
        const double t = frames > 1 ? start + span * double(f) / double(frames - 1) : start;
        poses.push_back(at(t, origin));
    }
    return poses;
}

bool parseCameraPath(std::string_view text, const std::string& file, CameraPath& out, std::string& error) {
    Json document;
    if (!parseJsonText(text, file, document, error)) return false;
    CameraPath path;
    try {
        Fields root(document, "");
        path.name = root.text("name", file);
        const std::string relative = root.text("relative_to", "world");
        if (relative != "world" && relative != "scene_centre") {
            Fields::fail("relative_to", "expected \"world\" or \"scene_centre\", got \"" + relative + "\"");
        }
        path.relativeToSceneCentre = relative == "scene_centre";
        const std::string interpolation = root.text("interpolation", "catmull_rom");
        if (interpolation != "catmull_rom" && interpolation != "linear") {
            Fields::fail("interpolation",
                         "expected \"catmull_rom\" or \"linear\", got \"" + interpolation + "\"");
        }
        path.interpolation =
            interpolation == "linear" ? PathInterpolation::Linear : PathInterpolation::CatmullRom;
        if (const Json* viewport = root.find("viewport")) {
            if (!viewport->is_array() || viewport->size() != 2)
                Fields::fail("viewport", "expected [width, height]");
            path.viewportWidth = uint32_t(Fields::checkedWhole((*viewport)[0], "viewport[0]", 16384));
            path.viewportHeight = uint32_t(Fields::checkedWhole((*viewport)[1], "viewport[1]", 16384));
            if (path.viewportWidth == 0 || path.viewportHeight == 0)
                Fields::fail("viewport", "must not be 0");
        }
        path.nearPlane = root.number("near", path.nearPlane, 1e-6, 1e9);
        path.farPlane = root.number("far", path.farPlane, 1e-6, 1e12);
        if (path.farPlane <= path.nearPlane) Fields::fail("far", "must be greater than near");
        const double defaultFov = root.number("fov_y_degrees", 60.0, 0.01, 179.99);
        const Json& keyframes = root.require("keyframes");
        if (!keyframes.is_array() || keyframes.empty())
            Fields::fail("keyframes", "expected a non-empty array");
        for (size_t k = 0; k < keyframes.size(); ++k) {
            const std::string at = "keyframes[" + std::to_string(k) + "]";
            Fields fields(keyframes[k], at);
            CameraKeyframe key;
            key.time = fields.number("time", double(k), -1e9, 1e9);
            if (!path.keyframes.empty() && key.time <= path.keyframes.back().time) {
                Fields::fail(fields.at("time"), "must be greater than the previous keyframe's time");
            }
            key.position = readVector(fields.require("position"), fields.at("position"));
            key.target = readVector(fields.require("target"), fields.at("target"));
            if (key.target == key.position)
                Fields::fail(fields.at("target"), "must differ from the position");
            key.fovY = fields.number("fov_y_degrees", defaultFov, 0.01, 179.99) * kPi / 180.0;
            fields.finish();
            path.keyframes.push_back(key);
        }
        root.finish();
    } catch (const ConfigError& e) {
        error = file + ": " + e.what();
        return false;
    }
    out = std::move(path);
    return true;
}

bool loadCameraPath(const std::string& path, CameraPath& out, std::string& error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = "cannot open camera path '" + path + "'";
        return false;
    }
    std::ostringstream text;
    text << in.rdbuf();
    return parseCameraPath(text.str(), path, out, error);
}

} // namespace hexlod::scene
