// The coated material (iris/render/materials/coated.hpp, docs/method.md §7) against what is
// known exactly about it: r_i against an independent quadrature, the white furnace of a
// smooth coat over a white base, the random walk against the closed form it estimates,
// reciprocity of the walk, the single mirror lobe of a coat over a smooth metal against a
// complex-arithmetic Fresnel, samples against eval and pdf, and a χ² of the sampled
// directions against the pdf.
//
// Statistical checks are z-tests with fixed seeds. The walk's estimates are averaged over
// directions that differ in their last bits (each seeds its own walk): `repeat` below.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include <iris/render/bsdf.hpp>
#include <iris/render/random.hpp>
#include <iris/spectrum/named.hpp>

#include "direction_fit.hpp"
#include "test_scenes.hpp"

namespace {

using iris::sampled_wavelengths;
using iris::test::flat;

constexpr double pi = std::numbers::pi;
const glm::vec3 up{0.0f, 0.0f, 1.0f};

glm::vec3 at(float c, float phi = 0.0f) {
    const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
    return {s * std::cos(phi), s * std::sin(phi), c};
}

/// Unpolarised Fresnel reflectance in double precision from the textbook form (s and p
/// amplitudes), index ratio n = n_t/n_i: the independent reference of these tests.
double fresnel_reference(double cos_i, double n) {
    const double sin2_t = (1.0 - cos_i * cos_i) / (n * n);
    if (sin2_t >= 1.0) return 1.0;
    const double cos_t = std::sqrt(1.0 - sin2_t);
    const double rs = (cos_i - n * cos_t) / (cos_i + n * cos_t), rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}
double conductor_reference(double cos_i, std::complex<double> n) {
    const double s2 = 1.0 - cos_i * cos_i;
    const std::complex<double> cos_t = std::sqrt(1.0 - s2 / (n * n));
    const std::complex<double> rs = (cos_i - n * cos_t) / (cos_i + n * cos_t), rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    return 0.5 * (std::norm(rs) + std::norm(rp));
}

iris::material::conductor gold(float alpha) {
    const auto au = iris::find_metal("Au");
    iris::material::conductor m{flat(0.5)};
    m.ior = iris::material::conductor_ior{"Au", au->eta_spectrum(), au->k_spectrum()};
    m.roughness = alpha;
    return m;
}

iris::material::coated coated(iris::material::coated c) {
    c.internal_reflectance = iris::coated_internal_reflectance(c.eta, c.thickness);
    return c;
}

struct mean_sd {
    double mean = 0.0, se = 0.0;  ///< the mean and its standard error
};
/// Mean of f(ωo, ωi′) over `n` copies of ωi that differ in their last bits (each a new walk).
template <class F>
mean_sd repeat(F&& f, int n, glm::vec3 wi) {
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; ++i) {
        glm::vec3 w = wi;
        w.x = std::nextafter(w.x, 2.0f);
        w.y += 1e-8f * static_cast<float>(i);
        wi = w;
        const double v = f(w);
        s += v;
        s2 += v * v;
    }
    const double m = s / n;
    return {m, std::sqrt(std::max(0.0, s2 / n - m * m) / (n - 1))};
}

// A family of z-tests at 4σ: each fails by chance with p = 6.3e-5.
constexpr double z4 = 4.0;

