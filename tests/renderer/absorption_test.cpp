// Absorbing dielectrics (iris/render/absorption.hpp; docs/method.md §8): a slab's
// transmittance against its closed form with Fresnel at both faces, for a grey and a strongly
// chromatic σ_a, through the path tracer (`hwss`; `paper` with its B term on) and the
// BSDF-only estimator; and the two estimators against each other where next-event estimation
// must attenuate its shadow rays (a lamp inside a block of coloured glass).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <iris/renderer/renderer.hpp>
#include <iris/scene/scene.hpp>
#include <iris/spectrum/color.hpp>

#include "phenomena_options.hpp"
#include "region_stats.hpp"

namespace {

using iris::renderer::options;
using iris_test::region_estimate;

options make(const std::string& estimator, const std::string& preset, int spp, std::uint64_t seed) {
    return iris_test::phenomena_options(estimator, preset, spp, seed);
}

const char* grey = "0.5";
const char* chromatic = R"({"wavelengths": [380, 450, 520, 600, 680, 780], "values": [3.0, 1.5, 0.05, 0.4, 1.2, 2.5]})";

/// \brief A camera looking along −z through a glass cube of edge 1 (index 1.5, absorption
/// `sigma` as JSON; none: no cube) at a large emitter facing it; a 2° field of view, so every
/// ray crosses the cube within 1° of its normal.
iris::scene_desc slab(const std::string& sigma) {
    std::string json = R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 2, "resolution": [8, 8]},
      "materials": {"black": {"type": "diffuse", "reflectance": 0})";
    if (!sigma.empty()) json += R"(, "glass": {"type": "dielectric", "ior": 1.5, "absorption": )" + sigma + "}";
    json += R"(}, "emitters": {"l": {"spd": "D65", "luminance": 1}},
      "shapes": [{"type": "quad", "size": [4, 4], "material": "black", "emitter": "l",
                  "transform": [{"rotate": {"axis": [1, 0, 0], "degrees": 90}}, {"translate": [0, 0, -2]}]})";
    if (!sigma.empty()) json += R"(, {"type": "cube", "size": 1, "material": "glass"})";
    json += "]}";
    return iris::scene::parse_scene(json, "slab", ".");
}

/// \brief ∫ L T ȳ / ∫ L ȳ over the scene's domain (1 nm steps): the slab's transmittance
/// weighted by what the camera sees of the emitter, T = (1 − R)² τ / (1 − R² τ²) with
/// τ = exp(−σ_a d), R = ((n − 1)/(n + 1))² (normal incidence, every internal reflection summed).
double expected_ratio(const iris::scene_desc& s) {
    const iris::material::dielectric* found = nullptr;
    for (const auto& m : s.materials)
        if (const auto* d = std::get_if<iris::material::dielectric>(&m)) found = d;
    if (!found) throw std::logic_error("the slab scene has no glass");
    const auto& glass = *found;
    const double r = std::pow((1.5 - 1.0) / (1.5 + 1.0), 2.0);
    double num = 0.0, den = 0.0;
    for (double l = s.lambda_min + 0.5; l < s.lambda_max; l += 1.0) {
        const double w = s.emitters[0].radiance(l) * iris::cie::y_bar(l);
        const double tau = std::exp(-(*glass.absorption)(l) * 1.0);
        num += w * (1.0 - r) * (1.0 - r) * tau / (1.0 - r * r * tau * tau);
        den += w;
    }
    return num / den;
}

/// \brief The whole image's mean Y and its standard error.
region_estimate whole(const iris::scene_desc& s, const options& o) { return iris_test::grid_estimates(s, o, 1, 1)[0]; }

}  // namespace

