// Homogeneous scattering media (iris/render/medium.hpp; docs/method.md §10): the
// Henyey–Greenstein phase function's normalisation and its sampling (χ²), and one free flight
// with the spectral MIS over C wavelengths against closed forms — the probability of flying
// through a slab, e^{−σ_t d}, and the density of first scatterings, σ_s e^{−σ_t t}, per
// wavelength — with the variance of the MIS against single-hero tracking, both in closed form.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>

#include <glm/geometric.hpp>

#include <iris/render/bsdf.hpp>
#include <iris/render/medium.hpp>
#include <iris/render/random.hpp>
#include <iris/sampling/random.hpp>

#include "direction_fit.hpp"
#include "stats.hpp"

namespace {

using iris::sampled_spectrum;
using iris::sampled_wavelengths;

/// \brief ∫ p_HG dω over the sphere by a midpoint rule in cos θ (the phase is axially symmetric).
double hg_integral(float g) {
    constexpr int n = 200000;
    double s = 0.0;
    for (int i = 0; i < n; ++i) {
        const double c = -1.0 + 2.0 * (i + 0.5) / n;
        s += static_cast<double>(iris::henyey_greenstein(static_cast<float>(c), g));
    }
    return s * 2.0 / n * 2.0 * std::numbers::pi;
}

}  // namespace

// ∫ p dω = 1 for forward, isotropic and backward phases, to the rule's accuracy (the
// forward-peaked g = 0.95 is the hardest: 2·10⁻⁴ with 200 000 points).
TEST(Medium, HenyeyGreensteinIntegratesToOne) {
    for (float g : {0.0f, 0.3f, -0.6f, 0.8f, 0.95f}) EXPECT_NEAR(hg_integral(g), 1.0, 2e-4) << "g " << g;
    // the mean cosine is g
    for (float g : {0.3f, -0.6f, 0.8f}) {
        constexpr int n = 200000;
        double m = 0.0;
        for (int i = 0; i < n; ++i) {
            const double c = -1.0 + 2.0 * (i + 0.5) / n;
            m += c * static_cast<double>(iris::henyey_greenstein(static_cast<float>(c), g));
        }
        EXPECT_NEAR(m * 2.0 / n * 2.0 * std::numbers::pi, g, 2e-4) << "g " << g;
    }
}

// χ² (direction_fit.hpp) of the phase function's sampled directions against its value, for
// g ∈ {0, 0.5, −0.7, 0.9} and an oblique ωo (the sampler's frame is built around −ωo),
// 200 000 draws each; family of 4 at family-wise α = 0.01 (Šidák). The sample's f and pdf must
// both equal the value (f/p = 1, which the B term relies on). Negative control: g = 0.5's
// samples against g = 0.55's density are rejected at the same α'.
TEST(Medium, HenyeyGreensteinSamplesItsDensity) {
    const double alpha = iris::test::sidak(0.01, 4);
    const glm::vec3 wo = glm::normalize(glm::vec3(0.3f, -0.5f, 0.81f));
    const sampled_wavelengths<1> wl({550.0f}, {1.0f});
    std::uint64_t seed = 40;
    const auto fit = [&](float g, float g_claimed) {
        const iris::hg_phase p{g}, c{g_claimed};
        return iris::test::direction_fit(
            [&](glm::vec2 u) -> std::optional<glm::vec3> {
                const auto s = p.sample<1>(wo, wl, 0.0f, u, iris::sampled_spectra<1>{});
                if (!s) return std::nullopt;
                EXPECT_EQ(s->f_cos[0], s->pdf[0]);
                EXPECT_NEAR(s->pdf[0], p.value(wo, s->wi), 1e-4f * s->pdf[0]);
                return s->wi;
            },
            [&](const glm::vec3& wi) { return static_cast<double>(c.value(wo, wi)); }, ++seed);
    };
    for (float g : {0.0f, 0.5f, -0.7f, 0.9f}) {
        const auto r = fit(g, g);
        EXPECT_TRUE(r.impossible.empty()) << "g " << g << ": " << r.impossible;
        EXPECT_GT(r.p_value, alpha) << "g " << g << ": χ² " << r.statistic << " dof " << r.dof;
    }
    EXPECT_LT(fit(0.5f, 0.55f).p_value, alpha) << "g = 0.5's samples against g = 0.55's density must be rejected";
}

