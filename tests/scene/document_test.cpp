// Scene files that must be rejected, each with the message and line it must give, and
// files that must be accepted with the values they spell out (docs/scene-format.md).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <variant>
#include <sstream>
#include <string>
#include <vector>

#include <iris/scene/document.hpp>
#include <iris/spectrum/color.hpp>
#include <iris/spectrum/named.hpp>

namespace {

using iris::scene::parse_scene_document;

// A valid scene; the cases below each break one thing in a copy of it.
constexpr const char* valid = R"({
  "camera": {"position": [0, 1, 4], "look_at": [0, 1, 0], "fov": 40, "resolution": [64, 48]},
  "materials": {
    "white": {"type": "diffuse", "reflectance": 0.8},
    "glass": {"type": "dielectric", "ior": "N-BK7"}
  },
  "shapes": [
    {"type": "quad", "size": [2, 2], "material": "white"},
    {"type": "cube", "size": 0.5, "material": "glass"},
    {"type": "quad", "size": [0.5, 0.5], "material": "white", "emitter": {"spd": "D65", "luminance": 2},
     "transform": [{"rotate": {"axis": [1, 0, 0], "degrees": 180}}, {"translate": [0, 2, 0]}]}
  ]
})";

std::string replace(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    if (at == std::string::npos) throw std::logic_error("test case: '" + from + "' not in the scene");
    return text.replace(at, from.size(), to);
}

struct bad_case {
    const char* what;
    std::string text;
    const char* message;   ///< substring of what()
    std::size_t line;      ///< expected line (0: not checked)
    const char* pointer;   ///< expected pointer (nullptr: not checked)
};

