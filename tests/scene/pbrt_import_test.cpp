// The pbrt-v4 importer (docs/pbrt-import.md): every built-in scene survives the round trip
// through `iris-scene export --pbrt` and back; pbrt-v4's conventions (its left-handed camera,
// its light normalisation, its roughness remapping, its orientation rules) land on iris's;
// bad input is an error at FILE:LINE:COLUMN, approximations are notes (errors with strict).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <unistd.h>

#include <glm/geometric.hpp>
#include <zlib.h>

#include <iris/exr/exr.hpp>
#include <iris/render/materials/coated.hpp>
#include <iris/scene/scene.hpp>
#include <iris/spectrum/color.hpp>
#include <iris/spectrum/named.hpp>
#include <iris/spectrum/rgb_sigmoid.hpp>
#include <iris/spectrum/rgb_upsampling.hpp>

namespace {

namespace fs = std::filesystem;

iris::scene_desc import(const std::string& text, const iris::scene::pbrt_import_options& o = {}) {
    return iris::scene::build_scene(iris::scene::parse_pbrt_document(text, "test.pbrt", fs::temp_directory_path(), o));
}

/// The message of the error `text` raises ("" if none).
std::string error_of(const std::string& text, const iris::scene::pbrt_import_options& o = {}) {
    try {
        (void)iris::scene::parse_pbrt_document(text, "test.pbrt", fs::temp_directory_path() / "iris-no-such-dir", o);
    } catch (const iris::scene::error& e) {
        return e.what();
    }
    return "";
}

const std::string camera = "LookAt 0 1 5  0 1 0  0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
                           "Film \"rgb\" \"integer xresolution\" 64 \"integer yresolution\" 48\n";
const std::string lamp = "AttributeBegin\n AreaLightSource \"diffuse\" \"blackbody L\" 5000 \"float scale\" 3\n"
                         " Shape \"trianglemesh\" \"point3 P\" [ -1 3 -1  1 3 -1  1 3 1  -1 3 1 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n"
                         "AttributeEnd\n";
std::string scene(const std::string& world) { return camera + "WorldBegin\n" + lamp + world; }

double luminance_of(const iris::tabulated_spectrum& s) { return iris::luminance(s); }

}  // namespace

TEST(PbrtImport, EveryBuiltinSceneSurvivesTheRoundTripThroughItsExport) {
    for (const auto& b : iris::scene::builtin_scenes()) {
        SCOPED_TRACE(std::string(b.name));
        const auto s = iris::scene::builtin_scene(b.name);
        const auto r = import(iris::scene::pbrt_scene_text(s));
        EXPECT_EQ(r.camera.width, s.camera.width);
        EXPECT_EQ(r.camera.height, s.camera.height);
        EXPECT_NEAR(r.camera.fov_y_degrees, s.camera.fov_y_degrees, 1e-4);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(r.camera.position[i], s.camera.position[i], 1e-5);
        const glm::vec3 d0 = glm::normalize(s.camera.look_at - s.camera.position), d1 = glm::normalize(r.camera.look_at - r.camera.position);
        EXPECT_GT(glm::dot(d0, d1), 1.0f - 1e-6f);
        EXPECT_GT(glm::dot(glm::normalize(glm::cross(d0, s.camera.up)), glm::normalize(glm::cross(d1, r.camera.up))), 1.0f - 1e-6f);
        ASSERT_EQ(r.shapes.size(), s.shapes.size());
        for (std::size_t i = 0; i < s.shapes.size(); ++i) {
            const auto &a = s.shapes[i].mesh, &c = r.shapes[i].mesh;
            ASSERT_EQ(a.positions.size(), c.positions.size());
            EXPECT_EQ(a.positions, c.positions);  // exact: 9 significant digits, an identity transform
            EXPECT_EQ(a.triangles, c.triangles);  // the same winding, so the same outside and emitting side
            EXPECT_EQ(s.shapes[i].emitter.has_value(), r.shapes[i].emitter.has_value());
            // the same material, evaluated where iris renders
            const auto &ma = s.materials[s.shapes[i].material], &mb = r.materials[r.shapes[i].material];
            ASSERT_EQ(ma.index(), mb.index());
            for (double l = s.lambda_min; l <= s.lambda_max; l += 7.3) {
                if (const auto* d = std::get_if<iris::material::diffuse>(&ma)) {
                    EXPECT_NEAR(std::get<iris::material::diffuse>(mb).reflectance(l), d->reflectance(l), 1e-7);
                }
                if (const auto* g = std::get_if<iris::material::dielectric>(&ma)) {
                    // η is written at every nanometre: exact (to 9 digits) there, and linear between
                    // (off by up to h²/8·|n''| ≈ 1e-6 for N-SF11 at 380 nm, h = 1 nm)
                    const auto& h = std::get<iris::material::dielectric>(mb);
                    const double k = std::round(l);
                    EXPECT_NEAR(iris::refractive_index(h.ior, k), iris::refractive_index(g->ior, k), 1e-8);
                    EXPECT_EQ(iris::is_dispersive(h.ior), iris::is_dispersive(g->ior));
                    EXPECT_EQ(h.roughness, g->roughness);
                }
            }
            if (const auto e = s.shapes[i].emitter) {
                const auto &la = s.emitters[*e].radiance, &lb = r.emitters[*r.shapes[i].emitter].radiance;
                for (double l = s.lambda_min; l <= s.lambda_max; l += 3.7) EXPECT_NEAR(lb(l), la(l), 1e-6 * la(l) + 1e-12) << l;
            }
        }
        EXPECT_EQ(r.lights.size(), s.lights.size());
        EXPECT_EQ(r.environment.has_value(), s.environment.has_value());
        EXPECT_EQ(r.default_spp, 64);
        EXPECT_EQ(r.default_max_depth, 32);
    }
}

TEST(PbrtImport, APlainLookAtIsMirroredIntoIrisWorldSoTheImageIsTheSame) {
    // pbrt-v4's camera x is up × dir: a point at world x = +1 seen from the origin along +z is on
    // the right of pbrt-v4's image. iris's right is dir × up: the importer mirrors the world.
    const std::string text = "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\"\nWorldBegin\n"
                             "LightSource \"point\" \"point3 from\" [ 1 0 5 ]\n"
                             "Shape \"trianglemesh\" \"point3 P\" [ 1 0 5  2 0 5  1 1 5 ]\n";
    const auto s = import(text);
    const glm::vec3 dir = glm::normalize(s.camera.look_at - s.camera.position), right = glm::cross(dir, s.camera.up);
    const auto& p = std::get<iris::light::point>(s.lights.at(0)).position;
    EXPECT_GT(glm::dot(p - s.camera.position, right), 0.5f);  // on the right, as in pbrt-v4's image
    EXPECT_GT(glm::dot(s.shapes[0].mesh.positions[0] - s.camera.position, right), 0.5f);
    // pbrt-v4's normal of (1,0,5) (2,0,5) (1,1,5) is +z in its world (counter-clockwise from +z); the
    // mirror keeps it +z: iris's winding normal must agree
    const auto& m = s.shapes[0].mesh;
    const auto& t = m.triangles[0];
    const glm::vec3 n = glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
    EXPECT_GT(n.z, 0.0f);
    // ReverseOrientation turns it
    const auto r = import("LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\"\nWorldBegin\n"
                          "LightSource \"point\" \"point3 from\" [ 1 0 5 ]\nReverseOrientation\n"
                          "Shape \"trianglemesh\" \"point3 P\" [ 1 0 5  2 0 5  1 1 5 ]\n");
    const auto& m2 = r.shapes[0].mesh;
    const auto& t2 = m2.triangles[0];
    EXPECT_LT(glm::cross(m2.positions[t2[1]] - m2.positions[t2[0]], m2.positions[t2[2]] - m2.positions[t2[0]]).z, 0.0f);
}

