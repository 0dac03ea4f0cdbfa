// Statistical properties of the method on real scenes (SPEC U1, U2; convergence rate).
// Fixed seeds throughout; every threshold is derived from a stated confidence level.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include <iris/metrics/metrics.hpp>
#include <iris/renderer/renderer.hpp>
#include <iris/scene/scene.hpp>

namespace {

using iris::renderer::options;

/// \brief Per-pixel XYZ means of the samples with index in [from, to) (0-based), from
/// two snapshots of the running mean: (m_to·to − m_from·from) / (to − from).
std::vector<iris::xyz> window_means(const iris::scene_desc& s, options o, int from) {
    std::vector<iris::xyz> at_from;
    iris::renderer::hooks h;
    h.on_pass = [&](const iris::film& f, const iris::renderer::status& st) {
        if (st.spp_done == from) {
            at_from.resize(static_cast<std::size_t>(f.width() * f.height()));
            for (std::size_t i = 0; i < at_from.size(); ++i) at_from[i] = f.mean(i);
        }
        return true;
    };
    iris::film f(1, 1);
    iris::renderer::render(s, o, f, h);
    std::vector<iris::xyz> out(static_cast<std::size_t>(f.width() * f.height()));
    const double n = o.spp, t = from;
    for (std::size_t i = 0; i < out.size(); ++i) {
        const auto m = f.mean(i);
        const auto a = from > 0 ? at_from[i] : iris::xyz{};
        out[i] = {(m.x * n - a.x * t) / (n - t), (m.y * n - a.y * t) / (n - t), (m.z * n - a.z * t) / (n - t)};
    }
    return out;
}

struct mean_se {
    double mean, se;
};
mean_se y_over_pixels(const std::vector<iris::xyz>& px) {
    double s = 0, s2 = 0;
    for (const auto& p : px) {
        s += p.y;
        s2 += p.y * p.y;
    }
    const double n = static_cast<double>(px.size());
    const double m = s / n;
    return {m, std::sqrt((s2 / n - m * m) * n / (n - 1) / n)};
}

// ---- U1: the white furnace, every preset ---------------------------------------------
// 16×16 pixel means are independent with the same expectation (the radiance is Y = 5
// everywhere), so their spread estimates the standard error of the grand mean. Family
// of presets × 1 test at family-wise α = 0.01, Šidák: per test α = 1 − 0.99^(1/m);
// with m ≤ 16 presets the two-sided normal quantile is ≤ 3.84 (256 pixels: normal is fine).
constexpr double z_furnace = 3.84;

TEST(Statistical, FurnaceIsFiveForEveryPreset) {
    const auto s = iris::scene::builtin_scene("furnace");
    const auto presets = iris::renderer::presets();
    ASSERT_LE(presets.size(), 16u);
    for (const auto& p : presets) {
        options o;
        o.preset = p.name;
        o.width = 16;
        o.height = 16;
        o.spp = 256;  // C = 1 needs it: at 64 spp its se is ≈ 0.07 (> the 0.05 power bound)
        o.nthold = 64;
        o.seed = 11;
        o.path.max_depth = 200;  // 0.8^200: truncation far below the noise
        // unbiased presets: every sample counts (α from 0 to 1); the others only after N_thold
        const int from = p.unbiased_before_nthold ? 0 : o.nthold;
        const auto e = y_over_pixels(window_means(s, o, from));
        EXPECT_NEAR(e.mean, 5.0, z_furnace * e.se) << p.name << " (se " << e.se << ")";
        EXPECT_LT(e.se, 0.05) << p.name << ": too few samples to see a 3 % error";
    }
}

TEST(Statistical, FurnaceNegativeControlRestrictOnlyIsDimBeforeNthold) {
    // Proves the furnace test can fail: restriction without a bias term is dim at α < 1.
    const auto s = iris::scene::builtin_scene("furnace");
    options o;
    o.preset = "restrict-only";
    o.width = 16;
    o.height = 16;
    o.spp = 32;
    o.nthold = 512;
    o.path.max_depth = 200;
    const auto e = y_over_pixels(window_means(s, o, 0));
    EXPECT_GT(std::fabs(e.mean - 5.0), z_furnace * e.se);
}

// ---- U2 / U3: two presets agree -----------------------------------------------------
// R = 16 seeds each; statistics: the mean X, Y, Z over the whole image and over its four
// quadrants (15 tests). Welch t-test per statistic, Šidák-corrected to family-wise
// α = 0.01: per-test α = 6.7e-4; with ≥ 15 degrees of freedom the two-sided t critical
// value is ≤ 4.271 (computed from Student's t; 30 dof would give 3.9).
constexpr double t_agree = 4.271;
constexpr int seeds = 16, width = 24, height = 18;

/// \brief Per-seed means of X, Y, Z over the image and its quadrants (15 statistics) of
/// the samples [from, spp) of `preset`.
std::array<std::vector<double>, 15> region_statistics(const iris::scene_desc& s, const std::string& preset, int spp,
                                                      int nthold, int from, std::uint64_t seed_base) {
    std::array<std::vector<double>, 15> stats;
    for (int seed = 0; seed < seeds; ++seed) {
        options o;
        o.preset = preset;
        o.width = width;
        o.height = height;
        o.spp = spp;
        o.nthold = nthold;
        o.seed = seed_base + static_cast<std::uint64_t>(seed);
        const auto px = window_means(s, o, from);
        for (int region = 0; region < 5; ++region) {
            std::array<double, 3> sum{};
            int n = 0;
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) {
                    if (region > 0 &&
                        ((x < width / 2) != ((region - 1) % 2 == 0) || (y < height / 2) != ((region - 1) / 2 == 0)))
                        continue;
                    const auto& p = px[static_cast<std::size_t>(y * width + x)];
                    sum[0] += p.x, sum[1] += p.y, sum[2] += p.z;
                    ++n;
                }
            for (std::size_t c = 0; c < 3; ++c) stats[static_cast<std::size_t>(region) * 3 + c].push_back(sum[c] / n);
        }
    }
    return stats;
}