// The image's Y through the slab over the image's Y without it must be the closed form. 2
// absorptions × 3 estimators = 6 ratios at family-wise α = 0.001 (Šidák; per-pass means of
// 64 pixels, 2048 passes each (bsdf-only: 8192), normal approximation; the ratio's standard error by the delta
// method). Power: each ratio's 90 %-detectable relative error is printed and asserted below
// 2 % — an absorption left out (τ = 0.61 grey), applied outside the glass or on the wrong
// side is a 40 % to 100 % error, and a B term that does not attenuate its bins brightens
// `paper`'s chromatic slab by far more than 2 %. Seeds fixed.
TEST(Absorption, ASlabKeepsTheClosedFormTransmittance) {
    const double z_max = iris_test::sidak_z(0.001, 6);
    std::uint64_t seed = 11;
    for (const char* sigma : {grey, chromatic}) {
        const iris::scene_desc with = slab(sigma), without = slab("");
        const double expected = expected_ratio(with);
        for (const auto& [estimator, preset] : std::vector<std::pair<std::string, std::string>>{
                 {"nee-mis", "hwss"}, {"nee-mis", "paper"}, {"bsdf-only", "hwss"}}) {
            const int spp = estimator == "bsdf-only" ? 8192 : 2048;  // one wavelength a sample: noisier
            const region_estimate a = whole(with, make(estimator, preset, spp, seed++));
            const region_estimate b = whole(without, make(estimator, preset, spp, seed++));
            const double ratio = a.mean[1] / b.mean[1];
            const double se = ratio * std::hypot(a.se[1] / a.mean[1], b.se[1] / b.mean[1]);
            const double z = (ratio - expected) / se;
            const double detectable = (z_max + 1.2816) * se / expected;
            std::printf("sigma %s, %s %s: ratio %.5f ± %.5f, closed form %.5f, z %+.2f (threshold %.2f); detects %.2f %%\n",
                        sigma == grey ? "grey" : "chromatic", estimator.c_str(), preset.c_str(), ratio, se, expected, z,
                        z_max, 100.0 * detectable);
            EXPECT_LE(std::fabs(z), z_max) << estimator << " " << preset << " " << sigma;
            EXPECT_LE(detectable, 0.02) << "the test has lost its power";
        }
    }
}

namespace {
/// \brief A floor lit only by a lamp inside a block of rough coloured glass (the lamp faces
/// down; the block stands clear of the floor): next-event estimation at the block's rough
/// surface reaches the lamp through the glass, and its shadow rays must be attenuated.
iris::scene_desc lamp_in_glass() {
    const std::string json = R"({"camera": {"position": [0, 2.4, 2.4], "look_at": [0, 0.3, 0], "fov": 55, "resolution": [32, 24]},
      "materials": {"floor": {"type": "diffuse", "reflectance": 0.6}, "black": {"type": "diffuse", "reflectance": 0},
                    "glass": {"type": "dielectric", "ior": 1.5, "roughness": 0.3,
                              "transmittance": {"srgb": [0.9, 0.35, 0.15]}, "transmittance_depth": 0.5}},
      "emitters": {"l": {"spd": "D65", "luminance": 40}},
      "shapes": [{"type": "quad", "size": [4, 4], "material": "floor"},
                 {"type": "cube", "size": 1, "material": "glass", "transform": [{"translate": [0, 0.6, 0]}]},
                 {"type": "quad", "size": [0.5, 0.5], "material": "black", "emitter": "l",
                  "transform": [{"rotate": {"axis": [1, 0, 0], "degrees": 180}}, {"translate": [0, 0.7, 0]}]}]})";
    return iris::scene::parse_scene(json, "lamp-in-glass", ".");
}
}  // namespace