TEST(Coated, InternalReflectanceIsTheHemisphericalMean) {
    for (double eta : {1.33, 1.5, 2.4})
        for (double tau : {0.0, 0.05, 0.5}) {
            // the definition, by the midpoint rule on 2·10⁶ points with the reference Fresnel
            const int n = 2000000;
            double sum = 0.0;
            for (int i = 0; i < n; ++i) {
                const double c = (i + 0.5) / n;
                sum += 2.0 * c * fresnel_reference(c, 1.0 / eta) * (tau > 0.0 ? std::exp(-2.0 * tau / c) : 1.0);
            }
            EXPECT_NEAR(iris::coated_internal_reflectance(static_cast<float>(eta), static_cast<float>(tau)), sum / n, 2e-6)
                << "η " << eta << " τ " << tau;
        }
    // without absorption, reciprocity ties it to the external mean: 1 − r_i = (1 − r_e)/η²
    for (double eta : {1.33, 1.5, 2.4}) {
        const int n = 2000000;
        double re = 0.0;
        for (int i = 0; i < n; ++i) {
            const double c = (i + 0.5) / n;
            re += 2.0 * c * fresnel_reference(c, eta) / n;
        }
        EXPECT_NEAR(iris::coated_internal_reflectance(static_cast<float>(eta), 0.0f), 1.0 - (1.0 - re) / (eta * eta), 2e-6);
    }
    EXPECT_EQ(iris::coated_internal_reflectance(1.0f, 0.1f), 0.0f);
}

// Albedo of the non-delta part over a 400 × 400 grid in (cos θ, φ): the midpoint rule
// without `jitter` (the closed form is smooth), else one jittered point per cell, with the
// standard error of the cells taken as independent (an overestimate for stratified points).
mean_sd albedo_by_quadrature(const iris::material_desc& m, const glm::vec3& wo, const sampled_wavelengths<1>& wl,
                             iris::sample_stream* jitter = nullptr) {
    const int n = 400;
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const glm::vec2 u = jitter ? jitter->next2() : glm::vec2(0.5f);
            const double z = (i + static_cast<double>(u.x)) / n, phi = 2.0 * pi * (j + static_cast<double>(u.y)) / n,
                         r = std::sqrt(1.0 - z * z);
            const glm::vec3 wi(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)), static_cast<float>(z));
            const double v = iris::bsdf_eval(m, up, wo, wi, wl)[0] * 2.0 * pi;
            sum += v;
            sum2 += v * v;
        }
    const double cells = static_cast<double>(n) * n, mean = sum / cells;
    return {mean, std::sqrt(std::max(0.0, sum2 / cells - mean * mean) / (cells - 1.0))};
}

TEST(Coated, SmoothCoatOverAWhiteBaseIsAWhiteFurnace) {
    // ρ = 1, no absorption, the series run to 50 visits ((ρ r_i)⁵⁰ < 10⁻¹¹): every photon leaves, at every angle
    iris::material::coated c{iris::material::diffuse{flat(1.0)}};
    c.thickness = 0.0f;
    c.max_depth = 99;
    const iris::material_desc lossless = coated(c);
    c.thickness = 0.1f;
    const iris::material_desc absorbing = coated(c);
    const sampled_wavelengths<1> wl({550.0f}, {1.0f});
    for (float co : {1.0f, 0.7f, 0.3f, 0.05f}) {
        const glm::vec3 wo = at(co);
        const double f = fresnel_reference(co, 1.5);
        EXPECT_NEAR(f + albedo_by_quadrature(lossless, wo, wl).mean, 1.0, 1e-4) << "cos θo " << co;
        EXPECT_LT(f + albedo_by_quadrature(absorbing, wo, wl).mean, 0.99) << "cos θo " << co;
    }
}

