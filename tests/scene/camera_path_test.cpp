// Camera paths: parsing with named errors, interpolation through every keyframe, sampling.
#include "../scratch_folder.h"
#include "hexlod/scene/camera_path.h"
#include "hexlod/scene/scene_config.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace hexlod::scene {
namespace {

constexpr const char* kPath = R"({
  "name": "test", "relative_to": "scene_centre", "viewport": [320, 200], "fov_y_degrees": 50,
  "keyframes": [
    {"time": 0, "position": [0, 0, 2], "target": [0, 10, 2]},
    {"time": 2, "position": [10, 0, 2], "target": [10, 10, 2]},
    {"time": 3, "position": [10, 10, 30], "target": [0, 0, 0], "fov_y_degrees": 80}
  ]
})";

TEST(CameraPathTest, PassesThroughEveryKeyframe) {
    CameraPath path;
    std::string error;
    ASSERT_TRUE(parseCameraPath(kPath, "p.json", path, error)) << error;
    EXPECT_TRUE(path.relativeToSceneCentre);
    EXPECT_EQ(path.viewportWidth, 320u);
    EXPECT_DOUBLE_EQ(path.duration(), 3.0);
    const glm::dvec3 origin(1e7, -2e6, 0.0);
    for (const CameraKeyframe& key : path.keyframes) {
        CameraPose pose = path.at(key.time, origin);
        EXPECT_NEAR(glm::length(pose.position - (key.position + origin)), 0.0, 1e-6);
        EXPECT_NEAR(glm::length(pose.forward - glm::normalize(key.target - key.position)), 0.0, 1e-9);
        EXPECT_NEAR(pose.fovY, key.fovY, 1e-12);
        EXPECT_NEAR(glm::dot(pose.forward, pose.up), 0.0, 1e-12);
        EXPECT_NEAR(glm::length(pose.up), 1.0, 1e-12);
    }
    // Halfway along the first segment, on a straight stretch of the spline.
    CameraPose middle = path.at(1.0, glm::dvec3(0.0));
    EXPECT_GT(middle.position.x, 2.0);
    EXPECT_LT(middle.position.x, 8.0);
    // Clamped outside the path.
    EXPECT_EQ(path.at(-5.0, origin).position, path.at(0.0, origin).position);
    EXPECT_EQ(path.at(99.0, origin).position, path.at(3.0, origin).position);
}

TEST(CameraPathTest, SamplingSpansThePathAndAZeroLengthPathRepeatsItsPose) {
    CameraPath path;
    std::string error;
    ASSERT_TRUE(parseCameraPath(kPath, "p.json", path, error)) << error;
    std::vector<CameraPose> poses = path.sample(7, glm::dvec3(0.0));
    ASSERT_EQ(poses.size(), 7u);
    EXPECT_EQ(poses.front().position, path.keyframes.front().position);
    EXPECT_NEAR(glm::length(poses.back().position - path.keyframes.back().position), 0.0, 1e-9);

    CameraPath still;
    ASSERT_TRUE(parseCameraPath(R"({"keyframes": [{"position": [1, 2, 3], "target": [1, 3, 3]}]})", "s.json",
                                still, error))
        << error;
    EXPECT_DOUBLE_EQ(still.duration(), 0.0);
    for (const CameraPose& pose : still.sample(5, glm::dvec3(0.0)))
        EXPECT_EQ(pose.position, glm::dvec3(1, 2, 3));
    EXPECT_EQ(still.sample(1, glm::dvec3(0.0)).size(), 1u);
}

TEST(CameraPathTest, LookingStraightDownKeepsAValidUpVector) {
    CameraPath path;
    std::string error;
    ASSERT_TRUE(parseCameraPath(R"({"keyframes": [{"position": [0, 0, 100], "target": [0, 0, 0]}]})",
                                "d.json", path, error))
        << error;
    CameraPose pose = path.at(0.0, glm::dvec3(0.0));
    EXPECT_NEAR(pose.forward.z, -1.0, 1e-12);
    EXPECT_NEAR(glm::length(pose.up), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(pose.up, pose.forward), 0.0, 1e-12);
}

struct BadPath {
    const char* text;
    const char* error;
};

class BadCameraPathTest : public ::testing::TestWithParam<BadPath> {};

TEST_P(BadCameraPathTest, IsRejectedNamingTheField) {
    CameraPath path;
    std::string error;
    EXPECT_FALSE(parseCameraPath(GetParam().text, "bad.json", path, error));
    EXPECT_EQ(error, GetParam().error);
}

