// libFuzzer target for camera path files (docs/scene.md, "Camera paths"): arbitrary text must be
// refused with "<file>: <field>: <problem>", or give a path whose every sampled pose, made
// usable as the renderer makes it, is finite with unit, orthogonal axes.
#include "fuzz_check.h"

#include "hexlod/scene/camera_path.h"

#include <glm/glm.hpp>

using hexlod::fuzz::allFinite;
using hexlod::fuzz::check;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    hexlod::scene::CameraPath path;
    std::string error;
    if (!hexlod::scene::parseCameraPath(text, "fuzz.json", path, error)) {
        check(hexlod::fuzz::startsWith(error, "fuzz.json:") &&
              error.size() > 11); // ": field: " or ":line:col: "
        return 0;
    }
    check(!path.keyframes.empty() && path.viewportWidth > 0 && path.viewportHeight > 0);
    check(allFinite(path.nearPlane, path.farPlane) && path.nearPlane > 0.0 && path.farPlane > path.nearPlane);
    check(allFinite(path.duration()) && path.duration() >= 0.0);
    for (const hexlod::scene::CameraPose& raw : path.sample(7, glm::dvec3(1e6, -2e6, 10.0))) {
        const hexlod::scene::CameraPose pose = hexlod::scene::usablePose(raw);
        check(allFinite(pose.position.x, pose.position.y, pose.position.z, pose.fovY));
        check(std::abs(glm::length(pose.forward) - 1.0) < 1e-6 &&
              std::abs(glm::length(pose.up) - 1.0) < 1e-6);
        check(std::abs(glm::dot(pose.forward, pose.up)) < 1e-6);
        check(pose.fovY > 0.0 && pose.fovY < 3.1415927);
    }
    return 0;
}