TEST(PbrtImport, LightsTakePbrtsNormalisationAndConventions) {
    const auto s = import(scene("LightSource \"point\" \"blackbody I\" 3000 \"float scale\" 5 \"point3 from\" [ 1 2 3 ]\n"
                                "LightSource \"spot\" \"float coneangle\" 40 \"float conedeltaangle\" 10 \"point3 from\" [ 0 4 0 ] \"point3 to\" [ 0 0 0 ]\n"
                                "LightSource \"distant\" \"point3 from\" [ 0 1 0 ] \"point3 to\" [ 0 0 0 ] \"rgb L\" [ 1 1 1 ] \"float scale\" 2\n"
                                "Shape \"sphere\" \"float radius\" 0.5\n"));
    // an area light: iris's luminance is pbrt-v4's scale (its spectrum's own luminance divided out)
    EXPECT_NEAR(luminance_of(s.emitters[0].radiance), 3.0, 1e-9);
    ASSERT_EQ(s.lights.size(), 3u);
    const auto& p = std::get<iris::light::point>(s.lights[0]);
    EXPECT_NEAR(luminance_of(s.emitters[p.emitter].radiance), 5.0, 1e-9);
    const auto& sp = std::get<iris::light::spot>(s.lights[1]);
    EXPECT_NEAR(sp.cos_total_width, std::cos(40.0 * std::numbers::pi / 180.0), 1e-6);
    EXPECT_NEAR(sp.cos_falloff_start, std::cos(30.0 * std::numbers::pi / 180.0), 1e-6);
    EXPECT_NEAR(sp.direction.y, -1.0f, 1e-6);
    EXPECT_NEAR(luminance_of(s.emitters[sp.emitter].radiance), 1.0, 1e-9);  // D65, pbrt-v4's default
    // an "rgb" light is scale × the RGB illuminant spectrum: white is D65 at luminance 1
    const auto& d = std::get<iris::light::distant>(s.lights[2]);
    EXPECT_NEAR(d.direction.y, -1.0f, 1e-6);  // it travels from → to
    EXPECT_NEAR(luminance_of(s.emitters[d.emitter].radiance), 2.0, 2.0 * 0.01);  // the sigmoid table's round trip
    EXPECT_NEAR(s.emitters[d.emitter].radiance(560.0) / iris::find_illuminant("D65")->spectrum()(560.0),
                s.emitters[d.emitter].radiance(460.0) / iris::find_illuminant("D65")->spectrum()(460.0), 0.02);
}

TEST(PbrtImport, MaterialsMapToIrisWithPbrtsRoughnessRemapping) {
    const auto s = import(scene("Material \"dielectric\" \"spectrum eta\" \"glass-BK7\" \"float roughness\" 0.04\n"
                                "Shape \"sphere\"\n"
                                "Material \"conductor\" \"spectrum eta\" \"metal-Au-eta\" \"spectrum k\" \"metal-Au-k\" "
                                "\"float roughness\" 0.09 \"bool remaproughness\" false\nShape \"sphere\"\n"
                                "Material \"diffuse\" \"rgb reflectance\" [ 0.8 0.2 0.1 ]\nShape \"disk\" \"float innerradius\" 0.5\n"
                                "Material \"dielectric\" \"float eta\" 1.33\nShape \"sphere\"\n"));
    const auto& g = std::get<iris::material::dielectric>(s.materials[s.shapes[1].material]);
    EXPECT_NEAR(g.roughness, 0.2f, 1e-7);  // pbrt-v4's remapping: α = √roughness
    EXPECT_NEAR(iris::refractive_index(g.ior, 587.5618), 1.5168, 1e-4);  // N-BK7's n_d
    EXPECT_TRUE(iris::is_dispersive(g.ior));
    const auto& c = std::get<iris::material::conductor>(s.materials[s.shapes[2].material]);
    EXPECT_NEAR(c.roughness, 0.09f, 1e-7);
    ASSERT_TRUE(c.ior.has_value());
    EXPECT_NEAR(c.ior->eta(600.0), iris::find_metal("Au")->eta_spectrum()(600.0), 1e-12);
    const auto& d = std::get<iris::material::diffuse>(s.materials[s.shapes[3].material]);
    EXPECT_GT(d.reflectance(650.0), 0.6);  // Jakob-Hanika's red
    EXPECT_LT(d.reflectance(450.0), 0.2);
    const auto& w = std::get<iris::material::dielectric>(s.materials[s.shapes[4].material]);
    EXPECT_FALSE(iris::is_dispersive(w.ior));
    // the tessellations: glass spheres are closed outward solids; a unit sphere's area within
    // 0.1 % of 4π, a unit annulus's of 3π/4
    EXPECT_TRUE(iris::scene::check_dielectric_solids(s).empty());
    double a = 0.0;
    for (const auto& t : s.shapes[1].mesh.triangles) {
        const auto& m = s.shapes[1].mesh;
        a += 0.5 * glm::length(glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]));
    }
    EXPECT_NEAR(a, 4.0 * std::numbers::pi, 4.0 * std::numbers::pi * 1e-3);
    double b = 0.0;
    for (const auto& t : s.shapes[3].mesh.triangles) {
        const auto& m = s.shapes[3].mesh;
        const glm::vec3 n = glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
        EXPECT_GT(n.z, 0.0f);  // facing +z, as pbrt-v4's disk
        b += 0.5 * glm::length(n);
    }
    EXPECT_NEAR(b, 0.75 * std::numbers::pi, 0.75 * std::numbers::pi * 1e-3);
}

TEST(PbrtImport, ObjectsAreInstancedWithTheInstanceTransform) {
    const auto s = import(scene("ObjectBegin \"tri\"\nShape \"trianglemesh\" \"point3 P\" [ 0 0 0  1 0 0  0 1 0 ]\nObjectEnd\n"
                                "AttributeBegin\nTranslate 10 0 0\nObjectInstance \"tri\"\nAttributeEnd\n"
                                "AttributeBegin\nTranslate 0 0 -10\nObjectInstance \"tri\"\nAttributeEnd\n"));
    ASSERT_EQ(s.shapes.size(), 3u);
    // LookAt 0 1 5 → 0 1 0 is left-handed in pbrt-v4: iris's world is pbrt's mirrored in x
    EXPECT_EQ(s.shapes[1].mesh.positions[0], glm::vec3(-10.0f, 0.0f, 0.0f));
    EXPECT_EQ(s.shapes[2].mesh.positions[0], glm::vec3(0.0f, 0.0f, -10.0f));
}