TEST(Coated, WalkConvergesToTheClosedForm) {
    // The closed form of a smooth coat over a diffuse base is what the layered walk estimates
    // (docs/method.md §7); the walk is run on that case directly. 2 depths × 3 pairs × 3
    // wavelengths = 18 z-tests at 4σ: family-wise false alarm 1.1e-3. Power: the standard
    // errors are ≤ 0.05 % of the value, so a 0.5 % error is rejected with probability ≈ 1;
    // the negative control (r_i off by 2 %) must be.
    const sampled_wavelengths<3> wl({450.0f, 550.0f, 650.0f}, {1.0f, 1.0f, 1.0f});
    iris::sampled_spectrum<3> rho;
    rho[0] = 0.2f;
    rho[1] = 0.6f;
    rho[2] = 0.95f;
    const auto spectra = iris::sampled_spectra<3>::with_albedo(rho);
    for (int depth : {10, 31}) {
        iris::material::coated c{iris::material::diffuse{flat(0.5)}};
        c.thickness = 0.1f;
        c.max_depth = depth;
        c.samples = 8;
        c = coated(c);
        const iris::coated_bxdf b{c};
        iris::material::coated wrong = c;
        wrong.internal_reflectance *= 1.02f;
        const iris::coated_bxdf bw{wrong};
        for (auto [co, ci] : {std::pair{0.9f, 0.8f}, {0.3f, 0.95f}, {0.95f, 0.1f}}) {
            const glm::vec3 wo = at(co), wi = at(ci, 2.0f);
            const auto exact = b.diffuse_closed_form<3>(wo, wi, spectra), off = bw.diffuse_closed_form<3>(wo, wi, spectra);
            for (std::size_t k = 0; k < 3; ++k) {
                const mean_sd w = repeat([&](const glm::vec3& x) { return b.walk<3>(wo, x, spectra)[k]; }, 3000, wi);
                EXPECT_NEAR(w.mean, exact[k], z4 * w.se) << "depth " << depth << " cos " << co << "," << ci << " ρ " << rho[k];
                if (depth == 31 && k == 2) {  // the multiple bounces matter most at ρ = 0.95
                    EXPECT_GT(std::fabs(w.mean - off[k]), z4 * w.se) << "negative control: r_i × 1.02 must be rejected";
                }
            }
        }
    }
}

TEST(Coated, IsReciprocal) {
    // f(a, b) = f(b, a) for the estimates of the rough coat (over diffuse and over rough
    // gold) and of the smooth coat over rough gold: entering and leaving use the two
    // transport modes (the 1/η′² of the coat), and the walk's two connections weigh the same
    // densities. 3 materials × 3 pairs = 9 z-tests at 4σ (family-wise 5.7e-4).
    const sampled_wavelengths<1> wl({600.0f}, {1.0f});
    std::vector<iris::material::coated> ms;
    {
        iris::material::coated c{iris::material::diffuse{flat(0.5)}};
        c.roughness = 0.2f;
        ms.push_back(coated(c));
        c.base = gold(0.1f);
        ms.push_back(coated(c));
        c.roughness = 0.0f;
        ms.push_back(coated(c));
    }
    for (auto& c : ms) c.samples = 8;
    for (const auto& c : ms) {
        const iris::coated_bxdf b{c};
        const auto s = iris::scene_spectra(b, wl);
        for (auto [ca, cb] : {std::pair{0.9f, 0.8f}, {0.3f, 0.9f}, {0.95f, 0.2f}}) {
            const glm::vec3 a = at(ca), bb = at(cb, 2.5f);
            const mean_sd ab = repeat([&](const glm::vec3& x) { return b.f_cos<1>(a, x, s)[0] / x.z; }, 4000, bb);
            const mean_sd ba = repeat([&](const glm::vec3& x) { return b.f_cos<1>(x, a, s)[0] / a.z; }, 4000, bb);
            EXPECT_NEAR(ab.mean, ba.mean, z4 * std::hypot(ab.se, ba.se))
                << "roughness " << c.roughness << " base " << c.base.index() << " cos " << ca << "," << cb;
        }
    }
}