std::vector<bad_case> bad_cases() {
    const std::string v = valid;
    return {
        {"syntax error: missing value", replace(v, "\"fov\": 40", "\"fov\": "), "syntax error", 2, ""},
        {"syntax error: trailing comma", replace(v, "\"N-BK7\"}", "\"N-BK7\"},"), "syntax error", 6, ""},
        {"empty input", "", "syntax error", 1, ""},
        {"not an object", "[1, 2]", "expected a scene object", 1, ""},
        {"duplicate key", replace(v, "\"fov\": 40", "\"fov\": 40, \"fov\": 30"), "duplicate key 'fov'", 2, "/camera"},
        {"unknown top-level key", replace(v, "\"camera\"", "\"camra\""), "unknown key 'camra'; expected one of name", 2, ""},
        {"unknown camera key", replace(v, "\"fov\": 40", "\"fov_y\": 40"), "unknown key 'fov_y'", 2, "/camera"},
        {"unknown shape key", replace(v, "\"size\": 0.5,", "\"size\": 0.5, \"colour\": 1,"), "unknown key 'colour'", 9,
         "/shapes/1"},
        {"unknown shape type", replace(v, "\"type\": \"cube\"", "\"type\": \"torus\""),
         "unknown shape type 'torus'; expected one of box, cube, prism, hollow_cube, quad, mesh, sphere", 9, "/shapes/1/type"},
        {"unknown material type", replace(v, "\"type\": \"diffuse\"", "\"type\": \"lambert\""),
         "unknown material type 'lambert'", 4, "/materials/white/type"},
        {"coat over glass", replace(v, "\"type\": \"diffuse\", \"reflectance\": 0.8", "\"type\": \"coated\", \"base\": {\"type\": \"dielectric\", \"ior\": 1.5}"),
         "a coat's base must be a diffuse, conductor or mirror material", 4, "/materials/white/base"},
        {"coat index below 1", replace(v, "\"type\": \"diffuse\", \"reflectance\": 0.8", "\"type\": \"coated\", \"base\": {\"type\": \"diffuse\", \"reflectance\": 0.8}, \"eta\": 0.9"),
         "the coat's index of refraction", 4, "/materials/white/eta"},
        {"coat without a base", replace(v, "\"type\": \"diffuse\", \"reflectance\": 0.8", "\"type\": \"coated\""),
         "base", 4, "/materials/white"},
        {"coat with unknown key", replace(v, "\"type\": \"diffuse\", \"reflectance\": 0.8", "\"type\": \"coated\", \"base\": {\"type\": \"diffuse\"}, \"albedo\": 0.5"),
         "unknown key 'albedo'", 4, "/materials/white"},
        {"unknown material", replace(v, "\"material\": \"glass\"", "\"material\": \"gold\""),
         "unknown material 'gold'; expected one of white, glass", 9, "/shapes/1/material"},
        {"unknown glass", replace(v, "\"N-BK7\"", "\"BK-7\""), "unknown glass 'BK-7'; expected one of N-BK7, N-SF11", 5,
         "/materials/glass/ior"},
        {"IOR below 1", replace(v, "\"N-BK7\"", "0.9"), "index of refraction (IOR) in [1, 10], got 0.9", 5,
         "/materials/glass/ior"},
        {"Cauchy IOR below 1", replace(v, "\"N-BK7\"", "{\"cauchy\": [0.5, 0.001]}"), "Cauchy A", 5, nullptr},
        {"Sellmeier IOR below 1 in the domain",
         replace(v, "\"N-BK7\"", "{\"sellmeier\": {\"B\": [-0.5, 0, 0], \"C\": [0, 0, 0]}}"),
         "IOR must be in [1, 10] over the spectral domain [380, 780] nm, but n(380 nm) = 0.707", 5, "/materials/glass/ior"},
        {"unknown glass model", replace(v, "\"N-BK7\"", "{\"glass\": \"N-BK7\", \"model\": \"abbe\"}"),
         "unknown IOR model 'abbe'", 5, nullptr},
        {"roughness above 1", replace(v, "\"N-BK7\"}", "\"N-BK7\", \"roughness\": 2}"), "GGX roughness in [0, 1], got 2", 5,
         "/materials/glass/roughness"},
        {"negative size", replace(v, "\"size\": 0.5,", "\"size\": -0.5,"), "expected a size in (0, 1000000], got -0.5", 9,
         "/shapes/1/size"},
        {"zero size", replace(v, "\"size\": [2, 2]", "\"size\": [2, 0]"), "expected a size", 8, "/shapes/0/size/1"},
        {"string instead of a number (NaN)", replace(v, "\"fov\": 40", "\"fov\": \"NaN\""),
         "expected a number, got string \"NaN\"", 2, "/camera/fov"},
        {"number too large for a double", replace(v, "\"fov\": 40", "\"fov\": 1e999"), "number overflow", 2, ""},
        {"number out of range", replace(v, "\"luminance\": 2", "\"luminance\": 1e300"), "luminance Y in (0, 1e+12]", 10,
         nullptr},
        {"negative luminance", replace(v, "\"luminance\": 2", "\"luminance\": -2"), "luminance Y", 10,
         "/shapes/2/emitter/luminance"},
        {"luminance and power", replace(v, "\"luminance\": 2", "\"luminance\": 2, \"power\": 5"), "not both", 10, nullptr},
        {"reflectance above 1", replace(v, "\"reflectance\": 0.8", "\"reflectance\": 1.5"), "reflectance in [0, 1], got 1.5",
         4, "/materials/white/reflectance"},
        {"colour component out of range", replace(v, "\"reflectance\": 0.8", "\"reflectance\": {\"srgb\": [1, 0, -0.1]}"),
         "colour component in [0, 1], got -0.1", 4, "/materials/white/reflectance/srgb/2"},
        {"table not increasing",
         replace(v, "\"reflectance\": 0.8", "\"reflectance\": {\"wavelengths\": [400, 500, 450], \"values\": [0, 1, 0]}"),
         "wavelengths must increase strictly", 4, "/materials/white/reflectance/wavelengths/2"},
        {"table sizes differ",
         replace(v, "\"reflectance\": 0.8", "\"reflectance\": {\"wavelengths\": [400, 500], \"values\": [0.5]}"),
         "expected an array of 2 values", 4, nullptr},
        {"unknown spectrum", replace(v, "\"spd\": \"D65\"", "\"spd\": \"D50\""), "unknown spectrum 'D50'; expected one of D65, A, LED-B1", 10,
         "/shapes/2/emitter/spd"},
        {"bad blackbody", replace(v, "\"spd\": \"D65\"", "\"spd\": \"blackbody:-5\""), "blackbody temperature in [100, 1000000] K", 10,
         nullptr},
        {"blackbody not a number", replace(v, "\"spd\": \"D65\"", "\"spd\": \"blackbody:hot\""), "blackbody:KELVIN", 10, nullptr},
        {"unknown emitter", replace(v, "\"emitter\": {\"spd\": \"D65\", \"luminance\": 2}", "\"emitter\": \"sun\""),
         "unknown emitter 'sun'; the scene defines no \"emitters\"", 10, "/shapes/2/emitter"},
        {"no emitter", replace(v, ", \"emitter\": {\"spd\": \"D65\", \"luminance\": 2}", ""), "the scene has no emitter", 7, ""},
        {"empty scene", R"({"camera": {"position": [0, 0, 1], "look_at": [0, 0, 0]}, "shapes": []})", "the scene is empty", 1,
         "/shapes"},
        {"no shapes key", R"({"camera": {"position": [0, 0, 1], "look_at": [0, 0, 0]}})", "missing key 'shapes'", 1, ""},
        {"no camera", R"({"shapes": []})", "missing key 'camera'", 1, ""},
        {"fov 0", replace(v, "\"fov\": 40", "\"fov\": 0"), "vertical field of view in degrees in (0, 180), got 0", 2,
         "/camera/fov"},
        {"fov 180", replace(v, "\"fov\": 40", "\"fov\": 180"), "field of view in degrees in (0, 180), got 180", 2, nullptr},
        {"zero resolution", replace(v, "[64, 48]", "[0, 48]"), "a width in pixels in [1, 16384], got 0", 2,
         "/camera/resolution/0"},
        {"fractional resolution", replace(v, "[64, 48]", "[64, 48.5]"), "a height in pixels (an integer)", 2, nullptr},
        {"look_at equals position", replace(v, "\"look_at\": [0, 1, 0]", "\"look_at\": [0, 1, 4]"),
         "the camera looks at its own position", 2, "/camera/look_at"},
        {"up parallel to the view", replace(v, "\"fov\": 40", "\"up\": [0, 0, -1], \"fov\": 40"), "up vector", 2,
         "/camera/up"},
        {"wall too thick", replace(v, "{\"type\": \"cube\", \"size\": 0.5,", "{\"type\": \"hollow_cube\", \"size\": 0.5, \"wall\": 0.25,"),
         "wall thickness below half the size", 9, "/shapes/1/wall"},
        {"zero scale", replace(v, "{\"translate\": [0, 2, 0]}", "{\"scale\": [1, 0, 1]}"), "scale factor must not be 0", 11,
         "/shapes/2/transform/1/scale/1"},
        {"two steps in one", replace(v, "{\"translate\": [0, 2, 0]}", "{\"translate\": [0, 2, 0], \"scale\": 2}"),
         "exactly one of", 11, "/shapes/2/transform/1"},
        {"zero rotation axis", replace(v, "\"axis\": [1, 0, 0]", "\"axis\": [0, 0, 0]"), "rotation axis must not be zero", 11,
         nullptr},
        {"missing mesh file", replace(v, "{\"type\": \"cube\", \"size\": 0.5,", "{\"type\": \"mesh\", \"file\": \"no-such-mesh.obj\","),
         "mesh file 'no-such-mesh.obj' not found", 9, "/shapes/1/file"},
        {"unsupported mesh format", replace(v, "{\"type\": \"cube\", \"size\": 0.5,", "{\"type\": \"mesh\", \"file\": \"bunny.stl\","),
         "unsupported mesh format '.stl'", 9, nullptr},
        {"reversed spectral domain", replace(v, "\"camera\"", "\"spectral_domain\": [700, 400], \"camera\""), "spectral domain", 2,
         "/spectral_domain"},
        {"domain outside the CMFs", replace(v, "\"camera\"", "\"spectral_domain\": [300, 700], \"camera\""),
         "a wavelength in nm in [360, 830], got 300", 2, nullptr},
        {"boolean expected", replace(v, "\"size\": 0.5,", "\"size\": 0.5, \"flip\": 1,"), "expected true or false", 9,
         "/shapes/1/flip"},
        {"materials not an object", R"({"camera": {"position": [0, 0, 1], "look_at": [0, 0, 0]}, "materials": [1], "shapes": []})",
         "expected an object of named materials, got array [1]", 1, "/materials"},
        // lights (docs/scene-format.md#lights)
        {"lights not an array", replace(v, "  \"shapes\": [", "  \"lights\": {}, \"shapes\": ["), "expected an array", 7, "/lights"},
        {"unknown light type", replace(v, "  \"shapes\": [", "  \"lights\": [{\"type\": \"area\"}], \"shapes\": ["),
         "unknown light type 'area'; expected one of point, spot, distant", 7, "/lights/0/type"},
        {"point light without a position",
         replace(v, "  \"shapes\": [", "  \"lights\": [{\"type\": \"point\", \"spd\": \"D65\"}], \"shapes\": ["),
         "missing key 'position'", 7, "/lights/0"},
        {"unknown point light key",
         replace(v, "  \"shapes\": [",
                 "  \"lights\": [{\"type\": \"point\", \"position\": [0, 1, 0], \"spd\": \"D65\", \"radius\": 1}], \"shapes\": ["),
         "unknown key 'radius'; expected one of type, position, spd, intensity, power", 7, "/lights/0"},
        {"intensity and power",
         replace(v, "  \"shapes\": [",
                 "  \"lights\": [{\"type\": \"point\", \"position\": [0, 1, 0], \"spd\": \"D65\", \"intensity\": 1, \"power\": 2}], \"shapes\": ["),
         "give either 'intensity' or 'power', not both", 7, "/lights/0/power"},
        {"spot falloff beyond its cone",
         replace(v, "  \"shapes\": [",
                 "  \"lights\": [{\"type\": \"spot\", \"position\": [0, 1, 0], \"look_at\": [0, 0, 0], \"cone_angle\": 30, "
                 "\"falloff_angle\": 45, \"spd\": \"D65\"}], \"shapes\": ["),
         "(at most cone_angle) in [0, 30], got 45", 7, "/lights/0/falloff_angle"},
        {"spot aimed at itself",
         replace(v, "  \"shapes\": [",
                 "  \"lights\": [{\"type\": \"spot\", \"position\": [0, 1, 0], \"look_at\": [0, 1, 0], \"cone_angle\": 30, "
                 "\"spd\": \"D65\"}], \"shapes\": ["),
         "the spot's look_at must differ from its position", 7, "/lights/0/look_at"},
        {"spot too narrow",
         replace(v, "  \"shapes\": [",
                 "  \"lights\": [{\"type\": \"spot\", \"position\": [0, 1, 0], \"look_at\": [0, 0, 0], \"cone_angle\": 1e-30, "
                 "\"spd\": \"D65\", \"power\": 1}], \"shapes\": ["),
         "the cone is too narrow", 7, "/lights/0/cone_angle"},
        {"distant light without a direction",
         replace(v, "  \"shapes\": [", "  \"lights\": [{\"type\": \"distant\", \"direction\": [0, 0, 0], \"spd\": \"D65\"}], \"shapes\": ["),
         "the direction must not be zero", 7, "/lights/0/direction"},
        {"light spectrum outside the domain",
         replace(v, "  \"shapes\": [",
                 "  \"lights\": [{\"type\": \"distant\", \"direction\": [0, -1, 0], "
                 "\"spd\": {\"wavelengths\": [300, 350], \"values\": [1, 1]}}], \"shapes\": ["),
         "is zero over the spectral domain", 7, "/lights/0/spd"},
        // environment images (docs/scene-format.md#environment)
        {"environment image not an EXR",
         replace(v, "  \"shapes\": [", "  \"environment\": {\"image\": \"sky.hdr\"}, \"shapes\": ["),
         "expected an OpenEXR image file (.exr, linear sRGB), got 'sky.hdr'", 7, "/environment/image"},
        {"environment image missing",
         replace(v, "  \"shapes\": [", "  \"environment\": {\"image\": \"no-such-sky.exr\"}, \"shapes\": ["),
         "environment image 'no-such-sky.exr' not found", 7, "/environment/image"},
        {"environment image with an spd",
         replace(v, "  \"shapes\": [", "  \"environment\": {\"image\": \"sky.exr\", \"spd\": \"D65\"}, \"shapes\": ["),
         "unknown key 'spd'", 7, "/environment"},
        {"environment without spd or image",
         replace(v, "  \"shapes\": [", "  \"environment\": {\"luminance\": 2}, \"shapes\": ["), "missing key 'spd'", 7,
         "/environment"},
    };
}

