// iris-scene export --pbrt (docs/pbrt-export.md): the written file holds what pbrt-v4 needs to
// render iris's scene — every spectrum iris's own, lights scaled so that pbrt-v4's radiance is
// iris's — and refuses what it cannot write exactly. pbrt-v4 itself is not part of the
// build: these tests read the text the way pbrt-v4 does (an inline spectrum is piecewise
// linear and 0 outside its list; a light's spectrum is divided by Σ ȳ(λ) L(λ) at 1 nm over
// 360–830 nm and multiplied by "scale"; its film's Y is ∫ȳL, iris's ∫ȳL / ∫ȳ, so pbrt-v4's
// radiance times ∫ȳ must be iris's), and bench/pbrt renders it with pbrt-v4.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <iris/scene/scene.hpp>
#include <iris/spectrum/color.hpp>

namespace {

/// The numbers of the list that follows the first `key` at or after `from` (`pos` is set
/// past it); empty if there is none.
std::vector<double> list_after(const std::string& text, const std::string& key, std::size_t& pos) {
    const std::size_t k = text.find(key, pos);
    if (k == std::string::npos) return {};
    const std::size_t open = text.find('[', k), close = text.find(']', open);
    pos = close;
    std::istringstream in(text.substr(open + 1, close - open - 1));
    std::vector<double> v;
    for (double x; in >> x;) v.push_back(x);
    return v;
}

/// pbrt-v4's reading of an inline spectrum: linear between the points, 0 outside them.
double pbrt_spectrum(const std::vector<double>& pairs, double lambda) {
    const std::size_t n = pairs.size() / 2;
    if (n == 0 || lambda < pairs[0] || lambda > pairs[2 * (n - 1)]) return 0.0;
    for (std::size_t i = 0; i + 1 < n; ++i) {
        const double l0 = pairs[2 * i], l1 = pairs[2 * i + 2];
        if (lambda <= l1) return pairs[2 * i + 1] + (lambda - l0) / (l1 - l0) * (pairs[2 * i + 3] - pairs[2 * i + 1]);
    }
    return pairs[2 * n - 1];
}

double pbrt_photometric(const std::vector<double>& pairs) {
    return iris::spectrum_to_xyz([&](double l) { return pbrt_spectrum(pairs, l); }).y;
}

bool increasing(const std::vector<double>& pairs) {
    for (std::size_t i = 2; i < pairs.size(); i += 2)
        if (!(pairs[i] > pairs[i - 2])) return false;
    return pairs.size() % 2 == 0 && !pairs.empty();
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
}

}  // namespace

TEST(PbrtExport, EveryBuiltinSceneIsWrittenWithOneBlockPerShapeAndIrisSpectra) {
    for (const auto& b : iris::scene::builtin_scenes()) {
        SCOPED_TRACE(std::string(b.name));
        const auto s = iris::scene::builtin_scene(b.name);
        const std::string t = iris::scene::pbrt_scene_text(s);
        EXPECT_EQ(count(t, "\nWorldBegin\n"), 1u);
        EXPECT_EQ(count(t, "Shape \"trianglemesh\""), s.shapes.size());
        EXPECT_EQ(count(t, "MakeNamedMaterial"), s.materials.size());
        std::size_t emissive = 0;
        for (const auto& sh : s.shapes) emissive += sh.emitter.has_value();
        EXPECT_EQ(count(t, "AreaLightSource \"diffuse\""), emissive);
        // every inline spectrum has increasing wavelengths (pbrt-v4 stops otherwise)
        for (const char* key : {"\"spectrum L\"", "\"spectrum reflectance\"", "\"spectrum eta\""}) {
            std::size_t pos = 0;
            for (auto v = list_after(t, key, pos); !v.empty(); v = list_after(t, key, pos)) EXPECT_TRUE(increasing(v)) << key;
        }
        // each emitter: pbrt-v4's radiance, L(λ)·scale / Σȳ L, times ∫ȳ is iris's L(λ) in the domain
        std::size_t pos = 0;
        for (const auto& sh : s.shapes) {
            if (!sh.emitter) continue;
            const auto scale = list_after(t, "AreaLightSource \"diffuse\" \"float scale\"", pos);
            const auto l = list_after(t, "\"spectrum L\"", pos);
            ASSERT_EQ(scale.size(), 1u);
            const auto& iris_l = s.emitters[*sh.emitter].radiance;
            const double k = scale[0] / pbrt_photometric(l) * iris::cie::y_integral;
            EXPECT_NEAR(k, 1.0, 1e-6);
            for (double lambda = s.lambda_min; lambda <= s.lambda_max; lambda += 0.37)
                EXPECT_NEAR(k * pbrt_spectrum(l, lambda), iris_l(lambda), 1e-6 * iris_l(lambda) + 1e-12) << lambda;
            EXPECT_EQ(pbrt_spectrum(l, s.lambda_min - 0.5), 0.0);  // iris emits nothing outside its domain
            EXPECT_EQ(pbrt_spectrum(l, s.lambda_max + 0.5), 0.0);
        }
    }
}

