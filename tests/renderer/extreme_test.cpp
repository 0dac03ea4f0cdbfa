// Scenes at the edges (label `extreme`): every preset on glass of η 1.0 … 4.0 (smooth and
// rough), a grazing camera, lamps of luminance 1e-6 and 1e6, scenes scaled to 1e-4 and 1e4
// units, degenerate and sliver triangles (an emitter's included), a camera inside glass,
// C = 1 and C = 32, N_thold = 1, and a million samples of one constant pixel. The renders
// must not crash and must leave the film finite, with no sample dropped as NaN/Inf (a
// dropped one is counted, and counted here as a failure); where the answer is known — the
// white furnace, Y = 5 — it must still come out, within a stated confidence.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <unistd.h>

#include <iris/render/camera.hpp>
#include <iris/render/film.hpp>
#include <iris/render/integrator.hpp>
#include <iris/render/lights.hpp>
#include <iris/embree/intersector.hpp>
#include <iris/renderer/renderer.hpp>
#include <iris/sampling/presets.hpp>
#include <iris/scene/scene.hpp>

#include "region_stats.hpp"
#include "render_loop.hpp"
#include "test_scenes.hpp"

namespace {

using iris::renderer::options;

/// \brief A 2 m room (floor, back wall, ceiling lamp) holding one cube of `material`,
/// every length multiplied by `scale`. Radiance does not depend on the scale.
std::string room_json(const std::string& material, double scale = 1.0, const std::string& camera = "",
                      double luminance = 10.0, const std::string& extra_shapes = "") {
    const auto v = [&](double x) { return fmt::format("{:.9g}", x * scale); };
    const std::string cam = camera.empty() ? fmt::format(R"({{"position": [{}, {}, {}], "look_at": [0, {}, 0], "fov": 50, "resolution": [16, 12]}})",
                                                         v(0), v(1), v(3.5), v(0.6))
                                           : camera;
    return fmt::format(R"({{"camera": {},
      "materials": {{"white": {{"type": "diffuse", "reflectance": 0.7}}, "thing": {}}},
      "emitters": {{"lamp": {{"spd": "D65", "luminance": {}}}}},
      "shapes": [
        {{"type": "quad", "size": [{}, {}], "material": "white"}},
        {{"type": "quad", "size": [{}, {}], "material": "white", "transform": [{{"rotate": {{"axis": [1, 0, 0], "degrees": 90}}}}, {{"translate": [0, {}, {}]}}]}},
        {{"type": "quad", "size": [{}, {}], "material": "white", "emitter": "lamp", "transform": [{{"rotate": {{"axis": [1, 0, 0], "degrees": 180}}}}, {{"translate": [0, {}, 0]}}]}},
        {{"type": "cube", "size": {}, "material": "thing", "transform": [{{"translate": [0, {}, 0]}}]}}{}
      ]}})",
                       cam, material, luminance, v(2), v(2), v(2), v(2), v(1), v(-1), v(0.6), v(0.6), v(1.9), v(0.5),
                       v(0.26), extra_shapes);
}

iris::scene_desc parse(const std::string& json, const std::filesystem::path& dir = ".") {
    return iris::scene::parse_scene(json, "extreme_test", dir);
}

/// \brief Render and check the film: finite, non-negative, nothing dropped; returns it.
iris::film render_checked(const iris::scene_desc& s, const options& o, const std::string& what) {
    iris::film f(1, 1);
    const auto st = iris::renderer::render(s, o, f);
    EXPECT_EQ(st.spp_done, o.spp) << what;
    EXPECT_EQ(st.nan_inf, 0u) << what << ": " << st.nan_inf << " non-finite samples dropped";
    for (std::size_t i = 0; i < static_cast<std::size_t>(f.width() * f.height()); ++i) {
        const auto m = f.mean(i);
        if (!(std::isfinite(m.x) && std::isfinite(m.y) && std::isfinite(m.z) && m.y >= 0.0)) {
            ADD_FAILURE() << what << ": pixel " << i << " is (" << m.x << ", " << m.y << ", " << m.z << ")";
            break;
        }
    }
    return f;
}

options small(const std::string& preset, int spp = 6, int nthold = 3) {
    options o;
    o.preset = preset;
    o.spp = spp;
    o.nthold = nthold;  // samples before and after N_thold
    o.seed = 3;
    return o;
}

double mean_y(const iris::film& f) {
    double y = 0.0;
    for (std::size_t i = 0; i < static_cast<std::size_t>(f.width() * f.height()); ++i) y += f.mean(i).y;
    return y / (f.width() * f.height());
}

}  // namespace