TEST(SceneDocument, TheValidSceneParses) {
    const auto d = parse_scene_document(valid, "valid.json", {});
    EXPECT_EQ(d.desc.name, "valid");
    EXPECT_EQ(d.shapes.size(), 3u);
    EXPECT_EQ(d.desc.materials.size(), 2u);
    EXPECT_EQ(d.desc.emitters.size(), 1u);
    EXPECT_EQ(d.shapes[1].line, 9u);
}

TEST(SceneDocument, MalformedScenesGiveFileLinePointerAndWhatWasExpected) {
    for (const auto& c : bad_cases()) {
        SCOPED_TRACE(c.what);
        try {
            parse_scene_document(c.text, "bad.json", {});
            ADD_FAILURE() << "accepted: " << c.text;
        } catch (const iris::scene::error& e) {
            const std::string w = e.what();
            EXPECT_NE(w.find(c.message), std::string::npos) << "what(): " << w;
            EXPECT_EQ(w.rfind("bad.json:", 0), 0u) << w;
            if (c.line > 0) {
                EXPECT_EQ(e.line(), c.line) << w;
            }
            if (c.pointer) {
                EXPECT_EQ(e.pointer(), c.pointer) << w;
            }
        } catch (const std::exception& e) {
            ADD_FAILURE() << "threw something other than iris::scene::error: " << e.what();
        }
    }
}

