// Environment images read when the scene is built (docs/scene-format.md#environment): the
// errors a bad image gives (file, line, pointer, what was wrong), and the clamping of
// out-of-gamut texels reported, never silent.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include <unistd.h>

#include <iris/exr/exr.hpp>
#include <iris/scene/scene.hpp>

namespace {

struct temp_dir {
    std::filesystem::path path = std::filesystem::temp_directory_path() / ("iris-env-image-test-" + std::to_string(::getpid()));
    temp_dir() { std::filesystem::create_directories(path); }
    ~temp_dir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
};

void write_map(const std::filesystem::path& p, int w, int h, const std::function<iris::rgb_pixel(int, int)>& f) {
    iris::image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) img(x, y) = f(x, y);
    iris::exr::write(p, img);
}

std::string scene_with(const std::string& environment) {
    return R"({"camera": {"position": [0, 1, 3], "look_at": [0, 0, 0]},
  "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
  "environment": )" +
           environment + R"(,
  "shapes": [{"type": "quad", "size": [2, 2], "material": "m"}]})";
}

/// \brief The message parsing `environment` gives (empty if it parses).
std::string error_of(const std::string& environment, const std::filesystem::path& dir) {
    try {
        (void)iris::scene::parse_scene(scene_with(environment), "env.json", dir);
    } catch (const iris::scene::error& e) {
        return e.what();
    }
    return {};
}

}  // namespace

TEST(EnvironmentImage, BadImagesGiveTheFileLineAndWhatWasWrong) {
    temp_dir dir;
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    write_map(dir.path / "wide.exr", 8, 4, [](int, int) { return iris::rgb_pixel{1, 1, 1}; });
    write_map(dir.path / "nan.exr", 8, 4, [&](int x, int) { return iris::rgb_pixel{1, x == 3 ? nan : 1.0f, 1}; });
    write_map(dir.path / "inf.exr", 8, 4, [&](int x, int y) { return iris::rgb_pixel{x == 1 && y == 2 ? inf : 1.0f, 1, 1}; });
    write_map(dir.path / "black.exr", 8, 4, [](int, int) { return iris::rgb_pixel{0, 0, 0}; });
    write_map(dir.path / "negative.exr", 8, 4, [](int, int) { return iris::rgb_pixel{-1, -0.5f, 0}; });
    { std::ofstream(dir.path / "garbage.exr") << "not an EXR file"; }
    const struct {
        const char* environment;
        const char* message;
    } cases[] = {
        {R"({"image": "wide.exr", "mapping": "equal-area"})", "env.json:3: environment/image: an equal-area environment image must be square, got 8x4"},
        {R"({"image": "nan.exr"})", "env.json:3: environment/image: the environment image has a pixel that is not finite"},
        {R"({"image": "inf.exr"})", "env.json:3: environment/image: the environment image has a pixel that is not finite"},
        {R"({"image": "black.exr"})", "env.json:3: environment/image: the environment image is black"},
        {R"({"image": "negative.exr"})", "env.json:3: environment/image: the environment image is black"},
        {R"({"image": "garbage.exr"})", "env.json:3: environment/image: "},
        {R"({"image": "wide.exr", "scale": 1e300})", "env.json:3: environment/scale: expected a scale of the image's radiance in (0, "},
        {R"({"image": "wide.exr", "mapping": "cube"})", "env.json:3: environment/mapping: unknown environment mapping 'cube'; expected latlong or equal-area"},
    };
    for (const auto& c : cases) {
        const std::string e = error_of(c.environment, dir.path);
        EXPECT_EQ(e.rfind(c.message, 0), 0u) << c.environment << "\n  gave: " << e << "\n  expected: " << c.message;
    }
    EXPECT_EQ(error_of(R"({"image": "wide.exr", "mapping": "latlong", "scale": 2})", dir.path), "");
}

// A texel with a negative component is clamped to 0 and counted; iris-scene and
// iris-render print `approximations` as warnings.
TEST(EnvironmentImage, OutOfGamutTexelsAreClampedAndReported) {
    temp_dir dir;
    write_map(dir.path / "sky.exr", 8, 4, [](int x, int y) {
        return iris::rgb_pixel{x == 0 && y < 3 ? -0.25f : 1.0f, 1.0f, 1.0f};
    });
    const auto s = iris::scene::parse_scene(scene_with(R"({"image": "sky.exr"})"), "env.json", dir.path);
    ASSERT_TRUE(s.environment && s.environment->map);
    EXPECT_EQ(s.environment->map->negative_texels, 3u);
    const auto a = iris::scene::approximations(s);
    ASSERT_EQ(a.size(), 1u);
    EXPECT_NE(a[0].find("3 of 32 texels have a negative (out-of-sRGB-gamut) component, clamped to 0"), std::string::npos) << a[0];
    write_map(dir.path / "sky.exr", 8, 4, [](int, int) { return iris::rgb_pixel{1.0f, 1.0f, 1.0f}; });
    EXPECT_TRUE(iris::scene::approximations(iris::scene::parse_scene(scene_with(R"({"image": "sky.exr"})"), "env.json", dir.path)).empty());
}

// "rotation" turns the map: the rows of the matrix taking the map's directions to the
// world's, stored as its inverse (world → map); one that is not orthogonal is an error.
TEST(EnvironmentImage, ARotationTurnsTheMap) {
    temp_dir dir;
    write_map(dir.path / "sky.exr", 8, 4, [](int x, int) { return iris::rgb_pixel{static_cast<float>(x), 1.0f, 1.0f}; });
    // the map's +y (up) to the world's +x, its +x to the world's −y
    const auto s = iris::scene::parse_scene(scene_with(R"({"image": "sky.exr", "rotation": [[0, 1, 0], [-1, 0, 0], [0, 0, 1]]})"), "env.json", dir.path);
    const glm::mat3& m = s.environment->map->to_map;
    EXPECT_LT(glm::length(m * glm::vec3(1, 0, 0) - glm::vec3(0, 1, 0)), 1e-6f);
    EXPECT_LT(glm::length(m * glm::vec3(0, -1, 0) - glm::vec3(1, 0, 0)), 1e-6f);
    const auto plain = iris::scene::parse_scene(scene_with(R"({"image": "sky.exr"})"), "env.json", dir.path);
    EXPECT_EQ(plain.environment->map->to_map, glm::mat3(1.0f));
    EXPECT_NE(iris::scene::fingerprint(s), iris::scene::fingerprint(plain));
    const std::string e = error_of(R"({"image": "sky.exr", "rotation": [[1, 0, 0], [0, 2, 0], [0, 0, 1]]})", dir.path);
    EXPECT_NE(e.find("env.json:3: environment/rotation: the rotation must be orthogonal"), std::string::npos) << e;
    EXPECT_NE(error_of(R"({"image": "sky.exr", "rotation": [[1, 0, 0], [0, 1, 0]]})", dir.path).find("three rows"), std::string::npos);
}