// Glass of η from 1.0 (no interface at all) to 4.0 (beyond any glass: total internal
// reflection past 14.5°), smooth and rough, under every preset.
TEST(Extreme, DielectricsFromEta1To4StayFiniteForEveryPreset) {
    for (const double eta : {1.0, 1.0001, 1.5, 2.4, 4.0})
        for (const double roughness : {0.0, 0.05, 1.0}) {
            const auto s = parse(room_json(fmt::format(R"({{"type": "dielectric", "ior": {}, "roughness": {}}})", eta, roughness)));
            for (const auto& p : iris::renderer::preset_names())
                render_checked(s, small(p), fmt::format("{} on eta {} roughness {}", p, eta, roughness));
        }
}

// A camera 1e-4 m above the floor looking along it, and one looking straight down at it
// from 1e-3 m: rays at grazing incidence and shading points almost at the camera.
TEST(Extreme, GrazingAndNearCamerasStayFinite) {
    const std::string grazing = R"({"position": [0, 0.0001, 0.99], "look_at": [0, 0.0001, -1], "fov": 40, "resolution": [16, 12]})";
    const std::string close = R"({"position": [0.5, 0.001, 0.5], "look_at": [0.5, 0, 0.5], "up": [0, 0, -1], "fov": 40, "resolution": [16, 12]})";
    for (const auto& cam : {grazing, close}) {
        const auto s = parse(room_json(R"({"type": "dielectric", "ior": "N-SF11"})", 1.0, cam));
        for (const auto& p : iris::renderer::preset_names()) render_checked(s, small(p), p + " at " + cam);
    }
}

// Emission enters the estimate linearly and nothing random depends on it (one lamp: light
// choice, roulette and MIS see only geometry and throughput), so with the same seed the
// images under lamps of luminance 1e-6 and 1e6 are the image at 1 scaled, to float
// rounding (relative 1e-4 per pixel allows ~100 ulps of float accumulation).
TEST(Extreme, LuminanceFrom1eMinus6To1e6ScalesTheImageExactly) {
    for (const auto& p : iris::renderer::preset_names()) {
        const std::string glass = R"({"type": "dielectric", "ior": "N-BK7"})";
        const auto base = render_checked(parse(room_json(glass, 1.0, "", 1.0)), small(p), p + " at luminance 1");
        for (const double l : {1e-6, 1e6}) {
            const auto f = render_checked(parse(room_json(glass, 1.0, "", l)), small(p), fmt::format("{} at luminance {}", p, l));
            for (std::size_t i = 0; i < static_cast<std::size_t>(f.width() * f.height()); ++i) {
                const double want = base.mean(i).y * l, got = f.mean(i).y;
                ASSERT_LE(std::fabs(got - want), 1e-4 * want + 1e-300) << p << " at luminance " << l << ", pixel " << i;
            }
        }
    }
}

// The room scaled to 1e-4 m and 1e4 m: ray offsets follow the hit points' error bounds,
// so the image must be the same image. Whole-image Y at each scale against scale 1, per
// preset, over independent seeds' passes (region_stats.hpp), at family-wise 0.001 (Šidák).
TEST(Extreme, SceneScaledTo1eMinus4And1e4GivesTheSameImage) {
    const auto names = iris::renderer::preset_names();
    const double z = iris_test::sidak_z(0.001, 2 * names.size());
    const std::string glass = R"({"type": "dielectric", "ior": "N-BK7", "roughness": 0.2})";
    for (const auto& p : names) {
        auto o = small(p, p == "hwss-c1" ? 1024 : 128, 1);  // one wavelength: 8x the variance of Y
        o.width = 64;
        o.height = 48;
        const auto ref = iris_test::grid_estimates(parse(room_json(glass, 1.0)), o, 1, 1, 1)[0];
        for (const double scale : {1e-4, 1e4}) {
            const auto s = parse(room_json(glass, scale));
            render_checked(s, small(p), fmt::format("{} at scale {}", p, scale));
            auto os = o;
            os.seed = scale < 1.0 ? 4 : 5;  // independent of the reference
            const auto e = iris_test::grid_estimates(s, os, 1, 1, 1)[0];
            const double se = std::hypot(e.se[1], ref.se[1]);
            EXPECT_NEAR(e.mean[1], ref.mean[1], z * se) << p << " at scale " << scale << ": Y " << e.mean[1] << " vs " << ref.mean[1];
            // and the comparison can see a 5 % change at 90 % power
            EXPECT_LE((z + 1.2816) * se, 0.05 * ref.mean[1]) << p << " at scale " << scale;
        }
    }
}