TEST(Coated, AlbedoMatchesAnAnalogSimulationOfTheLayer) {
    // An independent estimator of what the walk computes: follow light through the layer as
    // it goes, with the rough dielectric and the base's own BxDFs (each tested in
    // bsdf_test.cpp) — no connections, no MIS, no virtual light — and count what leaves
    // after at most K visits of the base. Its mean is the directional albedo, which the
    // walk's f integrated over the hemisphere (jittered grid) must match. Rough coats over
    // diffuse and over rough gold, a smooth coat over rough gold (its mirror's F added):
    // 3 × 2 z-tests at 4σ. Measured power: a walk weighing its exit connection with the
    // coat's density of ωi (pbrt-v4's weights) is 6–12 % too bright here, 16–22σ.
    const sampled_wavelengths<1> wl({600.0f}, {1.0f});
    const auto au = iris::find_metal("Au");
    iris::material::conductor relative = gold(0.2f);  // gold's index relative to the coat
    relative.ior->eta = au->eta_spectrum().scaled(1.0 / 1.5);
    relative.ior->k = au->k_spectrum().scaled(1.0 / 1.5);
    iris::sample_stream rng(11, 12, 13), jitter(14, 15, 16);
    for (int which = 0; which < 3; ++which) {
        iris::material::coated c{iris::material::diffuse{flat(0.5)}};
        iris::material_desc base = iris::material::diffuse{flat(0.5)};
        if (which >= 1) {
            c.base = gold(0.2f);
            base = relative;
        }
        c.roughness = which == 2 ? 0.0f : 0.3f;
        c.thickness = 0.05f;
        const iris::material_desc m = coated(c);
        const iris::material_desc coat = iris::material::dielectric{iris::constant_ior{1.5}, c.roughness};
        const int visits = (c.max_depth + 1) / 2;
        const auto tr = [&](const glm::vec3& d) { return std::exp(-static_cast<double>(c.thickness) / std::fabs(d.z)); };
        for (float co : {0.9f, 0.4f}) {
            const glm::vec3 wo = at(co);
            double sum = 0.0, sum2 = 0.0;
            const int n = 400000;
            for (int i = 0; i < n; ++i) {
                double w = 1.0, out = 0.0;
                const auto t = iris::bsdf_sample_hero(coat, up, wo, wl, rng.next(), rng.next2());
                if (!t) continue;
                w *= t->f_cos[0] / t->pdf[0];
                if (t->kind == iris::lobe::reflection) out = w;
                else {
                    glm::vec3 d = t->wi;  // down into the layer
                    for (int k = 0; k < visits; ++k) {
                        w *= tr(d);
                        const auto b = iris::bsdf_sample_hero(base, up, -d, wl, rng.next(), rng.next2());
                        if (!b) break;
                        w *= b->f_cos[0] / b->pdf[0];
                        d = b->wi;  // up
                        w *= tr(d);
                        const auto u = iris::bsdf_sample_hero(coat, up, -d, wl, rng.next(), rng.next2());
                        if (!u) break;
                        w *= u->f_cos[0] / u->pdf[0];
                        if (u->kind == iris::lobe::transmission) {
                            out = w;
                            break;
                        }
                        d = u->wi;  // back down
                    }
                }
                sum += out;
                sum2 += out * out;
            }
            const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1));
            const double mirror = c.roughness == 0.0f ? fresnel_reference(co, 1.5) : 0.0;
            const mean_sd q = albedo_by_quadrature(m, wo, wl, &jitter);
            EXPECT_NEAR(mean, mirror + q.mean, z4 * std::hypot(se, q.se)) << "case " << which << " cos θo " << co;
        }
    }
}