TEST(PbrtExport, DispersiveGlassIsWrittenAsItsIndexAtEveryWavelengthPbrtSamples) {
    const auto s = iris::scene::builtin_scene("prism");  // N-SF11, Sellmeier
    const std::string t = iris::scene::pbrt_scene_text(s);
    std::size_t pos = 0;
    const auto eta = list_after(t, "\"spectrum eta\"", pos);
    ASSERT_FALSE(eta.empty());
    EXPECT_EQ(eta.front(), iris::cie::cmf_lambda_min);  // pbrt-v4 reads η at 360–830 nm: never 0
    EXPECT_EQ(eta[eta.size() - 2], iris::cie::cmf_lambda_max);
    const iris::material::dielectric* glass = nullptr;
    for (const auto& m : s.materials)
        if (const auto* d = std::get_if<iris::material::dielectric>(&m)) glass = d;
    ASSERT_NE(glass, nullptr);
    for (double lambda = s.lambda_min; lambda <= s.lambda_max; lambda += 10.0)  // integer knots: exact to print precision
        EXPECT_NEAR(pbrt_spectrum(eta, lambda), iris::refractive_index(glass->ior, lambda), 1e-8) << lambda;
}

TEST(PbrtExport, LightsEnvironmentAndConductorsAreWrittenInPbrtsConventions) {
    auto s = iris::scene::builtin_scene("furnace");
    const iris::tabulated_spectrum flat({380.0, 780.0}, {2.0, 2.0});
    s.emitters.push_back({"flat", flat, false});
    const auto e = static_cast<std::uint32_t>(s.emitters.size() - 1);
    s.lights.push_back(iris::light::point{{1.0f, 2.0f, 3.0f}, e});
    s.lights.push_back(iris::light::spot{{0.0f, 4.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, std::cos(0.5f), std::cos(0.6f), e});
    s.lights.push_back(iris::light::distant{{0.0f, -1.0f, 0.0f}, e});
    s.environment = iris::environment_desc{"flat", flat, std::nullopt, {}};
    s.materials.push_back(iris::material::conductor{flat, iris::material::conductor_ior{"test", flat, flat}, 0.25f});
    s.material_names.push_back("my \"metal\"");
    s.camera.width = 100;
    s.camera.height = 200;
    s.camera.fov_y_degrees = 40.0f;
    const std::string t = iris::scene::pbrt_scene_text(s, {.spp = 7, .integrator = "bdpt", .max_depth = 5});
    EXPECT_NE(t.find("Sampler \"zsobol\" \"integer pixelsamples\" [ 7 ]"), std::string::npos);
    EXPECT_NE(t.find("Integrator \"bdpt\" \"integer maxdepth\" [ 5 ]"), std::string::npos);
    // a tall image: pbrt-v4's fov is the horizontal one, tan(fov/2) = tan(20°)·w/h
    std::size_t pos = 0;
    const auto fov = list_after(t, "\"float fov\"", pos);
    ASSERT_EQ(fov.size(), 1u);
    EXPECT_NEAR(std::tan(fov[0] * std::numbers::pi / 360.0), std::tan(20.0 * std::numbers::pi / 180.0) * 0.5, 1e-7);
    EXPECT_NE(t.find("LightSource \"point\" \"point3 from\" [ 1 2 3 ]"), std::string::npos);
    EXPECT_NE(t.find("LightSource \"spot\" \"point3 from\" [ 0 4 0 ] \"point3 to\" [ 0 3 0 ]"), std::string::npos);
    pos = t.find("LightSource \"spot\"");
    const auto cone = list_after(t, "\"float coneangle\"", pos), delta = list_after(t, "\"float conedeltaangle\"", pos);
    ASSERT_EQ(cone.size(), 1u);
    ASSERT_EQ(delta.size(), 1u);
    EXPECT_NEAR(cone[0], 0.6 * 180.0 / std::numbers::pi, 1e-4);
    EXPECT_NEAR(cone[0] - delta[0], 0.5 * 180.0 / std::numbers::pi, 1e-4);
    // the light travels along iris's direction: pbrt-v4's arrives from `from` − `to`
    EXPECT_NE(t.find("LightSource \"distant\" \"point3 from\" [ 0 0 0 ] \"point3 to\" [ 0 -1 0 ]"), std::string::npos);
    pos = t.find("LightSource \"infinite\"");
    ASSERT_NE(pos, std::string::npos);
    const auto scale = list_after(t, "\"float scale\"", pos), l = list_after(t, "\"spectrum L\"", pos);
    ASSERT_EQ(scale.size(), 1u);
    EXPECT_NEAR(scale[0] / pbrt_photometric(l) * iris::cie::y_integral * pbrt_spectrum(l, 555.5), 2.0, 1e-6);
    // the conductor: η and k, GGX α written as is (no remapping), a name pbrt-v4 can read
    EXPECT_NE(t.find("\"string type\" [ \"conductor\" ]"), std::string::npos);
    EXPECT_NE(t.find("\"float roughness\" [ 0.25 ] \"bool remaproughness\" [ false ]"), std::string::npos);
    EXPECT_NE(t.find("MakeNamedMaterial \"1-my__metal_\""), std::string::npos);
}

TEST(PbrtExport, WhatCannotBeWrittenExactlyIsRefusedWithTheReason) {
    auto s = iris::scene::builtin_scene("furnace");
    auto expect_error = [&](const iris::scene_desc& scene, const iris::scene::pbrt_export_options& o, const std::string& what) {
        try {
            (void)iris::scene::pbrt_scene_text(scene, o);
            ADD_FAILURE() << "no error for " << what;
        } catch (const iris::scene::error& e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    expect_error(s, {.integrator = "whitted"}, "unknown pbrt-v4 integrator 'whitted'");
    expect_error(s, {.spp = 0}, "pixel samples must be at least 1");
    expect_error(s, {.max_depth = -1}, "max depth must be at least 0");
    auto dark = s;
    dark.emitters[0].radiance = iris::tabulated_spectrum({800.0, 900.0}, {1.0, 1.0});  // outside 380-780 nm
    expect_error(dark, {}, "has no luminance in the domain");
    auto mirror = s;
    mirror.materials.push_back(iris::material::conductor{iris::tabulated_spectrum({380.0, 780.0}, {0.9, 0.9})});
    mirror.material_names.push_back("mirror");
    expect_error(mirror, {}, "material 'mirror' is a conductor given by its reflectance alone");
    auto textured = s;
    textured.materials.push_back(iris::material::diffuse{iris::tabulated_spectrum({380.0, 780.0}, {0.5, 0.5}), 0u});
    textured.material_names.push_back("wood");
    expect_error(textured, {}, "material 'wood' has an image texture");
    const auto dir = std::filesystem::temp_directory_path() / ("iris-pbrt-export-" + std::to_string(::getpid()));
    EXPECT_THROW(iris::scene::export_pbrt(s, dir / "no-such-dir" / "furnace.pbrt"), iris::scene::error);
    std::filesystem::create_directories(dir);
    iris::scene::export_pbrt(s, dir / "furnace.pbrt");
    std::ifstream in(dir / "furnace.pbrt");
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), iris::scene::pbrt_scene_text(s));
    std::filesystem::remove_all(dir);
}