namespace {

constexpr std::size_t C = 4;
// a strongly chromatic medium: σ_s over a factor 20, σ_a uneven
constexpr std::array<float, C> sigma_s{0.2f, 1.0f, 2.5f, 4.0f};
constexpr std::array<float, C> sigma_a{0.3f, 0.0f, 0.5f, 0.1f};

/// \brief The coefficients with wavelength h as the hero (index 0), the others rotated after it.
iris::medium_coefficients<C> rotated(std::size_t h) {
    iris::medium_coefficients<C> m;
    for (std::size_t i = 0; i < C; ++i) {
        m.sigma_s[i] = sigma_s[(h + i) % C];
        m.sigma_a[i] = sigma_a[(h + i) % C];
    }
    m.scatters = true;
    return m;
}

}  // namespace

// A slab of thickness d = 0.8: each of the C wavelengths is the hero of a quarter of the
// flights (as hero rotation makes it); a flight that reaches the far side estimates every
// wavelength's transmittance T_j = e^{−σ_t,j d} by the spectral MIS, C β_j / Σ_k ρ_k, and by
// single-hero tracking, β_j. Both are unbiased; their variances have closed forms,
//   MIS: T_j² (C / Σ_k P_k − 1),   single: T_j² ((1/C) Σ_h 1/P_h − 1),   P_k = e^{−σ_s,k d},
// and the MIS's is the smaller (harmonic against arithmetic mean). 400 000 flights; the 4
// means of each estimator against T_j and the 8 variances against their closed forms at
// family-wise α = 0.001 (Šidák over 16; the variance's standard error from the fourth moment,
// normal approximation). Power: the MIS's variance is below single-hero's by far more than
// the threshold at every wavelength (asserted), and a transmittance wrong by 1 % is 5.6 to 38
// standard errors off (printed).
TEST(Medium, SpectralMisFlightThroughASlabIsUnbiasedWithTheClosedFormVariance) {
    const float d = 0.8f;
    constexpr int n = 400000;
    const double z = iris::test::normal_quantile_two_sided(iris::test::sidak(0.001, 16));
    std::array<double, C> p{}, t{};
    double p_sum = 0.0, inv_p_mean = 0.0;
    for (std::size_t k = 0; k < C; ++k) {
        p[k] = std::exp(-static_cast<double>(sigma_s[k]) * d);
        t[k] = std::exp(-static_cast<double>(sigma_s[k] + sigma_a[k]) * d);
        p_sum += p[k];
        inv_p_mean += 1.0 / p[k] / C;
    }
    std::array<std::array<double, 4>, C> mis{}, single{};  // Σx, Σx², Σx³, Σx⁴
    iris::counter_rng rng(77, 0);
    for (int i = 0; i < n; ++i) {
        const std::size_t h = static_cast<std::size_t>(i) % C;
        const auto fl = iris::medium_flight(rotated(h), d, rng.next());
        for (std::size_t j = 0; j < C; ++j) {
            double xm = 0.0, xs = 0.0;
            if (!fl.scattered) {
                const std::size_t r = (j + C - h) % C;  // wavelength j's place in the rotated flight
                xm = C * static_cast<double>(fl.beta[r]) / static_cast<double>(fl.ratio.sum());
                xs = static_cast<double>(fl.beta[r]);
            }
            for (int m = 0; m < 4; ++m) {
                mis[j][static_cast<std::size_t>(m)] += std::pow(xm, m + 1);
                single[j][static_cast<std::size_t>(m)] += std::pow(xs, m + 1);
            }
        }
    }
    for (std::size_t j = 0; j < C; ++j) {
        const double var_mis = t[j] * t[j] * (C / p_sum - 1.0), var_single = t[j] * t[j] * (inv_p_mean - 1.0);
        for (const auto& [name, sums, var] : {std::tuple{"mis", mis[j], var_mis}, std::tuple{"single", single[j], var_single}}) {
            const double mean = sums[0] / n, m2 = sums[1] / n, m3 = sums[2] / n, m4 = sums[3] / n;
            const double v = m2 - mean * mean;
            const double se_mean = std::sqrt(v / n);
            const double c4 = m4 - 4 * mean * m3 + 6 * mean * mean * m2 - 3 * std::pow(mean, 4);  // central 4th moment
            const double se_var = std::sqrt(std::max(0.0, c4 - v * v) / n);
            std::printf("λ%zu %-6s mean %.5f (T %.5f, z %+.2f; 1 %% = %.1f se)  var %.5f (closed form %.5f, z %+.2f)\n", j,
                        name, mean, t[j], (mean - t[j]) / se_mean, 0.01 * t[j] / se_mean, v, var, (v - var) / se_var);
            EXPECT_LE(std::fabs(mean - t[j]), z * se_mean) << name << " λ" << j;
            EXPECT_LE(std::fabs(v - var), z * se_var) << name << " λ" << j;
        }
        // power: the MIS's advantage is far beyond the noise of the variances
        EXPECT_LT(var_mis, var_single - 10.0 * z * t[j] * t[j] / std::sqrt(static_cast<double>(n))) << "λ" << j;
    }
}