TEST(PbrtImport, BadInputIsAnErrorAtFileLineAndColumn) {
    struct bad {
        std::string text, message;
    };
    const bad cases[] = {
        {camera + "WorldBegin\n  Foo 1 2\n", "test.pbrt:5:3: unknown directive 'Foo'"},
        {camera + "WorldBegin\nShape \"sphere\" \"float radius\" 1 \"float foo\" 2\n",
         "test.pbrt:5:33: parameter \"float foo\" of Shape \"sphere\" is not supported"},
        {camera + "WorldBegin\nShape \"sphere\" \"string radius\" \"x\"\n", "test.pbrt:5:16: parameter \"string radius\" of Shape \"sphere\" has the wrong type"},
        {camera + "WorldBegin\nShape \"sphere\" \"float radius\" \"one\"\n", "test.pbrt:5:31: \"float radius\" takes numbers, found 'one'"},
        {camera + "WorldBegin\nNamedMaterial \"nope\"\n", "test.pbrt:5:1: unknown material 'nope'"},
        {camera + "WorldBegin\nAttributeEnd\n", "test.pbrt:5:1: AttributeEnd without a matching AttributeBegin"},
        {camera + "WorldBegin\nAttributeBegin\n" + lamp, "test.pbrt:5:1: AttributeBegin without its AttributeEnd"},
        {camera, "no WorldBegin"},
        {camera + "WorldBegin\n", "the scene has no shapes"},
        {camera + "WorldBegin\nShape \"sphere\"\n", "the scene has no light"},
        {scene("Shape \"curve\"\n"), "Shape \"curve\" is not supported"},
        {scene("Texture \"t\" \"spectrum\" \"checkerboard\"\n"), "test.pbrt:9:1: Texture \"t\": the class \"checkerboard\" is not supported"},
        {scene("Texture \"t\" \"spectrum\" \"imagemap\"\n"), "test.pbrt:9:1: an imagemap texture has no \"string filename\""},
        {scene("Texture \"t\" \"float\" \"imagemap\" \"string filename\" \"r.png\"\n"), "float image textures (roughness, bump or alpha maps) are not supported"},
        {scene("Texture \"t\" \"color\" \"constant\"\n"), "the kind must be \"spectrum\" or \"float\""},
        {scene("Texture \"t\" \"spectrum\" \"constant\" \"rgb value\" [ 2 0 0 ]\n"), "is a reflectance: components must be at most 1"},
        {scene("Texture \"t\" \"spectrum\" \"scale\" \"texture tex\" \"nope\"\n"), "test.pbrt:9:32: unknown spectrum texture 'nope'"},
        {scene("Texture \"t\" \"spectrum\" \"constant\"\nTexture \"t\" \"spectrum\" \"constant\"\n"), "test.pbrt:10:1: Texture \"t\" \"spectrum\" is defined twice"},
        {scene("Texture \"t\" \"spectrum\" \"constant\" \"float uscale\" 2\n"), "parameter \"float uscale\" of Texture \"t\" \"spectrum\" \"constant\" is not supported"},
        {scene("Material \"diffuse\" \"texture reflectance\" \"nope\"\n"), "unknown spectrum texture 'nope'"},
        {scene([] {
             std::string t = "Texture \"t0\" \"spectrum\" \"constant\"\n";
             for (int i = 1; i <= 70; ++i)
                 t += "Texture \"t" + std::to_string(i) + "\" \"spectrum\" \"scale\" \"texture tex\" \"t" + std::to_string(i - 1) + "\"\n";
             return t;
         }()),
         "textures nested more than 64 deep"},
        {scene("Material \"conductor\" \"texture roughness\" \"nope\"\n"), "unknown float texture 'nope'"},
        {scene("LightSource \"infinite\" \"string filename\" \"sky.pfm\"\n"), "iris reads OpenEXR environment images only"},
        {scene("LightSource \"infinite\" \"string filename\" \"sky.exr\"\n"), "infinite light image 'sky.exr' does not exist"},
        {scene("Material \"hair\"\nShape \"sphere\"\n"), "material type 'hair' is not supported"},
        {scene("Shape \"sphere\" \"float radius\" 1 \"float zmax\" 0.5\n"), "partial spheres"},
        {scene("Material \"diffuse\" \"rgb reflectance\" [ 2 0 0 ]\n"), "components must be at most 1"},
        {scene("Material \"dielectric\" \"spectrum eta\" [ 400 1.5 300 1.6 ]\n"), "the wavelengths must increase"},
        {scene("Material \"dielectric\" \"spectrum eta\" \"glass-XYZ\"\n"), "unknown named spectrum 'glass-XYZ'"},
        {scene("Include \"missing.pbrt\"\n"), "included file"},
        {scene("Shape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 ] \"integer indices\" [ 0 1 3 ]\n"), "is not one of the 3 points"},
        {camera + "WorldBegin\nShape \"sphere\" \"string name\" \"unterminated\n", "test.pbrt:5:30: unterminated string"},
        {camera + "WorldBegin\nTranslate 1 2 nan\n", "test.pbrt:5:15: expected Translate's x y z (a number), found 'nan'"},
        {camera + "WorldBegin\nTranslate 1 2 1e999\n", "test.pbrt:5:15: '1e999' is not a number"},
        {camera + "WorldBegin\nCamera \"perspective\"\n", "Camera is allowed only before WorldBegin"},
        {scene("MakeNamedMedium \"m\" \"string type\" \"uniformgrid\"\n"), "test.pbrt:9:21: medium type 'uniformgrid' is not supported"},
        {scene("MakeNamedMedium \"m\" \"rgb sigma_s\" [ 1 1 1 ]\n"), "test.pbrt:9:1: MakeNamedMedium \"m\" has no \"string type\""},
        {scene("MakeNamedMedium \"m\" \"string type\" \"homogeneous\"\nMakeNamedMedium \"m\" \"string type\" \"homogeneous\"\n"),
         "test.pbrt:10:1: medium 'm' is defined twice"},
        {scene("MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"string preset\" \"Skin1\"\n"), "\"preset\" (pbrt-v4's measured media) is not supported"},
        {scene("MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"float g\" 1\n"), "\"float g\" must lie in [-0.99, 0.99]"},
        {scene("MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"spectrum sigma_a\" [ 400 -1 700 1 ]\n"),
         "test.pbrt:9:49: medium 'm': \"sigma_a\" times scale must lie in [0, 1e9]"},
        {scene("MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"float scale\" -2\n"), "\"float scale\" must lie in [0, 1e9]"},
        {scene("MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"rgb Le\" [ 1 1 1 ]\n"), "emissive media (\"Le\") are not supported"},
        {scene("MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"float density\" 1\n"), "parameter \"float density\" of MakeNamedMedium \"m\" is not supported"},
        {scene("MediumInterface \"nope\" \"\"\nShape \"sphere\"\n"), "test.pbrt:10:1: the shape's MediumInterface names medium 'nope', which no MakeNamedMedium defines"},
        {"MediumInterface \"fog\"\n" + scene(""), "test.pbrt:3:1: the camera (its MediumInterface) names medium 'fog'"},
        {scene("Material \"interface\"\n"), "material \"interface\" (a surface that only bounds a medium) is not supported yet"},
        {scene("MakeNamedMedium \"m\" \"string type\" \"homogeneous\"\nMediumInterface \"\" \"m\"\nMaterial \"dielectric\"\nShape \"sphere\"\n"),
         "test.pbrt:12:1: the shape's outside medium is 'm' but the camera's is '': iris has one medium outside the solids"},
        {scene("LightSource \"point\" \"float illuminance\" 10\n"), "test.pbrt:9:21: parameter \"float illuminance\" of LightSource \"point\" is not supported"},
        {scene("Shape \"sphere\" \"float radius\" [ 1 2 ]\n"), "takes 1 value, got 2"},
        // mismatched nesting, values that overflow, bad geometry (found by review)
        {scene("ObjectBegin \"a\"\nAttributeEnd\nObjectEnd\n"), "test.pbrt:10:1: AttributeEnd without a matching AttributeBegin (mismatched nesting)"},
        {scene("AttributeBegin\nObjectEnd\n"), "test.pbrt:10:1: ObjectEnd without a matching ObjectBegin"},
        {scene("AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 1e39 1 1 ]\nShape \"sphere\"\nAttributeEnd\n"), "test.pbrt:10:1: a value out of range"},
        {scene("LightSource \"point\" \"float scale\" 1e300\n"), "the light's radiance overflows"},
        {scene("LightSource \"point\" \"point3 from\" [ 1e39 0 0 ]\n"), "a light's position is beyond"},
        {scene("LightSource \"spot\" \"point3 from\" [ 0 0 0 ] \"point3 to\" [ 0 0 0 ]\n"), "a spot light has no direction"},
        {scene("Material \"conductor\" \"spectrum eta\" [ 380 1.5 780 1.5 ]\nShape \"sphere\"\n"), "eta must be > 0 and k ≥ 0 at 360-830 nm"},
        {scene("Material \"conductor\" \"spectrum eta\" [ 360 1e200 830 1e200 ]\nShape \"sphere\"\n"), "a value out of range"},
        {scene("Material \"coatedconductor\" \"float conductor.roughness\" -1\nShape \"sphere\"\n"), "a roughness must be at least 0"},
        {scene("Material \"dielectric\" \"float roughness\" 4\nShape \"sphere\"\n"), "a GGX α above 1"},
        {scene("Option \"bool disablepixeljitter\" [ true\n"), "the file ends inside the list of Option"},
        {"Scale 0 1 1\n" + scene("Shape \"sphere\"\n"), "the camera's transform is singular"},
        {camera + "Import \"x.pbrt\"\n", "Import is allowed only after WorldBegin"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.text);
        const std::string e = error_of(c.text);
        EXPECT_NE(e.find(c.message), std::string::npos) << e;
    }
}