TEST(SceneDocument, MessageFormatIsFileLinePointerMessage) {
    try {
        parse_scene_document(replace(valid, "\"N-BK7\"", "\"BK-7\""), "falling.json", {});
        FAIL();
    } catch (const iris::scene::error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("falling.json:5: materials/glass/ior: unknown glass 'BK-7'; expected one of N-BK7, ", 0), 0u)
            << e.what();
        EXPECT_EQ(e.file(), "falling.json");
        EXPECT_EQ(e.message().rfind("unknown glass", 0), 0u);
    }
}

TEST(SceneDocument, CommentsAreAllowedAndLinesStillCount) {
    const std::string text = "// a comment\n/* block\n comment */\n" + replace(valid, "\"N-BK7\"", "\"BK-7\"");
    try {
        parse_scene_document(text, "c.json", {});
        FAIL();
    } catch (const iris::scene::error& e) {
        EXPECT_EQ(e.line(), 8u) << e.what();
    }
}

TEST(SceneDocument, DefaultsAreDocumented) {
    const auto d = parse_scene_document(
        R"({"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
            "materials": {"m": {"type": "mirror"}},
            "environment": {"spd": "A"},
            "shapes": [{"type": "box", "size": [1, 2, 3], "material": "m"}]})",
        "d.json", {});
    EXPECT_FLOAT_EQ(d.desc.lambda_min, 380.0f);
    EXPECT_FLOAT_EQ(d.desc.lambda_max, 780.0f);
    EXPECT_EQ(d.desc.camera.width, 256);
    EXPECT_EQ(d.desc.camera.height, 256);
    EXPECT_FLOAT_EQ(d.desc.camera.fov_y_degrees, 40.0f);
    EXPECT_EQ(d.desc.camera.up, glm::vec3(0, 1, 0));
    ASSERT_TRUE(d.desc.environment);
    EXPECT_NEAR(iris::luminance(d.desc.environment->radiance), 1.0, 1e-9);  // default luminance 1
    const auto* m = std::get_if<iris::material::conductor>(&d.desc.materials[0]);
    ASSERT_NE(m, nullptr);
    EXPECT_EQ(m->reflectance(550.0), 1.0);
    EXPECT_FALSE(d.shapes[0].flip);
}