TEST(Coated, SmoothCoatOverSmoothMetalIsOneMirror) {
    // All light leaves along the mirror direction: R = F + (1 − F)² Σ_{n<K} (T² F_c)ⁿ⁺¹ Fⁿ,
    // F_c at the refracted angle with gold's index relative to the coat — here from complex
    // arithmetic, term by term.
    iris::material::coated c{gold(0.0f)};
    c.thickness = 0.05f;
    c = coated(c);
    const iris::material_desc m = c;
    const sampled_wavelengths<2> wl({450.0f, 650.0f}, {1.0f, 1.0f});
    const auto au = iris::find_metal("Au");
    iris::sample_stream rng(3, 1, 4);
    for (float co : {0.95f, 0.5f, 0.1f}) {
        const glm::vec3 wo = at(co, 0.7f);
        const auto s = iris::bsdf_sample_hero(m, up, wo, wl, rng.next(), rng.next2());
        ASSERT_TRUE(s && s->delta);
        EXPECT_NEAR(s->wi.x, -wo.x, 1e-6f);
        EXPECT_NEAR(s->wi.z, wo.z, 1e-6f);
        EXPECT_EQ(s->pdf[0], 1.0f);
        const double f = fresnel_reference(co, 1.5), ci = std::sqrt(1.0 - (1.0 - co * co) / 2.25);
        const double t2 = std::exp(-2.0 * 0.05 / ci);
        for (std::size_t k = 0; k < 2; ++k) {
            const double l = wl[k];
            const double fc = conductor_reference(ci, std::complex<double>(au->eta_spectrum()(l), au->k_spectrum()(l)) / 1.5);
            double r = f;
            for (int n = 0; n < 5; ++n) r += (1.0 - f) * (1.0 - f) * std::pow(t2 * fc, n + 1) * std::pow(f, n);
            EXPECT_NEAR(s->f_cos[k], r, 2e-5 * (1.0 + r)) << "cos " << co << " λ " << l;
        }
        EXPECT_EQ(iris::bsdf_eval(m, up, wo, at(0.5f, 1.0f), wl)[0], 0.0f);  // no non-delta part
    }
}

TEST(Coated, TwoSidedAndOpaque) {
    iris::material::coated c{gold(0.2f)};
    c.roughness = 0.1f;
    const iris::material_desc m = coated(c);
    const sampled_wavelengths<1> wl({550.0f}, {1.0f});
    const glm::vec3 a = at(0.6f), b = at(0.8f, 2.0f);
    const glm::vec3 a_below{a.x, a.y, -a.z}, b_below{b.x, b.y, -b.z};
    EXPECT_EQ(iris::bsdf_eval(m, up, a_below, b_below, wl)[0], iris::bsdf_eval(m, up, a, b, wl)[0]);
    EXPECT_EQ(iris::bsdf_pdf(m, up, a_below, b_below, wl)[0], iris::bsdf_pdf(m, up, a, b, wl)[0]);
    EXPECT_EQ(iris::bsdf_eval(m, up, a, b_below, wl)[0], 0.0f);
    EXPECT_EQ(iris::bsdf_pdf(m, up, a, b_below, wl)[0], 0.0f);
    EXPECT_GT(iris::bsdf_eval(m, up, a, b, wl)[0], 0.0f);
}

std::vector<iris::material_desc> all_cases() {
    std::vector<iris::material_desc> out;
    for (float coat : {0.0f, 0.15f})
        for (int base = 0; base < 3; ++base) {
            iris::material::coated c{iris::material::diffuse{flat(0.7)}};
            if (base == 1) c.base = gold(0.2f);
            if (base == 2) c.base = gold(0.0f);
            c.roughness = coat;
            c.thickness = 0.02f;
            out.emplace_back(std::in_place_type<iris::material::coated>, coated(c));
        }
    return out;
}