// Both estimators are unbiased here; only the path tracer's shadow rays cross the glass
// toward the lamp (`light_absorbed`, and the hero's transmittance in `next_event`), so a
// missing or wrong attenuation there shows as a disagreement. 4 × 3 regions × 3 channels
// at family-wise α = 0.001 (Šidák); per-pass region means of 2560 (nee-mis) and 20480
// (bsdf-only) passes, normal approximation. Power: the
// relative difference of the whole image's Y detected with 90 % probability is printed and
// asserted below 6 % (without the shadow rays' attenuation the path tracer's image is
// brighter by far more: τ ≈ 0.35–0.9 over half a unit of glass, its direct light the most of it).
TEST(Absorption, BsdfOnlyAgreesWithNeeMisThroughColouredGlass) {
    const iris::scene_desc s = lamp_in_glass();
    const double z_max = iris_test::sidak_z(0.001, (12 + 1) * 3);
    options a = make("nee-mis", "paper", 2560, 21), b = make("bsdf-only", "hwss", 20480, 22);
    for (options* o : {&a, &b}) {
        o->width = 32;
        o->height = 24;
    }
    const auto ra = iris_test::grid_estimates(s, a, 4, 3), rb = iris_test::grid_estimates(s, b, 4, 3);
    const auto wa = iris_test::grid_estimates(s, a, 1, 1)[0], wb = iris_test::grid_estimates(s, b, 1, 1)[0];
    const double worst = std::max(iris_test::max_abs_z(ra, rb), iris_test::max_abs_z({wa}, {wb}));
    const double detectable = (z_max + 1.2816) * std::hypot(wa.se[1], wb.se[1]) / wb.mean[1];
    std::printf("lamp in glass: Y nee-mis %.5f ± %.5f, bsdf-only %.5f ± %.5f; max |z| %.2f (threshold %.2f); detects "
                "%.1f %%\n",
                wa.mean[1], wa.se[1], wb.mean[1], wb.se[1], worst, z_max, 100.0 * detectable);
    EXPECT_LE(worst, z_max);
    EXPECT_LE(detectable, 0.06) << "the test has lost its power";
}

// Bad input gets a clear error; the bidirectional estimators refuse absorbing glass for now.
TEST(Absorption, BadInputAndUnsupportedEstimatorsAreErrors) {
    const auto parse = [](const std::string& glass) {
        const std::string json = R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
          "materials": {"g": )" + glass + R"(}, "shapes": [{"type": "cube", "size": 1, "material": "g"}],
          "environment": {"spd": "D65", "luminance": 1}})";
        return iris::scene::parse_scene(json, "bad", ".");
    };
    const auto message = [&](const std::string& glass) {
        try {
            parse(glass);
        } catch (const std::exception& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message(R"({"type": "dielectric", "ior": 1.5, "absorption": -1})").find("absorption"), std::string::npos);
    EXPECT_NE(message(R"({"type": "dielectric", "ior": 1.5, "transmittance": 0.5})").find("transmittance_depth"),
              std::string::npos);
    EXPECT_NE(message(R"({"type": "dielectric", "ior": 1.5, "transmittance": 0.5, "transmittance_depth": 0})")
                  .find("transmittance_depth"),
              std::string::npos);
    EXPECT_NE(message(R"({"type": "dielectric", "ior": 1.5, "absorption": 1, "transmittance": 0.5, "transmittance_depth": 1})")
                  .find("not both"),
              std::string::npos);
    EXPECT_NE(message(R"({"type": "dielectric", "ior": 1.5, "absorption": "red"})").find("absorption"), std::string::npos);
    // a transmittance over a depth is σ_a = −ln T / depth
    const auto g = parse(R"({"type": "dielectric", "ior": 1.5, "transmittance": 0.25, "transmittance_depth": 2})");
    EXPECT_NEAR((*std::get<iris::material::dielectric>(g.materials[0]).absorption)(550.0), std::log(4.0) / 2.0, 1e-9);
    EXPECT_TRUE(g.features().absorbing);
    iris::film f(1, 1);
    for (const char* e : {"light", "bdpt"}) {
        options o = make(e, "hwss", 1, 1);
        try {
            iris::renderer::render(slab(grey), o, f);
            ADD_FAILURE() << e << " rendered an absorbing scene";
        } catch (const std::invalid_argument& x) {
            EXPECT_NE(std::string(x.what()).find("absorbing"), std::string::npos) << x.what();
        }
    }
}