/// \brief Welch t of the difference of the means of two samples.
double welch_t(const std::vector<double>& a, const std::vector<double>& b) {
    auto ms = [](const std::vector<double>& v) {
        double m = 0, s2 = 0;
        for (double x : v) m += x;
        m /= static_cast<double>(v.size());
        for (double x : v) s2 += (x - m) * (x - m);
        return std::pair{m, s2 / static_cast<double>(v.size() - 1)};
    };
    const auto [ma, va] = ms(a);
    const auto [mb, vb] = ms(b);
    return (ma - mb) / std::sqrt(va / static_cast<double>(a.size()) + vb / static_cast<double>(b.size()));
}

/// \brief `preset` over samples [from, spp) agrees with `hwss` over the same samples.
void expect_agreement(const iris::scene_desc& s, const std::string& preset, int spp, int nthold, int from,
                      const std::string& what) {
    const auto a = region_statistics(s, "hwss", spp, nthold, from, 1);
    const auto b = region_statistics(s, preset, spp, nthold, from, 1001);
    for (std::size_t k = 0; k < 15; ++k)
        EXPECT_LT(std::fabs(welch_t(a[k], b[k])), t_agree) << what << " statistic " << k;
}

// U2: after N_thold (samples [8, 24) with N_thold = 8, α = 1) paper is hwss.
TEST(Statistical, U2PaperAgreesWithHwssAfterNtholdOnCornell) {
    expect_agreement(iris::scene::builtin_scene("cornell"), "paper", 24, 8, 8, "cornell");
}
TEST(Statistical, U2PaperAgreesWithHwssAfterNtholdOnFallingCubes) {
    expect_agreement(iris::scene::builtin_scene("falling-cubes"), "paper", 24, 8, 8, "falling-cubes");
}

enum class glass { rough, non_dispersive };

/// \brief falling-cubes with its glass made rough (GGX α = 0.3) or non-dispersive (n = n_d).
iris::scene_desc falling_cubes_variant(glass g) {
    auto s = iris::scene::builtin_scene("falling-cubes");
    for (auto& m : s.materials)
        if (auto* d = std::get_if<iris::material::dielectric>(&m)) {
            if (g == glass::rough) d->roughness = 0.3f;
            if (g == glass::non_dispersive) d->ior = iris::constant_ior{iris::refractive_index(d->ior, 587.5618)};
        }
    return s;
}

// U3, first half: without specular dispersion the propagated term is exact, so paper is
// unbiased at every iteration: samples [0, 24) with N_thold = 64 all have α < 0.4.
TEST(Statistical, U3PaperIsUnbiasedBeforeNtholdWithoutSpecularDispersion) {
    const auto rough = falling_cubes_variant(glass::rough);
    ASSERT_FALSE(rough.features().dispersive_specular);
    ASSERT_TRUE(rough.features().dispersive_rough);
    expect_agreement(rough, "paper", 24, 64, 0, "rough dispersive glass");
    const auto plain = falling_cubes_variant(glass::non_dispersive);
    ASSERT_FALSE(plain.features().dispersive());
    expect_agreement(plain, "paper", 24, 64, 0, "non-dispersive glass");
}