TEST(SceneDocument, LuminanceScalingGivesTheRequestedY) {
    for (const char* spd : {"\"D65\"", "\"A\"", "\"LED-V2\"", "\"blackbody:3000\"", "{\"blackbody\": 6500}",
                            "{\"wavelengths\": [400, 500, 600, 700], \"values\": [1, 2, 3, 4]}"}) {
        const auto d = parse_scene_document(
            std::string(R"({"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
                "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
                "shapes": [{"type": "quad", "size": [1, 1], "material": "m", "emitter": {"luminance": 7.5, "spd": )") +
                spd + "}}]}",
            "l.json", {});
        ASSERT_EQ(d.desc.emitters.size(), 1u);
        EXPECT_NEAR(iris::luminance(d.desc.emitters[0].radiance), 7.5, 1e-9) << spd;
        EXPECT_FALSE(d.emitters[0].power);
    }
}

TEST(SceneDocument, SpdNamesFeedTheFeatureSummary) {
    const auto d = parse_scene_document(
        R"({"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
            "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
            "emitters": {"a": {"spd": "LED-B1"}, "b": {"spd": "blackbody:2700"}, "unused": {"spd": "A"}},
            "shapes": [{"type": "quad", "size": [1, 1], "material": "m", "emitter": "b"},
                       {"type": "quad", "size": [1, 1], "material": "m", "emitter": "a"},
                       {"type": "quad", "size": [1, 1], "material": "m", "emitter": "b"},
                       {"type": "quad", "size": [1, 1], "material": "m",
                        "emitter": {"spd": {"wavelengths": [400, 700], "values": [1, 1]}}}]})",
        "s.json", {});
    // named emitters are shared by the shapes that use them, kept in order of first use; unused ones dropped
    ASSERT_EQ(d.desc.emitters.size(), 3u);
    EXPECT_EQ(d.desc.emitters[0].spd_name, "blackbody:2700");
    EXPECT_EQ(d.desc.emitters[1].spd_name, "LED-B1");
    EXPECT_EQ(d.desc.emitters[2].spd_name, "tabulated");
    EXPECT_EQ(d.shapes[0].emitter, 0u);
    EXPECT_EQ(d.shapes[2].emitter, 0u);
    EXPECT_EQ(d.shapes[3].emitter, 2u);
}

TEST(SceneDocument, IorForms) {
    const auto parse = [](const std::string& ior) {
        const auto d = parse_scene_document(
            R"({"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
                "materials": {"g": {"type": "dielectric", "roughness": 0.1, "ior": )" + ior + R"(}},
                "environment": {"spd": "D65"},
                "shapes": [{"type": "cube", "size": 1, "material": "g"}]})",
            "i.json", {});
        return std::get<iris::material::dielectric>(d.desc.materials[0]);
    };
    const auto sf11 = *iris::find_glass("N-SF11");
    EXPECT_DOUBLE_EQ(iris::refractive_index(parse("\"N-SF11\"").ior, 500.0), sf11.sellmeier.n(500.0));
    EXPECT_DOUBLE_EQ(iris::refractive_index(parse(R"({"glass": "N-SF11", "model": "cauchy"})").ior, 500.0),
                     sf11.cauchy.n(500.0));
    EXPECT_DOUBLE_EQ(iris::refractive_index(parse(R"({"cauchy": [1.5, 0.01]})").ior, 500.0), 1.5 + 0.01 / 0.25);
    EXPECT_DOUBLE_EQ(iris::refractive_index(parse("1.33").ior, 500.0), 1.33);
    EXPECT_FALSE(iris::is_dispersive(parse("1.33").ior));
    EXPECT_TRUE(iris::is_dispersive(parse("\"N-BK7\"").ior));
    const auto s = parse(R"({"sellmeier": {"B": [1.03961212, 0.231792344, 1.01046945], "C": [0.00600069867, 0.0200179144, 103.560653]}})");
    EXPECT_NEAR(iris::refractive_index(s.ior, 587.5618), 1.5168, 1e-4);  // N-BK7's n_d
    EXPECT_FLOAT_EQ(s.roughness, 0.1f);
}

