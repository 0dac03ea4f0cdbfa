// Reflectance textures read when the scene is built (docs/scene-format.md#diffuse): the
// errors a bad texture gives (file, line, pointer, what was wrong), sRGB decoding of 8-bit
// images, clamping reported (never silent), and the fingerprint seeing the texels; and the
// normals and uvs a mesh file brings.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include <unistd.h>

#include <glm/geometric.hpp>

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

// A mesh file's normals and uvs reach the scene (docs/scene-format.md, shapes): the uvs as
// written, the normals carried through the shape's transform by its inverse transpose
// (perpendicular to the transformed surface, whatever the scale); a broken normal is an
// error naming the scene file, its line and the mesh file.
TEST(MeshAttributes, ReachTheSceneThroughTheTransform) {
    const temp_dir dir;
    {
        std::ofstream out(dir.path / "tri.ply");
        out << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "property float nx\nproperty float ny\nproperty float nz\nproperty float u\nproperty float v\n"
               "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
               "0 0 0 1 0 1 0 0\n1 0 0 0 0 1 1 0\n0 1 0 0 0 1 0.25 1\n3 0 1 2\n";
    }
    {
        std::ofstream out(dir.path / "bad.ply");
        out << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "property float nx\nproperty float ny\nproperty float nz\n"
               "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
               "0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n3 0 1 2\n";
    }
    const auto scene = [](const std::string& file) {
        return R"({"camera": {"position": [0, 1, 3], "look_at": [0, 0, 0]},
  "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
  "environment": {"spd": "D65"},
  "shapes": [{"type": "mesh", "file": ")" +
               file + R"(", "material": "m",
              "transform": [{"scale": [3, 1, 1]}, {"rotate": {"axis": [1, 0, 0], "degrees": 90}}]}]})";
    };
    const auto s = iris::scene::parse_scene(scene("tri.ply"), "mesh.json", dir.path);
    const auto& m = s.shapes.at(0).mesh;
    ASSERT_EQ(m.normals.size(), 3u);
    ASSERT_EQ(m.uvs.size(), 3u);
    EXPECT_EQ(m.uvs[2], glm::vec2(0.25f, 1.0f));
    // scale x by 3, then rotate +90° about x: (1, 0, 1) → (1/3, 0, 1) → (1/3, −1, 0), up to length
    const glm::vec3 n0 = glm::normalize(m.normals[0]);
    const glm::vec3 want = glm::normalize(glm::vec3(1.0f / 3.0f, -1.0f, 0.0f));
    EXPECT_NEAR(glm::length(n0 - want), 0.0f, 1e-5f) << n0.x << " " << n0.y << " " << n0.z;
    const glm::vec3 e1 = m.positions[1] - m.positions[0], e2 = m.positions[2] - m.positions[0];
    EXPECT_NEAR(glm::dot(glm::normalize(m.normals[1]), glm::normalize(e1)), 0.0f, 1e-5f);  // still perpendicular
    EXPECT_NEAR(glm::dot(glm::normalize(m.normals[1]), glm::normalize(e2)), 0.0f, 1e-5f);
    try {
        (void)iris::scene::parse_scene(scene("bad.ply"), "mesh.json", dir.path);
        ADD_FAILURE() << "a zero normal must be an error";
    } catch (const iris::scene::error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("mesh.json:"), std::string::npos) << what;
        EXPECT_NE(what.find("bad.ply"), std::string::npos) << what;
        EXPECT_NE(what.find("vertex 1 has a zero normal"), std::string::npos) << what;
    }
}

// `uv_scale` and `uv_offset` map the surface's uv to the image's (pbrt-v4's uscale, vscale,
// udelta, vdelta): a lookup at uv is the unmapped lookup at uv·scale + offset; bad values
// are errors at their pointer.
TEST(TextureImage, UvScaleAndOffsetMapTheSurfacesUv) {
    temp_dir dir;
    iris::exr::write(dir.path / "ramp.exr", make_image(4, 3, [](int x, int y) {
        return iris::rgb_pixel{0.1f + 0.2f * static_cast<float>(x), 0.3f, 0.2f * static_cast<float>(y)};
    }));
    const auto plain = iris::scene::parse_scene(scene_with(R"({"texture": "ramp.exr"})"), "tex.json", dir.path);
    const auto mapped = iris::scene::parse_scene(scene_with(R"({"texture": "ramp.exr", "uv_scale": [2, -0.5], "uv_offset": [0.25, 0.1]})"),
                                                 "tex.json", dir.path);
    const auto& a = plain.textures[0];
    const auto& b = mapped.textures[0];
    EXPECT_EQ(b.uv_scale, glm::vec2(2.0f, -0.5f));
    EXPECT_EQ(b.uv_offset, glm::vec2(0.25f, 0.1f));
    for (const glm::vec2 uv : {glm::vec2(0.1f, 0.2f), glm::vec2(0.6f, 0.9f), glm::vec2(-0.3f, 1.7f)}) {
        const glm::vec3 want = iris::lookup(a, uv * glm::vec2(2.0f, -0.5f) + glm::vec2(0.25f, 0.1f));
        EXPECT_LT(glm::length(iris::lookup(b, uv) - want), 1e-6f) << uv.x << ' ' << uv.y;
    }
    EXPECT_NE(iris::scene::fingerprint(plain), iris::scene::fingerprint(mapped));
    EXPECT_NE(error_of(R"({"texture": "ramp.exr", "uv_scale": [0, 1]})", dir.path).find("tex.json:3: materials/m/reflectance/uv_scale/0: a uv scale factor must not be 0"),
              std::string::npos)
        << error_of(R"({"texture": "ramp.exr", "uv_scale": [0, 1]})", dir.path);
    EXPECT_NE(error_of(R"({"texture": "ramp.exr", "uv_offset": [1]})", dir.path).find("uv_offset"), std::string::npos);
}