// A mesh of bad triangles: zero-area ones (a repeated index, three collinear points, a
// point triangle), a 1e-7-wide sliver, and a huge flat one, used as the floor and as
// the lamp (a zero-area emitter triangle must get no light samples: its pdf would be 1/0).
TEST(Extreme, DegenerateAndSliverTrianglesAsFloorAndLamp) {
    const auto dir = std::filesystem::temp_directory_path() / fmt::format("iris-extreme-{}", ::getpid());
    std::filesystem::create_directories(dir);
    {
        std::ofstream off(dir / "bad.off");
        off << "OFF\n9 6 0\n"
               "-1 0 -1\n1 0 -1\n1 0 1\n-1 0 1\n"  // a good quad (0 1 2 3), wound to face +y below
               "0 0 0\n0.5 0 0\n1 0 0\n"           // collinear 4 5 6
               "0.2 0 0.2\n0.2 0 0.2000001\n"      // a sliver with 7 8
               "3 0 3 2\n3 0 2 1\n"
               "3 0 0 1\n"                          // repeated index
               "3 4 5 6\n"                          // collinear
               "3 7 7 7\n"                          // a point
               "3 7 8 2\n";                         // sliver
    }
    for (const bool as_lamp : {false, true}) {
        const std::string shape = as_lamp
            ? R"(, {"type": "mesh", "file": "bad.off", "material": "white", "emitter": "lamp", "transform": [{"rotate": {"axis": [1, 0, 0], "degrees": 180}}, {"translate": [0, 1.8, 0]}]})"
            : R"(, {"type": "mesh", "file": "bad.off", "material": "white", "transform": [{"scale": 0.4}, {"translate": [0, 0.001, 0]}]})";
        const auto s = parse(room_json(R"({"type": "diffuse", "reflectance": 0.5})", 1.0, "", 10.0, shape), dir);
        for (const auto& p : iris::renderer::preset_names())
            render_checked(s, small(p), p + (as_lamp ? " with a degenerate lamp" : " with a degenerate floor"));
    }
    std::filesystem::remove_all(dir);
}

// The camera inside a glass cube (every camera ray starts in glass and leaves through it).
TEST(Extreme, CameraInsideGlass) {
    const std::string inside = R"({"position": [0, 0.26, 0], "look_at": [0, 0.26, -1], "fov": 70, "resolution": [16, 12]})";
    for (const double roughness : {0.0, 0.3}) {
        const auto s = parse(room_json(fmt::format(R"({{"type": "dielectric", "ior": "N-SF11", "roughness": {}}})", roughness), 1.0, inside));
        for (const auto& p : iris::renderer::preset_names()) {
            const auto f = render_checked(s, small(p), fmt::format("{} inside glass, roughness {}", p, roughness));
            EXPECT_GT(mean_y(f), 0.0) << p << ": the room is visible from inside the glass";
        }
    }
}

namespace {

/// \brief A render of `Config` (any C) through the renderer's own loop, as renderer.cpp's
/// run<Preset> does it, for configurations that are not presets (C = 32).
template <class Config>
iris::film render_config(const iris::scene_desc& scene, const options& opt, iris::renderer::status& st) {
    typename Config::parameters params;
    params.n_thold = static_cast<std::uint32_t>(opt.nthold);
    params.domain = {scene.lambda_min, scene.lambda_max};
    const Config cfg(params);
    const iris::embree::intersector tracer(scene);
    const iris::light_sampler lights(scene);
    const iris::path_integrator<Config> integ(scene, lights, opt.path);
    iris::film f(opt.width, opt.height);
    const iris::camera_rays cam(scene.camera, f.width(), f.height());
    st.isa = "baseline";
    std::optional<typename Config::distribution_type> dist;
    iris::renderer::detail::run_passes<iris::renderer::detail::isa::baseline>(integ, tracer, cam, opt,
                                       [&](int i) {
                                           const float a = cfg.alpha(static_cast<std::uint64_t>(i));
                                           dist.emplace(cfg.distribution(a));
                                           return std::pair<float, const typename Config::distribution_type&>(a, *dist);
                                       },
                                       f, st, {});
    return f;
}

std::pair<double, double> furnace_y(const iris::film& f) {
    double m = 0, m2 = 0;
    const auto n = static_cast<std::size_t>(f.width() * f.height());
    for (std::size_t i = 0; i < n; ++i) {
        const double y = f.mean(i).y;
        m += y;
        m2 += y * y;
    }
    const double k = static_cast<double>(n);
    m /= k;
    return {m, std::sqrt((m2 / k - m * m) / (k - 1.0))};
}

}  // namespace