TEST(SceneDocument, TransformStepsApplyInTheOrderListed) {
    const auto d = parse_scene_document(
        R"({"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
            "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
            "environment": {"spd": "D65"},
            "shapes": [{"type": "cube", "size": 1, "material": "m",
                        "transform": [{"translate": [1, 0, 0]}, {"rotate": {"axis": [0, 0, 1], "degrees": 90}}, {"scale": 2}]}]})",
        "t.json", {});
    const glm::vec4 p = d.shapes[0].transform * glm::vec4(0, 0, 0, 1);  // → (1,0,0) → (0,1,0) → (0,2,0)
    EXPECT_NEAR(p.x, 0.0f, 1e-6f);
    EXPECT_NEAR(p.y, 2.0f, 1e-6f);
    EXPECT_NEAR(p.z, 0.0f, 1e-6f);
}

}  // namespace

namespace {

// Every complete scene in docs/scene-format.md (a ```json block that starts with '{' and
// has a "camera") must parse: the documentation cannot drift from the parser.
TEST(SceneDocument, EveryCompleteExampleInTheDocsParses) {
    std::ifstream in(IRIS_SCENE_FORMAT_DOC);
    ASSERT_TRUE(in) << IRIS_SCENE_FORMAT_DOC;
    std::ostringstream buffer;
    buffer << in.rdbuf();
    const std::string doc = buffer.str();
    std::size_t examples = 0;
    for (std::size_t at = doc.find("```json\n"); at != std::string::npos; at = doc.find("```json\n", at + 1)) {
        const std::size_t begin = at + 8, end = doc.find("```", begin);
        const std::string block = doc.substr(begin, end - begin);
        if (block.empty() || block.front() != '{' || block.find("\"camera\"") == std::string::npos) continue;
        ++examples;
        EXPECT_NO_THROW(parse_scene_document(block, "scene-format.md", {})) << block;
    }
    EXPECT_GE(examples, 1u);
}

}  // namespace