TEST(Coated, SamplesAreWhatEvalAndPdfSay) {
    // Every non-delta sample reports eval's value and pdf's density for its direction (one
    // walk, seeded by the directions); delta samples are the mirror. The mean weight
    // f·|cos|/p of 10⁵ samples equals the mirror's weight plus the quadrature albedo of eval:
    // 6 materials × 2 angles = 12 z-tests at 4σ on the two estimates' difference (family-wise
    // 7.6e-4).
    const sampled_wavelengths<1> wl({550.0f}, {1.0f});
    iris::sample_stream rng(5, 6, 7), jitter(8, 9, 10);
    int material_index = 0;
    for (const auto& m : all_cases()) {
        ++material_index;
        for (float co : {0.85f, 0.35f}) {
            const glm::vec3 wo = at(co, 0.3f);
            // the mirror lobe's weight: a smooth coat's sample at u_lobe = 0 is its mirror
            const auto s0 = iris::bsdf_sample_hero(m, up, wo, wl, 0.0f, {0.5f, 0.5f});
            const double mirror = s0 && s0->delta ? s0->f_cos[0] : 0.0;
            // in the BxDF's own frame: the walk is seeded by the directions' bits
            const iris::coated_bxdf bxdf{std::get<iris::material::coated>(m)};
            const auto spectra = iris::scene_spectra(bxdf, wl);
            double sum = 0.0, sum2 = 0.0;
            const int n = 100000;
            for (int i = 0; i < n; ++i) {
                const float u_lobe = rng.next();
                const auto s = bxdf.sample<1>(wo, wl, u_lobe, rng.next2(), spectra);
                if (!s) continue;
                const double w = s->f_cos[0] / s->pdf[0];
                sum += w;
                sum2 += w * w;
                if (s->delta) {
                    ASSERT_EQ(s->kind, iris::lobe::reflection);
                    ASSERT_NEAR(s->wi.x, -wo.x, 1e-6f);
                    continue;
                }
                ASSERT_GT(s->wi.z, 0.0f);
                ASSERT_EQ(bxdf.eval<1>(wo, s->wi, spectra).f_cos[0], s->f_cos[0]) << material_index;
                ASSERT_EQ(bxdf.pdf<1>(wo, s->wi, spectra)[0], s->pdf[0]) << material_index;
            }
            const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1));
            const mean_sd q = albedo_by_quadrature(m, wo, wl, &jitter);
            EXPECT_NEAR(mean, mirror + q.mean, z4 * std::hypot(se, q.se)) << "material " << material_index << " cos θo " << co;
        }
    }
}

}  // namespace

// χ² (direction_fit.hpp) of the non-delta directions each coated material samples against
// the pdf it claims (its delta samples count as failures, expected draws·(1 − ∫pdf)): 6
// materials × 2 angles = 12 fits at family-wise α = 0.01 (Šidák α' ≈ 8.4e-4). Negative
// control: the rough coat over diffuse against the pdf of a coat twice as rough.
TEST(Coated, SamplesItsPdf) {
    const double alpha = iris::test::sidak(0.01, 12);
    const sampled_wavelengths<1> wl({550.0f}, {1.0f});
    const auto fit = [&](const iris::material_desc& m, const iris::material_desc& claimed, const glm::vec3& wo,
                         std::uint64_t seed) {
        iris::counter_rng lobe_rng(seed, 1);
        iris::test::direction_grid g;
        g.z_bands = 32;
        g.phi_sectors = 64;
        g.sub_z = 16;
        g.sub_phi = 4;
        return iris::test::direction_fit(
            [&](glm::vec2 u) -> std::optional<glm::vec3> {
                const auto s = iris::bsdf_sample_hero(m, up, wo, wl, lobe_rng.next(), u);
                if (!s || s->delta) return std::nullopt;
                return s->wi;
            },
            [&](const glm::vec3& wi) { return static_cast<double>(iris::bsdf_pdf(claimed, up, wo, wi, wl)[0]); }, seed, g);
    };
    std::uint64_t seed = 40;
    for (const auto& m : all_cases())
        for (float co : {0.9f, 0.3f}) {
            const auto r = fit(m, m, at(co, 1.0f), ++seed);
            EXPECT_TRUE(r.impossible.empty()) << r.impossible;
            EXPECT_GT(r.p_value, alpha) << "cos θo " << co << ": χ² " << r.statistic << " dof " << r.dof;
        }
    iris::material::coated a{iris::material::diffuse{flat(0.7)}}, b = a;
    a.roughness = 0.15f;
    b.roughness = 0.3f;
    const auto bad = fit(coated(a), coated(b), at(0.6f), 99);
    EXPECT_LT(bad.p_value, alpha) << "a coat of α 0.15 against the pdf of α 0.3 must be rejected";
}