TEST(PbrtImport, TransformEndAndImportKeepTheirStateInside) {
    // pbrt-v4 reads TransformBegin/End as AttributeBegin/End: a material set inside does not leak
    const auto s = import(scene("TransformBegin\nMaterial \"dielectric\"\nTransformEnd\nShape \"sphere\"\n"));
    EXPECT_TRUE(std::holds_alternative<iris::material::diffuse>(s.materials[s.shapes.back().material]));
    // an Import's transform, material and area light stay inside the imported file
    const fs::path dir = fs::temp_directory_path() / ("iris-pbrt-import-state-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "main.pbrt") << scene("Import \"part.pbrt\"\nShape \"disk\"\n");
    std::ofstream(dir / "part.pbrt") << "Translate 5 0 0\nMaterial \"dielectric\"\nAreaLightSource \"diffuse\"\nShape \"sphere\"\n";
    const auto r = iris::scene::load_scene_file(dir / "main.pbrt");
    ASSERT_EQ(r.shapes.size(), 3u);
    EXPECT_TRUE(r.shapes[1].emitter.has_value());   // the imported sphere
    EXPECT_FALSE(r.shapes[2].emitter.has_value());  // the disk after it: no area light, no dielectric, no shift
    EXPECT_TRUE(std::holds_alternative<iris::material::diffuse>(r.materials[r.shapes[2].material]));
    float xmax = -1e9f;
    for (const auto& p : r.shapes[2].mesh.positions) xmax = std::max(xmax, std::fabs(p.x));
    EXPECT_LT(xmax, 1.5f);
    std::ofstream(dir / "part.pbrt", std::ios::trunc) << "AttributeBegin\nShape \"sphere\"\n";
    try {
        (void)iris::scene::load_scene_file(dir / "main.pbrt");
        ADD_FAILURE() << "no error for an import that leaves an AttributeBegin open";
    } catch (const iris::scene::error& e) {
        EXPECT_NE(std::string(e.what()).find("the imported file ends inside an AttributeBegin"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

TEST(PbrtImport, ApproximationsAreNotesAndErrorsWhenStrict) {
    const std::string text = scene("Material \"coateddiffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ] \"spectrum eta\" \"glass-BK7\"\n"
                                   "Shape \"sphere\"\n");
    const auto s = import(text);
    bool noted = false;
    for (const auto& n : iris::scene::approximations(s)) noted |= n.find("approximated by its value at 550 nm") != std::string::npos;
    EXPECT_TRUE(noted);
    const std::string e = error_of("PixelFilter \"box\"\n" + text, {.strict = true});
    EXPECT_NE(e.find("test.pbrt:10:1: material 'material.1': the coat's spectral \"eta\" approximated by its value at 550 nm"), std::string::npos) << e;
    // without a PixelFilter, pbrt-v4's default Gaussian is the first approximation
    EXPECT_NE(error_of(text, {.strict = true}).find("no PixelFilter: pbrt-v4's default Gaussian filter approximated"), std::string::npos);
    EXPECT_NE(e.find("(an error under --strict)"), std::string::npos) << e;
}

TEST(PbrtImport, CoatedMaterialsKeepTheirLayer) {
    auto s = import(scene("Material \"coateddiffuse\" \"rgb reflectance\" [ 0.4 0.2 0.2 ] \"float roughness\" 0.04 \"float eta\" 1.6\n"
                          "  \"float thickness\" 0.2 \"integer maxdepth\" 7 \"integer nsamples\" 3 \"float g\" 0.3\nShape \"sphere\"\n"));
    const auto* c = std::get_if<iris::material::coated>(&s.materials[s.shapes.back().material]);
    ASSERT_NE(c, nullptr);
    EXPECT_TRUE(std::holds_alternative<iris::material::diffuse>(c->base));
    EXPECT_FLOAT_EQ(c->roughness, 0.2f);  // √0.04: pbrt-v4 remaps by default
    EXPECT_FLOAT_EQ(c->eta, 1.6f);
    EXPECT_FLOAT_EQ(c->thickness, 0.2f);
    EXPECT_EQ(c->max_depth, 7);
    EXPECT_EQ(c->samples, 3);
    EXPECT_FLOAT_EQ(c->internal_reflectance, iris::coated_internal_reflectance(1.6f, 0.2f));  // filled by the loader
    s = import(scene("Material \"coatedconductor\" \"spectrum conductor.eta\" \"metal-Au-eta\" \"spectrum conductor.k\" \"metal-Au-k\"\n"
                     "  \"float interface.roughness\" 0.01 \"float conductor.roughness\" 0.09 \"bool remaproughness\" true\nShape \"sphere\"\n"));
    c = std::get_if<iris::material::coated>(&s.materials[s.shapes.back().material]);
    ASSERT_NE(c, nullptr);
    const auto& base = std::get<iris::material::conductor>(c->base);
    EXPECT_FLOAT_EQ(c->roughness, 0.1f);
    EXPECT_FLOAT_EQ(base.roughness, 0.3f);
    EXPECT_NEAR(base.ior->eta(600.0), iris::find_metal("Au")->eta_spectrum()(600.0), 1e-9);
    EXPECT_FLOAT_EQ(c->eta, 1.5f);       // pbrt-v4's default
    EXPECT_FLOAT_EQ(c->thickness, 0.01f);
    EXPECT_EQ(c->max_depth, 10);
    for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
             {"Material \"coateddiffuse\" \"rgb albedo\" [ 0.5 0.5 0.5 ]\n", "a scattering medium in the coat (\"albedo\" > 0) is not supported"},
             {"Material \"coateddiffuse\" \"float thickness\" -1\n", "\"float thickness\" must lie in [0, 1000]"},
             {"Material \"coateddiffuse\" \"float eta\" 0.8\n", "the coat's \"eta\" must lie in [1, 4], it is 0.8"},
             {"Material \"coatedconductor\" \"integer maxdepth\" 0\n", "\"integer maxdepth\" must lie in [1, 100]"},
             {"Material \"coateddiffuse\" \"integer nsamples\" 1000\n", "\"integer nsamples\" must lie in [1, 256]"},
             {"Material \"coateddiffuse\" \"float sigma\" 1\n", "parameter \"float sigma\" of Material \"coateddiffuse\" is not supported"}}) {
        SCOPED_TRACE(text);
        const std::string e = error_of(scene(text + "Shape \"sphere\"\n"));
        EXPECT_NE(e.find(message), std::string::npos) << e;
    }
}

TEST(PbrtImport, LoopSubdivisionSurfacesAreBuiltWithTheirNormals) {
    const std::string octahedron = "\"point3 P\" [ 1 0 0  -1 0 0  0 1 0  0 -1 0  0 0 1  0 0 -1 ]\n"
                                   "  \"integer indices\" [ 0 2 4  2 1 4  1 3 4  3 0 4  2 0 5  1 2 5  3 1 5  0 3 5 ]";
    const auto s = import(scene("Shape \"loopsubdiv\" \"integer levels\" 2 " + octahedron + "\n"));
    const auto& mesh = s.shapes.back().mesh;
    EXPECT_EQ(mesh.triangles.size(), 8u * 16u);
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) EXPECT_GT(glm::dot(mesh.normals[i], mesh.positions[i]), 0.0f);  // outward
    EXPECT_EQ(import(scene("Shape \"loopsubdiv\" " + octahedron + "\n")).shapes.back().mesh.triangles.size(), 8u * 64u);  // 3 by default
    for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
             {"Shape \"loopsubdiv\" \"integer levels\" 11 " + octahedron + "\n", "\"integer levels\" must lie in [0, 10]"},
             {"Shape \"loopsubdiv\" \"string scheme\" \"butterfly\" " + octahedron + "\n", "the only scheme is \"loop\""},
             {"Shape \"loopsubdiv\" \"integer levels\" 2 " + octahedron + " \"normal N\" [ 0 0 1 ]\n", "parameter \"normal N\" of Shape \"loopsubdiv\" is not supported"}}) {
        SCOPED_TRACE(text);
        const std::string e = error_of(scene(text));
        EXPECT_NE(e.find(message), std::string::npos) << e;
    }
    // a control mesh that is not an oriented manifold is refused when the scene is built, at its line
    try {
        (void)import(scene("Shape \"loopsubdiv\" \"point3 P\" [ 0 0 0  1 0 0  0 1 0  0 0 1 ] \"integer indices\" [ 0 1 2  0 1 3  0 2 1 ]\n"));
        ADD_FAILURE() << "no error for a non-manifold control mesh";
    } catch (const iris::scene::error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("test.pbrt:9: loopsubdiv"), std::string::npos) << m;
        EXPECT_NE(m.find("loopsubdiv: the control mesh is not an oriented manifold"), std::string::npos) << m;
    }
}