// The density of the first scattering: flights of the same slab that scatter, binned in t
// (16 bins over [0, d]), estimate each wavelength's ∫_bin σ_s,j e^{−σ_t,j t} dt by the
// spectral MIS's C β_j / Σ_k ρ_k. 64 means (16 bins × 4 wavelengths) at family-wise
// α = 0.001 (Šidák), 1 600 000 flights. Power: an e^{−σ_t t} that used the hero's σ_a, or a
// ratio without σ_s,k/σ_s,0, is off by ≥ 5 % in most bins; the 90 %-detectable relative error
// of the bins' total is printed and asserted below 1 %.
TEST(Medium, SpectralMisFlightScattersWithEveryWavelengthsDensity) {
    const float d = 0.8f;
    constexpr int n = 1600000, bins = 16;
    const double z = iris::test::normal_quantile_two_sided(iris::test::sidak(0.001, bins * C));
    std::array<std::array<double, bins>, C> s1{}, s2{};
    iris::counter_rng rng(78, 0);
    for (int i = 0; i < n; ++i) {
        const std::size_t h = static_cast<std::size_t>(i) % C;
        const auto fl = iris::medium_flight(rotated(h), d, rng.next());
        if (!fl.scattered) continue;
        const auto b = static_cast<std::size_t>(std::min(bins - 1, static_cast<int>(fl.t / d * static_cast<float>(bins))));
        for (std::size_t j = 0; j < C; ++j) {
            const std::size_t r = (j + C - h) % C;
            const double x = C * static_cast<double>(fl.beta[r]) / static_cast<double>(fl.ratio.sum());
            s1[j][b] += x;
            s2[j][b] += x * x;
        }
    }
    for (std::size_t j = 0; j < C; ++j) {
        const double st = static_cast<double>(sigma_s[j] + sigma_a[j]), ss = sigma_s[j];
        double total = 0.0, total_var = 0.0, total_expected = 0.0;
        for (int b = 0; b < bins; ++b) {
            const double a = static_cast<double>(d) * b / bins, e = static_cast<double>(d) * (b + 1) / bins;
            const double expected = ss / st * (std::exp(-st * a) - std::exp(-st * e));
            const double mean = s1[j][static_cast<std::size_t>(b)] / n;
            const double var = s2[j][static_cast<std::size_t>(b)] / n - mean * mean;
            const double se = std::sqrt(var / n);
            EXPECT_LE(std::fabs(mean - expected), z * se) << "λ" << j << " bin " << b << ": " << mean << " vs " << expected;
            total += mean;
            total_var += var / n;  // (bins of one flight are exclusive: their covariance is −mean_a·mean_b/n, ignored: conservative)
            total_expected += expected;
        }
        const double detectable = (z + 1.2816) * std::sqrt(total_var) / total_expected;
        std::printf("λ%zu: scattered %.5f (closed form %.5f), detects %.2f %%\n", j, total, total_expected, 100.0 * detectable);
        EXPECT_LT(detectable, 0.01) << "the test has lost its power";
    }
}

