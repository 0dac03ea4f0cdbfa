// Reflectance textures read when the scene is built (docs/scene-format.md#diffuse): the
// errors a bad texture gives (file, line, pointer, what was wrong), sRGB decoding of 8-bit
// images, clamping reported (never silent), and the fingerprint seeing the texels.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include <unistd.h>

#include <iris/exr/exr.hpp>
#include <iris/render/texture.hpp>
#include <iris/scene/scene.hpp>
#include <iris/spectrum/rgb_upsampling.hpp>

namespace {

struct temp_dir {
    std::filesystem::path path = std::filesystem::temp_directory_path() / ("iris-texture-test-" + std::to_string(::getpid()));
    temp_dir() { std::filesystem::create_directories(path); }
    ~temp_dir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
};

iris::image make_image(int w, int h, const std::function<iris::rgb_pixel(int, int)>& f) {
    iris::image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) img(x, y) = f(x, y);
    return img;
}

std::string scene_with(const std::string& reflectance) {
    return R"({"camera": {"position": [0, 1, 3], "look_at": [0, 0, 0]},
  "materials": {"m": {"type": "diffuse",
                      "reflectance": )" +
           reflectance + R"(}},
  "environment": {"spd": "D65"},
  "shapes": [{"type": "quad", "size": [2, 2], "material": "m"}]})";
}

/// \brief The message parsing `reflectance` gives (empty if it parses).
std::string error_of(const std::string& reflectance, const std::filesystem::path& dir) {
    try {
        (void)iris::scene::parse_scene(scene_with(reflectance), "tex.json", dir);
    } catch (const iris::scene::error& e) {
        return e.what();
    }
    return {};
}

}  // namespace

TEST(TextureImage, BadTexturesGiveTheFileLineAndWhatWasWrong) {
    temp_dir dir;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    iris::exr::write(dir.path / "ok.exr", make_image(4, 4, [](int, int) { return iris::rgb_pixel{0.5f, 0.5f, 0.5f}; }));
    iris::exr::write(dir.path / "nan.exr", make_image(4, 4, [&](int x, int) { return iris::rgb_pixel{x == 2 ? nan : 0.5f, 0.5f, 0.5f}; }));
    { std::ofstream(dir.path / "garbage.png") << "not a PNG file"; }
    { std::ofstream(dir.path / "notes.txt") << "text"; }
    const struct {
        const char* reflectance;
        const char* message;
    } cases[] = {
        {R"({"texture": "missing.png"})", "tex.json:3: materials/m/reflectance/texture: texture image 'missing.png' not found (looked for "},
        {R"({"texture": "notes.txt"})", "tex.json:3: materials/m/reflectance/texture: expected a texture image (.png, .jpg, .jpeg, .bmp, .tga: sRGB-encoded; .exr: linear), got 'notes.txt'"},
        {R"({"texture": ""})", "tex.json:3: materials/m/reflectance/texture: expected the file name of texture image, got an empty string"},
        {R"({"texture": "ok.exr", "wrap": "tile"})", "tex.json:3: materials/m/reflectance/wrap: unknown texture wrap 'tile'; expected repeat, clamp or mirror"},
        {R"({"texture": "ok.exr", "encoding": "linear"})", "tex.json:3: materials/m/reflectance/encoding: an EXR texture is linear"},
        {R"({"texture": "garbage.png", "encoding": "gamma"})", "tex.json:3: materials/m/reflectance/encoding: unknown texture encoding 'gamma'; expected srgb or linear"},
        {R"({"texture": "ok.exr", "scale": 0})", "tex.json:3: materials/m/reflectance/scale: expected a scale of the texture's values in (0, "},
        {R"({"texture": "ok.exr", "filter": "nearest"})", "tex.json:3: materials/m/reflectance: unknown key 'filter'"},
        {R"({"texture": "nan.exr"})", "tex.json:3: materials/m/reflectance/texture: the texture image has a pixel that is not finite"},
        {R"({"texture": "garbage.png"})", "tex.json:3: materials/m/reflectance/texture: cannot read image '"},
    };
    for (const auto& c : cases) {
        const std::string e = error_of(c.reflectance, dir.path);
        EXPECT_EQ(e.rfind(c.message, 0), 0u) << c.reflectance << "\n  gave: " << e << "\n  expected: " << c.message;
    }
    EXPECT_EQ(error_of(R"({"texture": "ok.exr", "wrap": "mirror", "scale": 2})", dir.path), "");
}