// C = 1 (hwss-c1) and C = 32 (an instantiation no preset uses, the dispersive one) on the
// flat white furnace, Y = 5, and on the furnace with N-BK7 glass (still Y = 5, see
// test_scenes.hpp); pixels are i.i.d., family-wise 0.001 over the four checks.
TEST(Extreme, OneAndThirtyTwoWavelengthsKeepTheFurnaceAtFive) {
    using c32 = iris::integrator_config<iris::restriction::unrestricted, iris::relaxation::none, 32, iris::bias::none>;
    const double z = iris_test::sidak_z(0.001, 4);
    const iris::scene_desc scenes[] = {iris::test::furnace(0.8), iris::test::furnace_with_glass(0.8, iris::sellmeier_ior{1.03961212, 0.231792344, 1.01046945, 0.00600069867, 0.0200179144, 103.560653})};
    for (const auto& s : scenes) {
        options o;
        o.width = o.height = 64;
        o.spp = 64;
        o.path.max_depth = 200;
        o.seed = 5;
        iris::renderer::status st;
        const auto f32 = render_config<c32>(s, o, st);
        EXPECT_EQ(st.nan_inf, 0u);
        const auto [m32, se32] = furnace_y(f32);
        EXPECT_NEAR(m32, 5.0, z * se32) << "C = 32 on " << s.name << ", se " << se32;
        EXPECT_LE((z + 1.2816) * se32, 0.1) << "C = 32 cannot see a 2 % bias";
        o.preset = "hwss-c1";
        iris::film f1(1, 1);
        EXPECT_EQ(iris::renderer::render(s, o, f1).nan_inf, 0u);
        const auto [m1, se1] = furnace_y(f1);
        EXPECT_NEAR(m1, 5.0, z * se1) << "C = 1 on " << s.name << ", se " << se1;
        EXPECT_LE((z + 1.2816) * se1, 0.1) << "C = 1 cannot see a 2 % bias";
    }
}

// N_thold = 1: sample 0 is drawn at α = 0 and every later one at α = 1. Every preset on
// the flat furnace must give Y = 5 on samples [1, spp) (and the unbiased ones on sample 0
// too, which the whole-run mean includes). Family-wise 0.001 over the presets.
TEST(Extreme, NtholdOneFurnaceIsFiveForEveryPreset) {
    const auto s = iris::test::furnace(0.8);
    const auto presets = iris::renderer::presets();
    const double z = iris_test::sidak_z(0.001, presets.size());
    for (const auto& p : presets) {
        options o = small(p.name, 64, 1);
        o.width = o.height = 64;
        o.path.max_depth = 200;
        const auto e = iris_test::grid_estimates(s, o, 1, 1, 1)[0];
        EXPECT_NEAR(e.mean[1], 5.0, z * e.se[1]) << p.name << ", se " << e.se[1];
        EXPECT_LE((z + 1.2816) * e.se[1], 0.1) << p.name << " cannot see a 2 % bias";
    }
}

// The film's accumulation precision: a million samples of one constant pixel (values
// not representable in binary) give back the constant. Double sums of n values carry at
// most n·ε relative error (1e6 · 1.1e-16 ≈ 1e-10); a float sum would be off by ~1e-2.
TEST(Extreme, AMillionSamplesOfAConstantPixelKeepItsValue) {
    iris::film f(2, 1);
    const iris::xyz v{0.1, 1.0 / 3.0, 7.77e-5};
    const iris::xyz big{1e6 / 3.0, 0.3, 2.2e7};
    for (int i = 0; i < 1'000'000; ++i) {
        f.add(0, v);
        f.add(1, big);
    }
    EXPECT_EQ(f.samples(0), 1'000'000u);
    const auto m = f.mean(0), b = f.mean(1);
    EXPECT_NEAR(m.x, v.x, 1e-9 * v.x);
    EXPECT_NEAR(m.y, v.y, 1e-9 * v.y);
    EXPECT_NEAR(m.z, v.z, 1e-9 * v.z);
    EXPECT_NEAR(b.x, big.x, 1e-9 * big.x);
    EXPECT_NEAR(b.z, big.z, 1e-9 * big.z);
}