// The flight's factors where the hero does not scatter at all (σ_s,0 = 0) and the ray escapes
// (t_max = ∞): finite, the others' ρ = 0 (they could not have flown through), β = 0 where
// there is absorption; and a hero that scatters never reaches ∞.
TEST(Medium, FlightToInfinityStaysFinite) {
    iris::medium_coefficients<C> m;
    m.sigma_s = sampled_spectrum<C>(std::array<float, C>{0.0f, 0.5f, 0.0f, 2.0f});
    m.sigma_a = sampled_spectrum<C>(std::array<float, C>{0.0f, 0.0f, 0.3f, 0.0f});
    m.scatters = true;
    const float inf = std::numeric_limits<float>::infinity();
    const auto fl = iris::medium_flight(m, inf, 0.7f);
    EXPECT_FALSE(fl.scattered);
    EXPECT_EQ(fl.hero_pass, 1.0f);
    EXPECT_EQ(fl.ratio[0], 1.0f);
    EXPECT_EQ(fl.ratio[1], 0.0f);
    EXPECT_EQ(fl.ratio[2], 1.0f);
    EXPECT_EQ(fl.beta[2], 0.0f);
    EXPECT_EQ(fl.beta[3], 0.0f);
    m.sigma_s[0] = 0.1f;
    for (float u : {0.0f, 0.5f, 0.99999994f}) {
        const auto f = iris::medium_flight(m, inf, u);
        EXPECT_TRUE(f.scattered) << u;
        EXPECT_TRUE(std::isfinite(f.t)) << u;
        for (std::size_t k = 0; k < C; ++k) EXPECT_TRUE(std::isfinite(f.beta[k]) && std::isfinite(f.ratio[k])) << u << " " << k;
    }
}

// The free flight's number is a slot of its own per bounce: it reads neither the bounce's
// five slots nor another bounce's flight, and drawing it does not move the bounce's slots.
TEST(Medium, FlightSlotsAreTheirOwn) {
    for (auto kind : {iris::sampler_kind::sobol, iris::sampler_kind::zsobol}) {
        const auto setup = iris::sampler_setup::make(kind, 5, 64);
        iris::sample_stream a(setup, 3, 4, 3 + 4 * 16, 7), b(setup, 3, 4, 3 + 4 * 16, 7);
        a.start_bounce(2);
        b.start_bounce(2);
        const float f2 = a.next_medium();
        EXPECT_EQ(a.slot(), b.slot()) << "the flight moved the bounce's slots";
        EXPECT_EQ(a.next(), b.next());
        a.start_bounce(3);
        EXPECT_NE(a.next_medium(), f2) << "two bounces' flights read one slot";
        EXPECT_NE(iris::sample_stream::medium_slot(2), iris::sample_stream::medium_slot(3));
        EXPECT_GT(iris::sample_stream::medium_slot(0), iris::sample_stream::first_bounce_slot + 5u * 100000u);
        EXPECT_LT(iris::sample_stream::medium_slot(100000), iris::sample_stream::overflow_slot(-1));
    }
}