TEST(PbrtImport, PlyMeshesMayBeGzipCompressed) {
    const fs::path dir = fs::temp_directory_path() / ("iris-pbrt-import-gz-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                            "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                            "-1 0 -1\n1 0 -1\n1 0 1\n-1 0 1\n4 0 1 2 3\n";
    gzFile gz = gzopen((dir / "quad.ply.gz").c_str(), "wb");
    ASSERT_NE(gz, nullptr);
    ASSERT_EQ(gzwrite(gz, ply.data(), static_cast<unsigned>(ply.size())), static_cast<int>(ply.size()));
    gzclose(gz);
    std::ofstream(dir / "main.pbrt") << camera << "WorldBegin\n" << lamp << "Shape \"plymesh\" \"string filename\" \"quad.ply.gz\"\n";
    const auto s = iris::scene::load_scene_file(dir / "main.pbrt");
    ASSERT_EQ(s.shapes.size(), 2u);
    EXPECT_EQ(s.shapes[1].mesh.triangle_count(), 2u);  // the quad, fanned
    std::ofstream(dir / "quad.ply.gz", std::ios::trunc) << ply;  // not compressed after all
    try {
        (void)iris::scene::load_scene_file(dir / "main.pbrt");
        ADD_FAILURE() << "no error for a .gz file that is not gzip";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("quad.ply.gz"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("not a valid gzip file"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

TEST(PbrtImport, IncludesAreReadRelativeToTheMainFileAndCyclesAreRefused) {
    const fs::path dir = fs::temp_directory_path() / ("iris-pbrt-import-" + std::to_string(::getpid()));
    fs::create_directories(dir / "sub");
    std::ofstream(dir / "main.pbrt") << camera << "WorldBegin\nInclude \"sub/geometry.pbrt\"\n";
    // relative to the main file's directory, as pbrt-v4 resolves every path
    std::ofstream(dir / "sub" / "geometry.pbrt") << lamp << "Include \"sub/more.pbrt\"\n";
    std::ofstream(dir / "sub" / "more.pbrt") << "Shape \"sphere\"\n";
    const auto s = iris::scene::load_scene_file(dir / "main.pbrt");
    EXPECT_EQ(s.shapes.size(), 2u);
    EXPECT_EQ(s.name, "main");
    std::ofstream(dir / "sub" / "more.pbrt", std::ios::trunc) << "Include \"sub/geometry.pbrt\"\n";
    try {
        (void)iris::scene::load_scene_file(dir / "main.pbrt");
        ADD_FAILURE() << "no error for an include cycle";
    } catch (const iris::scene::error& e) {
        EXPECT_NE(std::string(e.what()).find("includes itself"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("more.pbrt:1:1:"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

TEST(PbrtImport, TexturesReachTheDiffuseReflectance) {
    const fs::path dir = fs::temp_directory_path() / ("iris-pbrt-import-tex-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    iris::image img(2, 1);
    img(0, 0) = {0.8f, 0.6f, 0.4f};
    img(1, 0) = {0.2f, 0.2f, 0.2f};
    iris::exr::write(dir / "grid.exr", img);
    const std::string quad = "Shape \"trianglemesh\" \"point3 P\" [ -1 0 -1  1 0 -1  1 0 1  -1 0 1 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n";
    std::ofstream(dir / "main.pbrt")
        << camera << "WorldBegin\n" << lamp
        << "Texture \"grid\" \"spectrum\" \"imagemap\" \"string filename\" \"grid.exr\" \"float uscale\" 2 \"float vdelta\" 0.5 "
           "\"string wrap\" \"clamp\"\n"
           "Texture \"half\" \"spectrum\" \"scale\" \"texture tex\" \"grid\" \"float scale\" 0.5\n"
           "Texture \"c\" \"spectrum\" \"constant\" \"rgb value\" [ 0.2 0.4 0.6 ]\n"
           "Texture \"m\" \"spectrum\" \"mix\" \"texture tex1\" \"c\" \"rgb tex2\" [ 1 1 1 ] \"float amount\" 0.25\n"
           "Texture \"r\" \"float\" \"constant\" \"float value\" 0.04\n"
           "Texture \"r2\" \"float\" \"scale\" \"texture tex\" \"r\" \"float scale\" 4\n"
           "Material \"diffuse\" \"texture reflectance\" \"half\"\n" << quad
        << "Material \"coateddiffuse\" \"texture reflectance\" \"half\"\n" << quad
        << "Material \"diffuse\" \"texture reflectance\" \"m\"\n" << quad
        << "Material \"conductor\" \"texture roughness\" \"r2\"\n" << quad;
    const auto s = iris::scene::load_scene_file(dir / "main.pbrt");
    ASSERT_EQ(s.textures.size(), 1u);  // one image, shared by the two materials that use it
    const auto& t = s.textures[0];
    EXPECT_EQ(t.wrap, iris::texture_wrap::clamp);
    EXPECT_EQ(t.uv_scale, glm::vec2(2.0f, 1.0f));
    EXPECT_EQ(t.uv_offset, glm::vec2(0.0f, 0.5f));
    // an EXR is linear: texel 0 is (0.8, 0.6, 0.4) · 0.5, upsampled as iris upsamples a texel
    const auto w = iris::upsample_linear_srgb({0.4, 0.3, 0.2});
    EXPECT_NEAR(t.weights[0].x, w.red, 1e-6);
    EXPECT_NEAR(t.weights[0].y, w.green, 1e-6);
    EXPECT_NEAR(t.weights[0].z, w.blue, 1e-6);
    const auto* d = iris::diffuse_part(s.materials[s.shapes[1].material]);
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->texture, std::optional<std::uint32_t>(0u));
    const auto* coated = std::get_if<iris::material::coated>(&s.materials[s.shapes[2].material]);
    ASSERT_NE(coated, nullptr);
    EXPECT_EQ(iris::diffuse_part(s.materials[s.shapes[2].material])->texture, std::optional<std::uint32_t>(0u));
    // the mix of two constants is the mix of their spectra (each upsampled as pbrt-v4 does)
    const auto* mixed = iris::diffuse_part(s.materials[s.shapes[3].material]);
    ASSERT_NE(mixed, nullptr);
    EXPECT_FALSE(mixed->texture.has_value());
    const auto a = iris::rgb_to_sigmoid({0.2, 0.4, 0.6}), b = iris::rgb_to_sigmoid({1.0, 1.0, 1.0});
    for (double l : {400.0, 500.0, 600.0, 700.0}) EXPECT_NEAR(mixed->reflectance(l), 0.75 * a(l) + 0.25 * b(l), 1e-9) << l;
    // a float texture as a roughness: 0.04 · 4, remapped (√) as pbrt-v4 does
    const auto* metal = std::get_if<iris::material::conductor>(&s.materials[s.shapes[4].material]);
    ASSERT_NE(metal, nullptr);
    EXPECT_NEAR(metal->roughness, 0.4f, 1e-6f);
    // what cannot be represented is refused where it is written
    const auto refused = [&](const std::string& world, const std::string& message) {
        std::ofstream(dir / "bad.pbrt", std::ios::trunc) << camera << "WorldBegin\n" << lamp
                                                          << "Texture \"grid\" \"spectrum\" \"imagemap\" \"string filename\" \"grid.exr\"\n"
                                                          << world;
        try {
            (void)iris::scene::load_scene_file(dir / "bad.pbrt");
            ADD_FAILURE() << "no error for " << world;
        } catch (const iris::scene::error& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
    };
    refused("Material \"diffuse\" \"texture reflectance\" \"grid\"\nShape \"sphere\"\n", "bad.pbrt:11:1: a textured material on a sphere");
    refused("Texture \"m\" \"spectrum\" \"mix\" \"texture tex1\" \"grid\"\n", "a mix texture of an image texture is not supported");
    refused("Material \"conductor\" \"texture eta\" \"grid\"\n", "an image texture is supported only as a diffuse or coateddiffuse");
    refused("Texture \"i\" \"spectrum\" \"imagemap\" \"string filename\" \"grid.exr\" \"bool invert\" true\n", "\"bool invert\" true) is not supported");
    refused("Texture \"i\" \"spectrum\" \"imagemap\" \"string filename\" \"grid.exr\" \"string wrap\" \"black\"\n", "imagemap wrap \"black\" is not supported");
    refused("Texture \"i\" \"spectrum\" \"imagemap\" \"string filename\" \"grid.exr\" \"string mapping\" \"spherical\"\n", "texture mapping \"spherical\" is not supported");
    refused("Texture \"i\" \"spectrum\" \"imagemap\" \"string filename\" \"grid.exr\" \"string encoding\" \"gamma 2.2\"\n", "imagemap encoding \"gamma 2.2\" is not supported");
    // a filter other than bilinear is an approximation: a note, an error under --strict
    std::ofstream(dir / "ewa.pbrt", std::ios::trunc) << camera << "WorldBegin\n" << lamp
                                                      << "Texture \"i\" \"spectrum\" \"imagemap\" \"string filename\" \"grid.exr\" \"string filter\" \"ewa\"\n"
                                                      << "Material \"diffuse\" \"texture reflectance\" \"i\"\n" << quad;
    const auto ewa = iris::scene::load_scene_file(dir / "ewa.pbrt");
    EXPECT_TRUE(std::any_of(ewa.notes.begin(), ewa.notes.end(), [](const std::string& n) { return n.find("filter \"ewa\" approximated") != std::string::npos; }));
    fs::remove_all(dir);
}

TEST(PbrtImport, InfiniteLightImagesAreEqualAreaMapsTurnedByTheirTransform) {
    const fs::path dir = fs::temp_directory_path() / ("iris-pbrt-import-env-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    iris::image img(8, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) img(x, y) = {1.0f, 1.0f, 1.0f};
    iris::exr::write(dir / "sky.exr", img);
    const auto to_map = [&](const std::string& transform) {
        std::ofstream(dir / "main.pbrt", std::ios::trunc)
            << camera << "WorldBegin\nAttributeBegin\n" << transform
            << "LightSource \"infinite\" \"string filename\" \"sky.exr\" \"float scale\" 2\nAttributeEnd\nShape \"sphere\"\n";
        const auto s = iris::scene::load_scene_file(dir / "main.pbrt");
        EXPECT_TRUE(s.environment && s.environment->map);
        EXPECT_EQ(s.environment->map->mapping, iris::environment_mapping::equal_area);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(s.environment->map->weights[0][i], 2.0f, 1e-5f);  // white: each basis weight 1, times scale
        return s.environment->map->to_map;
    };
    const auto near = [](glm::vec3 a, glm::vec3 b) { return glm::length(a - b) < 1e-6f; };
    // pbrt-v4's +z is the map's centre (iris's map convention: +y); the plain LookAt mirrors x
    const glm::mat3 plain = to_map("");
    EXPECT_TRUE(near(plain * glm::vec3(0, 0, 1), {0, 1, 0}));
    EXPECT_TRUE(near(plain * glm::vec3(-1, 0, 0), {1, 0, 0}));  // pbrt-v4's +x, mirrored into iris's world
    // Rotate 90° about y takes the light's +z to pbrt's +x, i.e. iris's −x
    const glm::mat3 turned = to_map("Rotate 90 0 1 0\n");
    EXPECT_TRUE(near(turned * glm::vec3(-1, 0, 0), {0, 1, 0}));
    // "illuminance" E_v: pbrt-v4's measure of a map's illuminance is 2π/(W·H)·Σ Y·cos θ over the
    // upper hemisphere's texels, π/2 for a white map (half of ∫ cos dω = π: its factor is 2π,
    // not 4π); the texels are scaled to make it E_v
    {
        iris::image big(64, 64);
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) big(x, y) = {1.0f, 1.0f, 1.0f};
        iris::exr::write(dir / "white.exr", big);
        std::ofstream(dir / "lit.pbrt", std::ios::trunc)
            << camera << "WorldBegin\nLightSource \"infinite\" \"string filename\" \"white.exr\" \"float illuminance\" 5\nShape \"sphere\"\n";
        const auto s = iris::scene::load_scene_file(dir / "lit.pbrt");
        for (int i = 0; i < 3; ++i)  // the midpoint rule over 64 × 64 texels: within 0.1 %
            EXPECT_NEAR(s.environment->map->weights[100][i], 5.0 / (std::numbers::pi / 2.0), 0.001 * 5.0 / (std::numbers::pi / 2.0));
    }
    // a uniform scale does not matter (pbrt-v4 normalises), a non-uniform one is refused
    EXPECT_TRUE(near(to_map("Scale 3 3 3\n") * glm::vec3(0, 0, 1), {0, 1, 0}));
    std::ofstream(dir / "bad.pbrt") << camera << "WorldBegin\nScale 1 2 1\nLightSource \"infinite\" \"string filename\" \"sky.exr\"\nShape \"sphere\"\n";
    try {
        (void)iris::scene::load_scene_file(dir / "bad.pbrt");
        ADD_FAILURE() << "no error for a sheared infinite light";
    } catch (const iris::scene::error& e) {
        EXPECT_NE(std::string(e.what()).find("non-uniform scale"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

// pbrt-v4's "power" and "illuminance" (lights.cpp's k_e): a point light's luminous intensity is
// φ/(4π); a spot's φ over its cone (the falloff band counted half); an area light's luminance
// φ/(π·A·sides) with A each shape's own area (a sphere's 4πr² in object space, each triangle
// of a mesh); a distant light's and a uniform sky's illuminance E_v (a sky's luminance E_v/π).
TEST(PbrtImport, PowerAndIlluminanceTakePbrtsNormalisation) {
    const double pi = std::numbers::pi;
    const auto s = import(camera + "WorldBegin\n"
                          "AttributeBegin\n AreaLightSource \"diffuse\" \"blackbody L\" 4000 \"float power\" 100 \"float scale\" 2\n"
                          " Shape \"trianglemesh\" \"point3 P\" [ -1 3 -1  1 3 -1  1 3 1  -1 3 1 ] \"integer indices\" [ 0 1 2 0 2 3 ]\n"
                          " Scale 3 3 3\n Shape \"sphere\" \"float radius\" 0.5\n"
                          " AreaLightSource \"diffuse\" \"float power\" 10 \"bool twosided\" true\n"
                          " Shape \"disk\" \"float radius\" 0.5 \"float innerradius\" 0.25\nAttributeEnd\n"
                          "LightSource \"point\" \"float power\" 50\n"
                          "LightSource \"spot\" \"float power\" 50 \"float coneangle\" 40 \"float conedeltaangle\" 10\n"
                          "LightSource \"distant\" \"float illuminance\" 7\n"
                          "LightSource \"infinite\" \"float illuminance\" 3\n"
                          "Shape \"sphere\"\n");
    ASSERT_EQ(s.shapes.size(), 4u);
    // the quad's triangles have area 2 each, in world space
    EXPECT_NEAR(luminance_of(s.emitters[*s.shapes[0].emitter].radiance), 2.0 * 100.0 / (pi * 2.0), 1e-9);
    // the sphere: pbrt-v4's Area() is in object space, the Scale does not enter
    EXPECT_NEAR(luminance_of(s.emitters[*s.shapes[1].emitter].radiance), 2.0 * 100.0 / (pi * 4.0 * pi * 0.25), 1e-9);
    EXPECT_NE(*s.shapes[0].emitter, *s.shapes[1].emitter);
    // a two-sided annulus: both sides share the power
    EXPECT_NEAR(luminance_of(s.emitters[*s.shapes[2].emitter].radiance), 10.0 / (pi * pi * (0.25 - 0.0625) * 2.0), 1e-9);
    ASSERT_EQ(s.lights.size(), 3u);
    EXPECT_NEAR(luminance_of(s.emitters[std::get<iris::light::point>(s.lights[0]).emitter].radiance), 50.0 / (4.0 * pi), 1e-9);
    const double c_end = std::cos(40.0 * pi / 180.0), c_start = std::cos(30.0 * pi / 180.0);
    EXPECT_NEAR(luminance_of(s.emitters[std::get<iris::light::spot>(s.lights[1]).emitter].radiance),
                50.0 / (2.0 * pi * ((1.0 - c_start) + (c_start - c_end) / 2.0)), 1e-9);
    EXPECT_NEAR(luminance_of(s.emitters[std::get<iris::light::distant>(s.lights[2]).emitter].radiance), 7.0, 1e-9);
    ASSERT_TRUE(s.environment.has_value());
    EXPECT_NEAR(luminance_of(s.environment->radiance), 3.0 / pi, 1e-9);
    // what iris cannot give pbrt-v4's per-shape normalisation is refused
    EXPECT_NE(error_of(scene("AreaLightSource \"diffuse\" \"float power\" 5\nShape \"trianglemesh\" \"point3 P\" [ 0 0 0  1 0 0  0 1 0  5 5 0 ] "
                             "\"integer indices\" [ 0 1 2  1 3 2 ]\n"))
                  .find("triangles differ in area"),
              std::string::npos);
    EXPECT_NE(error_of(scene("AreaLightSource \"diffuse\" \"float power\" 5\nShape \"plymesh\" \"string filename\" \"x.ply\"\n"))
                  .find("\"power\" on a plymesh is not supported"),
              std::string::npos);
}

// pbrt-v4 reads gzip-compressed scene files: an Include of `part.pbrt.gz` is decompressed
// (bounded), and one that is not gzip is an error naming it.
TEST(PbrtImport, IncludedFilesMayBeGzipCompressed) {
    const fs::path dir = fs::temp_directory_path() / ("iris-pbrt-import-incgz-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string part = lamp + "Shape \"sphere\"\n";
    gzFile gz = gzopen((dir / "part.pbrt.gz").c_str(), "wb");
    ASSERT_NE(gz, nullptr);
    ASSERT_EQ(gzwrite(gz, part.data(), static_cast<unsigned>(part.size())), static_cast<int>(part.size()));
    gzclose(gz);
    std::ofstream(dir / "main.pbrt") << camera << "WorldBegin\nInclude \"part.pbrt.gz\"\n";
    EXPECT_EQ(iris::scene::load_scene_file(dir / "main.pbrt").shapes.size(), 2u);
    // and so may the main file be
    const std::string main = camera + "WorldBegin\n" + part;
    gz = gzopen((dir / "whole.pbrt.gz").c_str(), "wb");
    ASSERT_NE(gz, nullptr);
    ASSERT_EQ(gzwrite(gz, main.data(), static_cast<unsigned>(main.size())), static_cast<int>(main.size()));
    gzclose(gz);
    EXPECT_EQ(iris::scene::load_scene_file(dir / "whole.pbrt.gz").shapes.size(), 2u);
    std::ofstream(dir / "part.pbrt.gz", std::ios::trunc) << part;
    try {
        (void)iris::scene::load_scene_file(dir / "main.pbrt");
        ADD_FAILURE() << "no error for a .gz include that is not gzip";
    } catch (const iris::scene::error& e) {
        EXPECT_NE(std::string(e.what()).find("main.pbrt:5:1: included file 'part.pbrt.gz': not a valid gzip file"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

// pbrt-v4's ActiveTransform: iris renders the pose at the shutter's opening — StartTime's
// transforms move the shape, EndTime's do not — and says so (a note; an error with strict).
TEST(PbrtImport, MotionIsApproximatedByTheShutterOpeningPose) {
    const std::string world = "AttributeBegin\nActiveTransform StartTime\nTranslate 1 0 0\nActiveTransform EndTime\nTranslate 0 5 0\n"
                              "ActiveTransform All\nTranslate 0 0 2\nShape \"sphere\"\nAttributeEnd\nShape \"sphere\"\n";
    const auto doc = iris::scene::parse_pbrt_document(scene(world), "test.pbrt", fs::temp_directory_path());
    ASSERT_EQ(doc.shapes.size(), 3u);
    // the plain LookAt mirrors x into iris's world: the start's +1 in x is −1
    const glm::vec4 o = doc.shapes[1].transform * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_NEAR(o.x, -1.0f, 1e-6f);
    EXPECT_NEAR(o.y, 0.0f, 1e-6f);
    EXPECT_NEAR(o.z, 2.0f, 1e-6f);
    // ActiveTransform is part of the attribute state: the last shape is where it was
    const glm::vec4 q = doc.shapes[2].transform * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_NEAR(glm::length(glm::vec3(q)), 0.0f, 1e-6f);
    const auto& notes = doc.desc.notes;
    EXPECT_EQ(std::count_if(notes.begin(), notes.end(), [](const std::string& n) { return n.find("motion blur approximated") != std::string::npos; }), 2);
    const std::string boxed = camera + "PixelFilter \"box\"\nWorldBegin\n" + lamp + world;  // no other note before it
    EXPECT_NE(error_of(boxed, {.strict = true}).find("test.pbrt:12:1: Translate under ActiveTransform StartTime: motion blur approximated"),
              std::string::npos)
        << error_of(boxed, {.strict = true});
    EXPECT_NE(error_of(scene("ActiveTransform Sometimes\n")).find("expected All, StartTime or EndTime"), std::string::npos);
}

// An "rgb" where pbrt-v4 wants an unbounded spectrum (a conductor's eta and k) is its
// RGBUnboundedSpectrum: m·S(λ), m = 2·max(r, g, b), S Jakob–Hanika's sigmoid of rgb/m.
TEST(PbrtImport, AnRgbIndexIsPbrtsUnboundedSpectrum) {
    const auto s = import(scene("Material \"conductor\" \"rgb eta\" [ 0.2 0.9 1.1 ] \"rgb k\" [ 3.9 2.4 2.1 ]\nShape \"sphere\"\n"));
    const auto* c = std::get_if<iris::material::conductor>(&s.materials[s.shapes[1].material]);
    ASSERT_NE(c, nullptr);
    ASSERT_TRUE(c->ior.has_value());
    const auto eta = iris::rgb_to_sigmoid({0.2 / 2.2, 0.9 / 2.2, 1.1 / 2.2}), k = iris::rgb_to_sigmoid({3.9 / 7.8, 2.4 / 7.8, 2.1 / 7.8});
    for (double l : {420.0, 550.0, 680.0}) {
        EXPECT_NEAR(c->ior->eta(l), 2.2 * eta(l), 1e-9) << l;
        EXPECT_NEAR(c->ior->k(l), 7.8 * k(l), 1e-9) << l;
    }
}

// pbrt-v4's homogeneous media (docs/pbrt-import.md, "Media"): the camera's medium fills the
// scene outside the solids; a dielectric bounding a medium holds it; a dielectric that is no
// medium boundary is filled with the camera's medium, as pbrt-v4 keeps the ray's medium there.
TEST(PbrtImport, HomogeneousMediaFillTheSceneAndTheDielectricsThatBoundThem) {
    const std::string fog = "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.02 0.04 0.08 ]\n"
                            "  \"rgb sigma_s\" [ 0.1 0.1 0.1 ] \"float scale\" 2 \"float g\" 0.4\nMediumInterface \"\" \"fog\"\n";
    const std::string world =
        "MakeNamedMedium \"smoke\" \"string type\" \"homogeneous\" \"spectrum sigma_s\" [ 400 3 700 1 ] \"spectrum sigma_a\" [ 400 0 700 0 ]\n"
        "Material \"dielectric\" \"float eta\" 1.4\n"
        "AttributeBegin\n MediumInterface \"smoke\" \"fog\"\n Shape \"sphere\"\nAttributeEnd\n"
        "AttributeBegin\n MediumInterface \"fog\" \"fog\"\n Translate 3 0 0\n Shape \"sphere\"\nAttributeEnd\n"
        "AttributeBegin\n MediumInterface \"smoke\" \"fog\"\n Translate -3 0 0\n Shape \"sphere\"\nAttributeEnd\n"
        "AttributeBegin\n Translate 0 3 0\n Shape \"sphere\"\nAttributeEnd\n"
        "Material \"diffuse\"\nShape \"sphere\" \"float radius\" 0.5\n";
    const auto s = import(fog + scene(world));
    ASSERT_TRUE(s.medium.has_value());
    ASSERT_TRUE(s.medium->absorption.has_value());
    ASSERT_TRUE(s.medium->scattering.has_value());
    const auto a = iris::rgb_to_sigmoid({0.02 / 0.16, 0.04 / 0.16, 0.08 / 0.16});
    for (double l : {420.0, 550.0, 680.0}) {
        EXPECT_NEAR((*s.medium->absorption)(l), 2.0 * 0.16 * a(l), 1e-9) << l;  // scale × pbrt-v4's unbounded rgb
        EXPECT_NEAR(s.medium->scattering->sigma_s(l), 0.2, 1e-9) << l;
    }
    EXPECT_FLOAT_EQ(s.medium->scattering->g, 0.4f);
    ASSERT_EQ(s.shapes.size(), 6u);
    const auto* smoke = std::get_if<iris::material::dielectric>(&s.materials[s.shapes[1].material]);
    ASSERT_NE(smoke, nullptr);
    EXPECT_FALSE(smoke->absorption.has_value());  // σ_a = 0 everywhere: no absorption
    ASSERT_TRUE(smoke->scattering.has_value());
    EXPECT_NEAR(smoke->scattering->sigma_s(400.0), 3.0, 1e-9);
    EXPECT_NEAR(smoke->scattering->sigma_s(700.0), 1.0, 1e-9);
    EXPECT_EQ(s.shapes[3].material, s.shapes[1].material);  // one material per (material, medium)
    const auto* fogged = std::get_if<iris::material::dielectric>(&s.materials[s.shapes[2].material]);
    ASSERT_NE(fogged, nullptr);
    ASSERT_TRUE(fogged->absorption.has_value() && fogged->scattering.has_value());
    EXPECT_NEAR((*fogged->absorption)(550.0), (*s.medium->absorption)(550.0), 1e-12);
    EXPECT_NEAR(fogged->scattering->sigma_s(550.0), 0.2, 1e-9);
    // without a MediumInterface of its own a shape keeps the current one — here the camera's
    // "" "fog", which pbrt-v4's WorldBegin does not reset: a boundary with nothing inside
    const auto* clear = std::get_if<iris::material::dielectric>(&s.materials[s.shapes[4].material]);
    ASSERT_NE(clear, nullptr);
    EXPECT_FALSE(clear->absorption.has_value() || clear->scattering.has_value());
    EXPECT_TRUE(std::holds_alternative<iris::material::diffuse>(s.materials[s.shapes[5].material]));
    for (const auto& n : s.notes) EXPECT_EQ(n.find("of an opaque shape"), std::string::npos) << n;  // "" inside: nothing to say

    // a glass that bounds no medium needs no closed solid (crossing it changes nothing); one
    // that bounds a medium does
    const std::string pane = "Material \"dielectric\"\nShape \"trianglemesh\" \"point3 P\" [ -1 0 -1  1 0 -1  1 0 1  -1 0 1 ] "
                             "\"integer indices\" [ 0 2 1  0 3 2 ]\n";
    EXPECT_NO_THROW((void)import(fog + scene("MediumInterface \"fog\" \"fog\"\n" + pane)));
    EXPECT_THROW((void)import(fog + scene("MakeNamedMedium \"smoke\" \"string type\" \"homogeneous\"\nMediumInterface \"smoke\" \"fog\"\n" + pane)),
                 iris::scene::error);

    // no camera medium: no scene medium; an opaque shape's inside medium is a note
    const std::string opaque = "MakeNamedMedium \"m\" \"string type\" \"homogeneous\"\nMediumInterface \"m\" \"\"\nShape \"sphere\"\n";
    const auto o = import(scene(opaque));
    EXPECT_FALSE(o.medium.has_value());
    bool noted = false;
    for (const auto& n : o.notes) noted |= n.find("the inside medium 'm' of an opaque shape is not modelled") != std::string::npos;
    EXPECT_TRUE(noted);
    iris::scene::pbrt_import_options strict;
    strict.strict = true;
    EXPECT_NE(error_of(scene(opaque), strict).find("(an error under --strict)"), std::string::npos);
}

// pbrt-v4's film records radiance times its imaging ratio, shutter time × ISO / 100: the
// importer scales every light by it (a note says so), so the image is pbrt-v4's.
TEST(PbrtImport, TheImagingRatioScalesEveryLight) {
    const std::string cam = "LookAt 0 1 5  0 1 0  0 1 0\nCamera \"perspective\" \"float fov\" 40 \"float shutterclose\" 0.5\n"
                            "Film \"rgb\" \"float iso\" 150\nPixelFilter \"box\"\n";
    const auto plain = import(scene("LightSource \"point\" \"float scale\" 3\nLightSource \"infinite\" \"float scale\" 2\nShape \"sphere\"\n"));
    const auto doc = iris::scene::parse_pbrt_document(cam + "WorldBegin\n" + lamp +
                                                          "LightSource \"point\" \"float scale\" 3\nLightSource \"infinite\" \"float scale\" 2\nShape \"sphere\"\n",
                                                      "test.pbrt", fs::temp_directory_path());
    const double k = 0.5 * 150.0 / 100.0;
    ASSERT_EQ(doc.desc.emitters.size(), plain.emitters.size());
    for (std::size_t i = 0; i < plain.emitters.size(); ++i)
        EXPECT_NEAR(luminance_of(doc.desc.emitters[i].radiance), k * luminance_of(plain.emitters[i].radiance), 1e-9) << i;
    EXPECT_NEAR(luminance_of(doc.desc.environment->radiance), k * 2.0, 1e-9);
    EXPECT_TRUE(std::any_of(doc.desc.notes.begin(), doc.desc.notes.end(),
                            [](const std::string& n) { return n.find("test.pbrt:3:1: pbrt-v4's imaging ratio 0.75") != std::string::npos; }));
    // an approximation no longer: --strict accepts it
    EXPECT_EQ(error_of(cam + "WorldBegin\n" + lamp + "Shape \"sphere\"\n", {.strict = true}), "");
}