INSTANTIATE_TEST_SUITE_P(
    Table, BadCameraPathTest,
    ::testing::Values(
        BadPath{"{", "bad.json:1:2: not valid JSON"},
        // Found by the camera_path fuzzer: a number past a double's range escaped as an exception.
        BadPath{R"({"near": 1e999})",
                "bad.json:1:10: a number is out of range (1e999 does not fit a double)"},
        BadPath{"{\"a\":\n -2000000000000000000000000000e400}",
                "bad.json:2:2: a number is out of range (-2000000000000000000000000000e400 does not fit a "
                "double)"},
        BadPath{"[]", "bad.json: top level: expected an object"},
        BadPath{"{}", "bad.json: keyframes: is required"},
        BadPath{R"({"keyframes": []})", "bad.json: keyframes: expected a non-empty array"},
        BadPath{R"({"keyframes": [{"position": [0, 0], "target": [1, 0, 0]}]})",
                "bad.json: keyframes[0].position: expected 3 finite numbers"},
        BadPath{R"({"keyframes": [{"position": [0, 0, "x"], "target": [1, 0, 0]}]})",
                "bad.json: keyframes[0].position[2]: expected a number"},
        BadPath{R"({"keyframes": [{"position": [0, 0, 1e300], "target": [1, 0, 0]}]})",
                "bad.json: keyframes[0].position[2]: must be a finite number in [-1e+09, 1e+09], got 1e+300"},
        BadPath{R"({"keyframes": [{"position": [0, 0, 0], "target": [0, 0, 0]}]})",
                "bad.json: keyframes[0].target: must differ from the position"},
        BadPath{R"({"keyframes": [{"time": 1, "position": [0, 0, 0], "target": [1, 0, 0]},
                                  {"time": 1, "position": [1, 0, 0], "target": [2, 0, 0]}]})",
                "bad.json: keyframes[1].time: must be greater than the previous keyframe's time"},
        BadPath{R"({"keyframes": [{"position": [0, 0, 0], "target": [1, 0, 0], "fov_y_degrees": 180}]})",
                "bad.json: keyframes[0].fov_y_degrees: must be a finite number in [0.01, 179.99], got 180"},
        BadPath{R"({"keyframes": [{"position": [0, 0, 0], "target": [1, 0, 0], "speed": 2}]})",
                "bad.json: keyframes[0].speed: unknown field (see docs/scene.md)"},
        BadPath{R"({"viewport": [0, 10], "keyframes": [{"position": [0, 0, 0], "target": [1, 0, 0]}]})",
                "bad.json: viewport: must not be 0"},
        BadPath{R"({"near": 10, "far": 5, "keyframes": [{"position": [0, 0, 0], "target": [1, 0, 0]}]})",
                "bad.json: far: must be greater than near"},
        BadPath{R"({"relative_to": "moon", "keyframes": [{"position": [0, 0, 0], "target": [1, 0, 0]}]})",
                "bad.json: relative_to: expected \"world\" or \"scene_centre\", got \"moon\""},
        BadPath{R"({"interpolation": "cubic", "keyframes": [{"position": [0, 0, 0], "target": [1, 0, 0]}]})",
                "bad.json: interpolation: expected \"catmull_rom\" or \"linear\", got \"cubic\""}));

TEST(LodProfileFileTest, ReadsOverDefaultsAndNamesBadFields) {
    const testing::ScratchFolder folder("hexlod-lod");
    const std::filesystem::path& dir = folder.path();
    std::string good = (dir / "good.json").string(), bad = (dir / "bad.json").string(), error;
    std::ofstream(good) << R"({"max_screen_space_error": 4})";
    std::ofstream(bad) << R"({"hysteresis": 1.0})";
    LodProfile profile;
    ASSERT_TRUE(loadLodProfile(good, profile, error)) << error;
    EXPECT_DOUBLE_EQ(profile.maxScreenSpaceError, 4.0);
    EXPECT_DOUBLE_EQ(profile.hysteresis, LodProfile().hysteresis);
    EXPECT_FALSE(loadLodProfile(bad, profile, error));
    EXPECT_EQ(error, bad + ": hysteresis: must be a finite number in [0, 0.95], got 1.0");
    EXPECT_FALSE(loadLodProfile((dir / "missing.json").string(), profile, error));
    EXPECT_NE(error.find("cannot open LOD profile"), std::string::npos);
}

} // namespace
} // namespace hexlod::scene
