// Camera paths for walkthroughs and benchmarks (docs/scene.md, "Camera paths"): keyframes of
// position and view target, interpolated with uniform Catmull-Rom splines (or
// linearly), sampled into as many frames as a run asks for. Positions are world metres in
// double, optionally relative to the scene's centre so one path fits any city.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace hexlod::scene {

struct CameraPose {
    glm::dvec3 position{0.0};
    glm::dvec3 forward{0.0, 1.0, 0.0}; // unit
    glm::dvec3 up{0.0, 0.0, 1.0};      // unit, orthogonal to forward
    double fovY = 1.0;                 // radians
};

// The pose made usable: a unit forward (north when it is not finite), an up orthogonal to it
// (the given one if possible, else world z, else y), a field of view inside (0, 180) degrees.
CameraPose usablePose(CameraPose pose);

enum class PathInterpolation : uint8_t { CatmullRom, Linear };

struct CameraKeyframe {
    double time = 0.0; // seconds, strictly increasing along the path
    glm::dvec3 position{0.0};
    glm::dvec3 target{0.0}; // the point looked at
    double fovY = 1.0;
};

struct CameraPath {
    std::string name;
    bool relativeToSceneCentre = false; // positions and targets are offsets from the scene's centre
    PathInterpolation interpolation = PathInterpolation::CatmullRom;
    uint32_t viewportWidth = 1280, viewportHeight = 720;
    double nearPlane = 0.5, farPlane = 20000.0;
    std::vector<CameraKeyframe> keyframes; // at least one

    double duration() const { return keyframes.back().time - keyframes.front().time; }
    // The pose at `time` (clamped to the path), with `origin` added to positions and targets.
    CameraPose at(double time, const glm::dvec3& origin) const;
    // `frames` poses evenly spaced from the first to the last keyframe (all equal for a path
    // of one keyframe or zero duration).
    std::vector<CameraPose> sample(uint32_t frames, const glm::dvec3& origin) const;
};

// Parses a camera path; false with "<file>: <field>: <problem>" (the field is named, e.g.
// "keyframes[2].position: expected 3 finite numbers").
bool parseCameraPath(std::string_view text, const std::string& file, CameraPath& out, std::string& error);
bool loadCameraPath(const std::string& path, CameraPath& out, std::string& error);

} // namespace hexlod::scene