// U3, second half — with specular dispersion paper is biased while α < 1 and the bias
// shrinks as α grows — has no test: on the built-in scenes the bias is below what 16 seeds
// can resolve (falling-cubes at 24×18, α < 0.25: image-mean ΔY = −0.02, Welch t = −1.8;
// with an exaggerated Cauchy B = 0.05 µm² still t = −1.7), and the paper's own argument is
// that it is small. docs/results.md shows where it lives instead (bias maps).

// ---- convergence: MSE ∝ 1/N for the unbiased configurations --------------------------
// hwss, hwss-c1 and hwss-c8 on cornell (24×24): the log-log slope of MSE against spp over
// 4…64 spp, against a 4096-spp hwss reference, in 16 independent renders per preset. One
// render's slope is noisy — its per-seed standard deviation is ≈ 0.15–0.2 here (fireflies
// through the glass cube), far more than the ≈ 0.04 a first version of this test assumed
// from 8 % relative noise per MSE point — so the test is a one-sample t-test of the mean
// slope against −1 per preset: Šidák over 3 presets at family-wise α = 0.01 gives per-test
// α = 3.34e-3, two-sided t critical value 3.482 at 15 degrees of freedom (Student's t,
// computed numerically). Power: with sd 0.2 the standard error is 0.05, so a slope of
// −0.8 (e.g. a bias floor in the MSE) gives t ≈ 4 and fails. The reference's own noise
// (64/4096 of the 64-spp MSE) flattens the expected slope by < 0.01.
constexpr double t_slope = 3.482;

double mse_slope(const iris::scene_desc& s, const options& o, const iris::image& reference) {
    std::vector<double> xs, ys;
    iris::renderer::hooks hk;
    hk.on_pass = [&](const iris::film& f, const iris::renderer::status& st) {
        if (st.spp_done == 4 || st.spp_done == 8 || st.spp_done == 16 || st.spp_done == 32 || st.spp_done == 64) {
            xs.push_back(std::log(static_cast<double>(st.spp_done)));
            ys.push_back(std::log(iris::mse(f.to_image(), reference)));
        }
        return true;
    };
    iris::film f(1, 1);
    iris::renderer::render(s, o, f, hk);
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < xs.size(); ++i) mx += xs[i], my += ys[i];
    mx /= static_cast<double>(xs.size()), my /= static_cast<double>(xs.size());
    double sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < xs.size(); ++i) sxy += (xs[i] - mx) * (ys[i] - my), sxx += (xs[i] - mx) * (xs[i] - mx);
    return sxy / sxx;
}

TEST(Statistical, UnbiasedPresetsMseFallsAsOneOverN) {
    const auto s = iris::scene::builtin_scene("cornell");
    options ref;
    ref.preset = "hwss";
    ref.width = ref.height = 24;
    ref.spp = 4096;
    ref.seed = 999;
    iris::film rf(1, 1);
    iris::renderer::render(s, ref, rf);
    const auto reference = rf.to_image();
    // the unbiased presets pass; restrict-only (dim until N_thold = 512: a bias floor under
    // the MSE) is the negative control that shows the test can fail
    for (const char* preset : {"hwss", "hwss-c1", "hwss-c8", "restrict-only"}) {
        const bool unbiased = std::string(preset) != "restrict-only";
        std::vector<double> slopes;
        for (int seed = 1; seed <= 16; ++seed) {
            options o = ref;
            o.preset = preset;
            o.spp = 64;
            o.seed = static_cast<std::uint64_t>(seed);
            slopes.push_back(mse_slope(s, o, reference));
        }
        double m = 0, v = 0;
        for (double x : slopes) m += x;
        m /= static_cast<double>(slopes.size());
        for (double x : slopes) v += (x - m) * (x - m);
        const double se = std::sqrt(v / static_cast<double>(slopes.size() - 1) / static_cast<double>(slopes.size()));
        if (unbiased)
            EXPECT_LT(std::fabs(m + 1.0) / se, t_slope) << preset << ": mean slope " << m << " (se " << se << ")";
        else
            EXPECT_GT(std::fabs(m + 1.0) / se, t_slope) << preset << ": mean slope " << m << " (se " << se << ")";
    }
}

}  // namespace