namespace {
/// \brief ∫ s(λ) dλ over [380, 780] nm (midpoint sum; the tables are piecewise linear).
double integral(const iris::tabulated_spectrum& s) {
    double sum = 0.0;
    for (double l = 380.05; l < 780.0; l += 0.1) sum += s(static_cast<float>(l)) * 0.1;
    return sum;
}
}  // namespace

// A light's "intensity"/"irradiance" is the luminance Y of I or E; its "power" is
// ∫s dω · ∫I dλ over the spectral domain (docs/scene-format.md#lights). Each light adds an
// emitter after the shapes' emitters.
TEST(SceneDocument, LightsScaleToTheirLuminanceOrPower) {
    const double pi = 3.14159265358979323846;
    const auto d = parse_scene_document(
        replace(valid, "  \"shapes\": [",
                R"(  "lights": [{"type": "point", "position": [0, 1, 0], "spd": "A", "intensity": 3},
                              {"type": "point", "position": [0, 1, 0], "spd": "D65", "power": 8},
                              {"type": "spot", "position": [0, 1, 0], "look_at": [0, 0, 0], "cone_angle": 60, "falloff_angle": 30,
                               "spd": "D65", "power": 5},
                              {"type": "distant", "direction": [0, -2, 0], "spd": "blackbody:3000", "irradiance": 0.5}],
  "shapes": [)"),
        "lights.json", {});
    ASSERT_EQ(d.desc.lights.size(), 4u);
    ASSERT_EQ(d.desc.emitters.size(), 5u);  // the area light first
    for (std::size_t i = 0; i < 4; ++i) {
        const std::uint32_t e = std::visit([](const auto& l) { return l.emitter; }, d.desc.lights[i]);
        EXPECT_EQ(e, i + 1);
    }
    EXPECT_NEAR(iris::luminance(d.desc.emitters[1].radiance), 3.0, 1e-6);
    EXPECT_NEAR(4.0 * pi * integral(d.desc.emitters[2].radiance), 8.0, 8e-3);
    const double c_start = std::cos(pi / 6.0), c_width = std::cos(pi / 3.0);
    const double spot_solid_angle = 2.0 * pi * (1.0 - c_start) + pi * (c_start - c_width);
    EXPECT_NEAR(spot_solid_angle * integral(d.desc.emitters[3].radiance), 5.0, 5e-3);
    EXPECT_NEAR(iris::luminance(d.desc.emitters[4].radiance), 0.5, 1e-6);
    const auto& dist = std::get<iris::light::distant>(d.desc.lights[3]);
    EXPECT_FLOAT_EQ(dist.direction.y, -1.0f);  // normalised
    const auto& spot = std::get<iris::light::spot>(d.desc.lights[2]);
    EXPECT_NEAR(spot.cos_total_width, c_width, 1e-6);
    EXPECT_NEAR(spot.cos_falloff_start, c_start, 1e-6);
}
