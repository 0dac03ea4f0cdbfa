// The renderer (Embree, TBB, preset dispatch) on analytic scenes: U1 on the white furnace
// for every preset, determinism across thread counts, cancellation, bad options.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include <iris/renderer/renderer.hpp>

#include "test_scenes.hpp"

namespace {

using iris::renderer::options;

/// \brief Per-pixel Y means of the samples with index ≥ from, from two snapshots.
std::vector<double> window_y(const iris::scene_desc& s, const options& o, int from) {
    std::vector<double> at;
    iris::renderer::hooks h;
    h.on_pass = [&](const iris::film& f, const iris::renderer::status& st) {
        if (st.spp_done == from)
            for (std::size_t i = 0; i < static_cast<std::size_t>(f.width() * f.height()); ++i) at.push_back(f.mean(i).y);
        return true;
    };
    iris::film f(1, 1);
    iris::renderer::render(s, o, f, h);
    std::vector<double> y;
    for (std::size_t i = 0; i < static_cast<std::size_t>(f.width() * f.height()); ++i)
        y.push_back((f.mean(i).y * o.spp - (from > 0 ? at[i] * from : 0.0)) / (o.spp - from));
    return y;
}

// Šidák over ≤ 16 presets at family-wise α = 0.01: per test 6.3e-4, two-sided z = 3.42;
// 3.84 (m = 16 at α = 0.002 each) is used as a round, conservative bound.
constexpr double z_family = 3.84;

TEST(RendererCore, WhiteFurnaceIsFiveForEveryPreset) {
    const auto s = iris::test::furnace(0.8);
    const auto presets = iris::renderer::presets();
    ASSERT_LE(presets.size(), 16u);
    for (const auto& p : presets) {
        options o;
        o.preset = p.name;
        o.width = o.height = 16;
        o.spp = 256;  // enough power: se < 0.05 even for C = 1 after N_thold (192 samples)
        o.nthold = 64;
        o.seed = 11;
        o.path.max_depth = 200;
        // unbiased presets count every sample (α from 0 to 1); the others only after N_thold (U2)
        const auto y = window_y(s, o, p.unbiased_before_nthold ? 0 : o.nthold);
        double m = 0, m2 = 0;
        for (double v : y) m += v, m2 += v * v;
        const double n = static_cast<double>(y.size());
        m /= n;
        const double se = std::sqrt((m2 / n - m * m) / (n - 1));
        EXPECT_NEAR(m, 5.0, z_family * se) << p.name << " se " << se;
        EXPECT_LT(se, 0.05) << p.name;
    }
}

TEST(RendererCore, RestrictOnlyIsDimBeforeNtholdNegativeControl) {
    const auto s = iris::test::furnace(0.8);
    options o;
    o.preset = "restrict-only";
    o.width = o.height = 16;
    o.spp = 32;
    o.nthold = 512;
    o.path.max_depth = 200;
    const auto y = window_y(s, o, 0);
    double m = 0;
    for (double v : y) m += v;
    m /= static_cast<double>(y.size());
    EXPECT_LT(m, 4.5);
}

TEST(RendererCore, IdenticalPixelsForAnyThreadCount) {
    const iris::sellmeier_ior bk7{1.03961212, 0.231792344, 1.01046945, 0.00600069867, 0.0200179144, 103.560653};
    const auto s = iris::test::furnace_with_glass(0.5, bk7);
    auto run = [&](int threads, std::uint64_t seed) {
        options o;
        o.preset = "paper";
        o.width = 20;
        o.height = 12;
        o.spp = 4;
        o.nthold = 2;
        o.threads = threads;
        o.seed = seed;
        iris::film f(1, 1);
        const auto st = iris::renderer::render(s, o, f);
        EXPECT_TRUE(st.dispersive_instantiation);
        return f.to_image();
    };
    const auto a = run(1, 7), b = run(2, 7), c = run(2, 7), d = run(2, 8);
    EXPECT_TRUE(a == b);
    EXPECT_TRUE(b == c);
    EXPECT_FALSE(b == d);
}

TEST(RendererCore, CancelKeepsTheLastCompletePass) {
    const auto s = iris::test::furnace(0.5);
    options o;
    o.spp = 100;
    o.width = o.height = 8;
    std::atomic<bool> cancel{false};
    iris::renderer::hooks h;
    h.cancel = &cancel;
    h.on_pass = [&](const iris::film&, const iris::renderer::status& st) {
        if (st.spp_done == 3) cancel = true;
        return true;
    };
    iris::film f(1, 1);
    const auto st = iris::renderer::render(s, o, f, h);
    EXPECT_TRUE(st.interrupted);
    EXPECT_EQ(st.spp_done, 3);
    for (std::size_t i = 0; i < 64; ++i) EXPECT_EQ(f.samples(i), 3u);
}

TEST(RendererCore, BadOptionsNameWhatIsAccepted) {
    const auto s = iris::test::furnace(0.5);
    iris::film f(1, 1);
    options o;
    o.preset = "no-such-preset";
    try {
        iris::renderer::render(s, o, f);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("paper"), std::string::npos) << e.what();
    }
    o.preset = "hwss";
    o.spp = 0;
    EXPECT_THROW(iris::renderer::render(s, o, f), std::invalid_argument);
    o.spp = 1;
    o.nthold = 0;
    EXPECT_THROW(iris::renderer::render(s, o, f), std::invalid_argument);
    o.nthold = 1;
    o.width = -3;
    o.height = 4;
    EXPECT_THROW(iris::renderer::render(s, o, f), std::invalid_argument);
    o.width = o.height = 0;
    o.isa = "sse9";
    try {
        iris::renderer::render(s, o, f);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("avx512"), std::string::npos) << e.what();
    }
    const auto sets = iris::renderer::instruction_sets();
    for (const char* isa : {"avx2", "avx512"})  // known, but refused where this CPU cannot run it
        if (std::find(sets.begin(), sets.end(), isa) == sets.end()) {
            o.isa = isa;
            EXPECT_THROW(iris::renderer::render(s, o, f), std::invalid_argument) << isa;
        }
}

TEST(RendererCore, ExtremeIorsStayFinite) {
    for (double eta : {1.0, 4.0}) {
        const auto s = iris::test::furnace_with_glass(0.5, iris::constant_ior{eta});
        options o;
        o.preset = "paper";
        o.width = o.height = 12;
        o.spp = 4;
        o.nthold = 1;
        iris::film f(1, 1);
        EXPECT_EQ(iris::renderer::render(s, o, f).nan_inf, 0u) << eta;
    }
}

}  // namespace
