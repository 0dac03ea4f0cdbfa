// U2 / U3 as a comparison of two presets, shared by statistical_test.cpp (the default
// suite, at the power it can afford) and statistical_long_test.cpp (label `long`, 2 %).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <variant>
#include <vector>

#include <iris/renderer/renderer.hpp>
#include <iris/scene/scene.hpp>

#include "region_stats.hpp"

namespace iris_test {

/// \brief Options for a w×h render of `preset` at `spp` with N_thold and seed.
inline iris::renderer::options render_options(const std::string& preset, int w, int h, int spp, int nthold, std::uint64_t seed) {
    iris::renderer::options o;
    o.preset = preset;
    o.width = w;
    o.height = h;
    o.spp = spp;
    o.nthold = nthold;
    o.seed = seed;
    return o;
}

// Statistics: the mean X, Y, Z over each quadrant of the image and over the whole image
// (15), of the samples [from, spp), for `hwss` (seed 1) and the preset (seed 1001, so the
// two are independent). Each is a mean of per-pass region means (region_stats.hpp): one
// pass is one independent sample per pixel, so their spread estimates the standard error.
// That holds while α changes too (U3's windows before N_thold): passes of equal expectation
// but different variances give a sample variance whose expectation is their mean variance
// — and equal expectations are the claim under test. z test of the difference per
// statistic, Šidák over the 15 at family-wise α = 0.01 (|z| ≤ 3.85; ≥ 200 passes of
// ≥ 768-pixel means: normal). Power, asserted: the smallest relative bias of the whole
// image's Y the test detects with 90 % power, (z + 1.2816) · se / Y, is at most 2 %.
// The default suite cannot afford 2 % everywhere (falling-cubes' caustics give heavy-tailed
// samples: 2 % there takes ~25 M samples per preset); each test there asserts the power
// it has, and statistical_long_test.cpp (label `long`) repeats the comparisons at sizes
// that reach 2 %.

/// \brief `preset` over samples [from, spp) agrees with `hwss` over the same samples, on a
/// w × h render (w, h even); the bias detectable with 90 % power (relative, Y) must be at
/// most `power` (2 % unless a smaller test has to state less).
inline double expect_agreement(const iris::scene_desc& s, const std::string& preset, int w, int h, int spp, int nthold,
                               int from, const std::string& what, double power = 0.02) {
    const auto quadrants = [&](const std::string& p, std::uint64_t seed) {
        return iris_test::grid_estimates(s, render_options(p, w, h, spp, nthold, seed), 2, 2, from);
    };
    const auto whole = [](const std::vector<iris_test::region_estimate>& q) {
        iris_test::region_estimate m;
        for (std::size_t c = 0; c < 3; ++c) {
            double var = 0.0;
            for (const auto& r : q) m.mean[c] += 0.25 * r.mean[c], var += 0.0625 * r.se[c] * r.se[c];
            m.se[c] = std::sqrt(var);
        }
        return m;
    };
    auto a = quadrants("hwss", 1), b = quadrants(preset, 1001);
    a.push_back(whole(a));
    b.push_back(whole(b));
    const double z = iris_test::sidak_z(0.01, 15);
    for (std::size_t r = 0; r < a.size(); ++r)
        for (std::size_t c = 0; c < 3; ++c) {
            const double se = std::hypot(a[r].se[c], b[r].se[c]);
            EXPECT_LT(std::fabs(a[r].mean[c] - b[r].mean[c]), z * se)
                << what << (r < 4 ? " quadrant " + std::to_string(r) : std::string(" whole image")) << " channel " << c
                << ": hwss " << a[r].mean[c] << ", " << preset << " " << b[r].mean[c] << " (se " << se << ")";
        }
    const double detectable = (z + 1.2816) * std::hypot(a[4].se[1], b[4].se[1]) / a[4].mean[1];
    std::printf("%s: Y hwss %.5f, %s %.5f; detects a %.2f %% bias with 90 %% power\n", what.c_str(), a[4].mean[1],
                preset.c_str(), b[4].mean[1], 100.0 * detectable);
    EXPECT_LE(detectable, power) << what << ": too few samples to detect a " << 100.0 * power << " % bias";
    return detectable;
}

enum class glass { rough, non_dispersive };

/// \brief falling-cubes with its glass made rough (GGX α = 0.3) or non-dispersive (n = n_d).
inline iris::scene_desc falling_cubes_variant(glass g) {
    auto s = iris::scene::builtin_scene("falling-cubes");
    for (auto& m : s.materials)
        if (auto* d = std::get_if<iris::material::dielectric>(&m)) {
            if (g == glass::rough) d->roughness = 0.3f;
            if (g == glass::non_dispersive) d->ior = iris::constant_ior{iris::refractive_index(d->ior, 587.5618)};
        }
    return s;
}

}  // namespace iris_test