// An 8-bit PNG holds sRGB-encoded values: read as a texture they are decoded, so a texel
// is the linear colour written (to 8-bit quantisation); with "encoding": "linear" the
// stored value is taken as it is. Row 0 is the image's top.
TEST(TextureImage, PngIsDecodedFromSrgbAndReadTopRowFirst) {
    temp_dir dir;
    const iris::rgb_pixel top{0.2f, 0.5f, 0.05f}, bottom{0.7f, 0.1f, 0.3f};
    iris::exr::write_png(dir.path / "two.png", make_image(1, 2, [&](int, int y) { return y == 0 ? top : bottom; }));
    const auto s = iris::scene::parse_scene(scene_with(R"({"texture": "two.png"})"), "tex.json", dir.path);
    ASSERT_EQ(s.textures.size(), 1u);
    const auto& t = s.textures[0];
    ASSERT_EQ(t.width, 1);
    ASSERT_EQ(t.height, 2);
    for (const auto& [row, colour] : {std::pair{0, top}, std::pair{1, bottom}}) {
        const auto want = iris::upsample_linear_srgb({colour.r, colour.g, colour.b});
        const glm::vec3 got = t.weights[static_cast<std::size_t>(row)];
        // one 8-bit step of sRGB is at most 1.4 % of a linear value above 0.04; the matrix
        // spreads it over the weights
        EXPECT_NEAR(got.x, want.red, 0.01) << row;
        EXPECT_NEAR(got.y, want.green, 0.01) << row;
        EXPECT_NEAR(got.z, want.blue, 0.01) << row;
    }
    EXPECT_EQ(t.clipped_texels, 0u);
    const auto lin = iris::scene::parse_scene(scene_with(R"({"texture": "two.png", "encoding": "linear"})"), "tex.json", dir.path);
    const auto encoded = iris::upsample_linear_srgb({iris::srgb_encode(top.r), iris::srgb_encode(top.g), iris::srgb_encode(top.b)});
    EXPECT_NEAR(lin.textures[0].weights[0].x, encoded.red, 0.01);
    EXPECT_NEAR(lin.textures[0].weights[0].y, encoded.green, 0.01);
    // the material's constant reflectance is the texture's mean
    const auto& d = std::get<iris::material::diffuse>(s.materials[0]);
    ASSERT_TRUE(d.texture.has_value());
    const glm::vec3 mean = 0.5f * (t.weights[0] + t.weights[1]);
    const double l = 550.0;
    const double want = mean.x * iris::rgb_upsampling::red_basis(l) + mean.y * iris::rgb_upsampling::green_basis(l) +
                        mean.z * iris::rgb_upsampling::blue_basis(l);
    EXPECT_NEAR(d.reflectance(l), want, 1e-6);
}

// Values above 1 (after the scale) are clamped and counted, and the tools say so.
TEST(TextureImage, ClampedTexelsAreReported) {
    temp_dir dir;
    iris::exr::write(dir.path / "bright.exr", make_image(4, 2, [](int x, int) { return iris::rgb_pixel{x == 0 ? 3.0f : 0.5f, 0.5f, 0.5f}; }));
    const auto s = iris::scene::parse_scene(scene_with(R"({"texture": "bright.exr"})"), "tex.json", dir.path);
    EXPECT_EQ(s.textures[0].clipped_texels, 2u);
    const auto notes = iris::scene::approximations(s);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("2 of 8 texels are outside [0, 1]"), std::string::npos) << notes[0];
    const auto scaled = iris::scene::parse_scene(scene_with(R"({"texture": "bright.exr", "scale": 0.3})"), "tex.json", dir.path);
    EXPECT_EQ(scaled.textures[0].clipped_texels, 0u);
    EXPECT_TRUE(iris::scene::approximations(scaled).empty());
}

// The fingerprint changes with a texel, the wrap mode and the uvs; an untextured scene's
// does not depend on the quad's (unused) uvs.
TEST(TextureImage, FingerprintSeesTheTexture) {
    temp_dir dir;
    iris::exr::write(dir.path / "a.exr", make_image(2, 2, [](int, int) { return iris::rgb_pixel{0.5f, 0.5f, 0.5f}; }));
    iris::exr::write(dir.path / "b.exr", make_image(2, 2, [](int x, int y) {
        return iris::rgb_pixel{x == 1 && y == 1 ? 0.6f : 0.5f, 0.5f, 0.5f};
    }));
    const auto fp = [&](const std::string& r) {
        return iris::scene::fingerprint(iris::scene::parse_scene(scene_with(r), "tex.json", dir.path));
    };
    const auto a = fp(R"({"texture": "a.exr"})");
    EXPECT_EQ(a, fp(R"({"texture": "a.exr"})"));
    EXPECT_NE(a, fp(R"({"texture": "b.exr"})"));
    EXPECT_NE(a, fp(R"({"texture": "a.exr", "wrap": "clamp"})"));
    auto s = iris::scene::parse_scene(scene_with(R"({"texture": "a.exr"})"), "tex.json", dir.path);
    s.shapes[0].mesh.uvs[0].x += 0.25f;
    EXPECT_NE(a, iris::scene::fingerprint(s));
    auto plain = iris::scene::parse_scene(scene_with("0.5"), "tex.json", dir.path);
    const auto p = iris::scene::fingerprint(plain);
    plain.shapes[0].mesh.uvs[0].x += 0.25f;
    EXPECT_EQ(p, iris::scene::fingerprint(plain));
}
