// BSDF sampling consistency: for every material, E[f·|cos| / pdf] over sampled directions
// equals the albedo computed by quadrature of bsdf_eval, and pdf() agrees with sample().
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>

#include <iris/render/bsdf.hpp>
#include <iris/render/random.hpp>
#include <iris/spectrum/named.hpp>

#include "test_scenes.hpp"

namespace {

using iris::sampled_wavelengths;

const glm::vec3 n{0.0f, 0.0f, 1.0f};

TEST(Bsdf, DiffuseSamplingIsConsistentWithEvalAndPdf) {
    const iris::material_desc m = iris::material::diffuse{iris::test::flat(0.6)};
    const glm::vec3 wo = glm::normalize(glm::vec3(0.3f, -0.2f, 0.9f));
    const sampled_wavelengths<2> wl({500.0f, 600.0f}, {1.0f, 1.0f});
    iris::sample_stream rng(1, 2, 3);
    double sum = 0.0;
    constexpr int n_samples = 20000;
    for (int i = 0; i < n_samples; ++i) {
        const auto s = iris::bsdf_sample_hero(m, n, wo, wl, rng.next(), rng.next2());
        ASSERT_TRUE(s.has_value());
        const auto f = iris::bsdf_eval(m, n, wo, s->wi, wl);
        const auto p = iris::bsdf_pdf(m, n, wo, s->wi, wl);
        EXPECT_NEAR(f[0], s->f_cos[0], 1e-5f);
        EXPECT_NEAR(p[0], s->pdf[0], 1e-5f);
        sum += static_cast<double>(s->f_cos[0] / s->pdf[0]);
    }
    EXPECT_NEAR(sum / n_samples, 0.6, 1e-5);  // f cos / pdf is exactly the albedo for a Lambertian
}

TEST(Bsdf, SmoothDielectricConservesEnergyAndTerminatesSecondaries) {
    const iris::material_desc glass = iris::material::dielectric{iris::sellmeier_ior{1.03961212, 0.231792344, 1.01046945,
                                                                                     0.00600069867, 0.0200179144, 103.560653},
                                                               0.0f};
    const glm::vec3 wo = glm::normalize(glm::vec3(0.5f, 0.0f, 0.8f));
    const sampled_wavelengths<4> wl({450.0f, 520.0f, 590.0f, 660.0f}, {1, 1, 1, 1});
    iris::sample_stream rng(9, 9, 9);
    int refracted = 0;
    for (int i = 0; i < 2000; ++i) {
        const auto s = iris::bsdf_sample_hero(glass, n, wo, wl, rng.next(), rng.next2());
        ASSERT_TRUE(s.has_value());
        ASSERT_TRUE(s->delta);
        if (s->kind == iris::lobe::transmission) {
            ++refracted;
            for (std::size_t k = 1; k < 4; ++k) {
                EXPECT_EQ(s->pdf[k], 0.0f);
                EXPECT_EQ(s->f_cos[k], 0.0f);
            }
            EXPECT_LT(s->wi.z, 0.0f);
        } else {
            for (std::size_t k = 0; k < 4; ++k) EXPECT_GT(s->pdf[k], 0.0f);  // reflection keeps all λ
        }
    }
    EXPECT_GT(refracted, 1500);  // F ≈ 0.05 at this angle
}

// Fresnel reflectance of a dielectric in double precision (the textbook s/p form, as
// detail::fresnel_dielectric computes it in float): the reference for the B term's form.
double fresnel_reference(double cos_i, double eta) {
    if (cos_i < 0.0) {
        eta = 1.0 / eta;
        cos_i = -cos_i;
    }
    const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0) return 1.0;
    const double cos_t = std::sqrt(1.0 - sin2_t);
    const double r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const double r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5 * (r_parl * r_parl + r_perp * r_perp);
}

// The B term's weight at a delta event, computed for all bins at once in another form of
// the Fresnel equations (one square root and one division per wavelength), must be the
// Fresnel weight: F(λ) for reflection and (1 − F(λ))/η_t² for transmission, from either
// side, through total internal reflection, at normal and grazing incidence and for η = 1
// (float rounding against a double reference; near grazing at η = 1 the scalar float
// fresnel_dielectric itself is off by 1e-5, so it cannot be the reference).
TEST(Bsdf, DeltaWeightAtTheBinsIsTheScalarFresnel) {
    constexpr std::size_t M = 24;
    std::array<float, M> lambdas{}, ones{};
    std::array<float, M> etas{};
    for (std::size_t k = 0; k < M; ++k) {
        lambdas[k] = 380.0f + 400.0f * (static_cast<float>(k) + 0.5f) / M;
        ones[k] = 1.0f;
        etas[k] = k == 0 ? 1.0f : (k == 1 ? 4.0f : 1.3f + 0.05f * static_cast<float>(k));
    }
    const sampled_wavelengths<M> wl(lambdas, ones);
    const iris::sampled_spectrum<M> eta(etas);
    const iris::material_desc glass = iris::material::dielectric{iris::constant_ior{1.5}, 0.0f};
    int tir = 0;
    for (float co : {1.0f, 0.9f, 0.5f, 0.2f, 1e-3f, 0.0f, -1e-3f, -0.2f, -0.5f, -0.9f, -1.0f}) {
        const float s = std::sqrt(std::max(0.0f, 1.0f - co * co));
        const glm::vec3 wo(s, 0.0f, co);
        for (auto kind : {iris::lobe::reflection, iris::lobe::transmission}) {
            const auto w = iris::smooth_dielectric{std::get<iris::material::dielectric>(glass)}.follow<M>(
                wo, wo, kind, iris::sampled_spectra<M>::with_eta(eta));
            for (std::size_t k = 0; k < M; ++k) {
                const double f = fresnel_reference(co, etas[k]);
                const double et = co > 0.0f ? etas[k] : 1.0 / etas[k];
                const double expected = kind == iris::lobe::reflection ? f : (1.0 - f) / (et * et);
                if (f == 1.0) ++tir;
                EXPECT_NEAR(w[k], expected, 4e-6 * std::max(1.0, expected))
                    << "cos " << co << " eta " << etas[k] << (kind == iris::lobe::reflection ? " R" : " T");
            }
        }
    }
    EXPECT_GT(tir, 0);  // total internal reflection was exercised
}

TEST(Bsdf, RoughDielectricPdfIntegratesToAtMostOneAndMatchesSampling) {
    const iris::material_desc rough = iris::material::dielectric{iris::cauchy_ior{1.5, 0.02}, 0.3f};
    const glm::vec3 wo = glm::normalize(glm::vec3(0.4f, 0.1f, 0.7f));
    const sampled_wavelengths<2> wl({450.0f, 650.0f}, {1, 1});
    // ∫ pdf dω over the sphere by stratified quadrature in (cos θ, φ): ≤ 1, ≈ 1 minus
    // the mass of rejected (shadowed) samples
    constexpr int nt = 400, np = 400;
    double mass = 0.0;
    for (int i = 0; i < nt; ++i)
        for (int j = 0; j < np; ++j) {
            const float z = -1.0f + 2.0f * (static_cast<float>(i) + 0.5f) / nt;
            const float phi = 2.0f * std::numbers::pi_v<float> * (static_cast<float>(j) + 0.5f) / np;
            const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
            const glm::vec3 wi{r * std::cos(phi), r * std::sin(phi), z};
            mass += iris::bsdf_pdf(rough, n, wo, wi, wl)[0] * (2.0 / nt) * (2.0 * std::numbers::pi / np);
        }
    EXPECT_LE(mass, 1.01);
    EXPECT_GT(mass, 0.9);
    iris::sample_stream rng(4, 5, 6);
    for (int i = 0; i < 500; ++i) {
        const auto s = iris::bsdf_sample_hero(rough, n, wo, wl, rng.next(), rng.next2());
        if (!s) continue;
        const auto p = iris::bsdf_pdf(rough, n, wo, s->wi, wl);
        const auto f = iris::bsdf_eval(rough, n, wo, s->wi, wl);
        EXPECT_NEAR(p[0], s->pdf[0], 1e-3f * (1.0f + p[0]));
        EXPECT_NEAR(p[1], s->pdf[1], 1e-3f * (1.0f + p[1]));  // secondary pdf at the hero's direction
        EXPECT_NEAR(f[1], s->f_cos[1], 1e-3f * (1.0f + f[1]));
    }
}

}  // namespace

// Fresnel against closed forms, for the hero (fresnel_dielectric and what a sample reports)
// and for the bins (smooth_dielectric::follow): at normal incidence R = ((n − 1)/(n + 1))² from
// either side; at Brewster's angle R_p = 0, so the unpolarised R is R_s/2 =
// ((n² − 1)/(n² + 1))²/2 from outside (tan θ = n) and from inside (tan θ = 1/n); past the
// critical angle from inside (sin θ > 1/n) R = 1. A Fresnel scaled by 1.05 with T = 1 − R
// still conserves energy; these values catch it.
TEST(Bsdf, FresnelMatchesClosedFormsForTheHeroAndTheBins) {
    constexpr std::size_t M = 3;
    const sampled_wavelengths<M> wl({450.0f, 550.0f, 650.0f}, {1.0f, 1.0f, 1.0f});
    for (double nd : {1.2, 1.33, 1.5168, 1.9, 2.4, 4.0}) {
        const auto ni = static_cast<float>(nd);
        const iris::material_desc glass = iris::material::dielectric{iris::constant_ior{nd}, 0.0f};
        const double normal = std::pow((nd - 1.0) / (nd + 1.0), 2.0);
        const double brewster = 0.5 * std::pow((nd * nd - 1.0) / (nd * nd + 1.0), 2.0);
        struct incidence {
            double cos_theta;  // signed: < 0 from inside
            double r;
            const char* what;
        };
        const double critical = std::asin(1.0 / nd);
        const incidence cases[] = {
            {1.0, normal, "normal, outside"},
            {-1.0, normal, "normal, inside"},
            {std::cos(std::atan(nd)), brewster, "Brewster, outside"},
            {-std::cos(std::atan(1.0 / nd)), brewster, "Brewster, inside"},
            {-std::cos(critical + 0.02), 1.0, "past the critical angle"},
            {-std::cos(0.5 * (std::numbers::pi / 2 + critical)), 1.0, "far past the critical angle"},
        };
        for (const auto& c : cases) {
            const auto co = static_cast<float>(c.cos_theta);
            const double tol = 2e-5 * std::max(c.r, 1e-2);
            EXPECT_NEAR(iris::detail::fresnel_dielectric(co, ni), c.r, tol) << c.what << ", n = " << nd;
            const float s = std::sqrt(std::max(0.0f, 1.0f - co * co));
            const glm::vec3 wo(s, 0.0f, co);
            // the hero's sample: u_lobe = 0 always reflects, and reports F at every wavelength
            const auto hs = iris::bsdf_sample_hero(glass, n, wo, wl, 0.0f, {0.5f, 0.5f});
            ASSERT_TRUE(hs.has_value());
            ASSERT_EQ(hs->kind, iris::lobe::reflection);
            for (std::size_t k = 0; k < M; ++k) {
                EXPECT_NEAR(hs->f_cos[k], c.r, tol) << c.what << ", n = " << nd << ", hero sample";
                EXPECT_NEAR(hs->pdf[k], c.r, tol) << c.what << ", n = " << nd << ", hero sample pdf";
            }
            // the bins: reflection F, transmission (1 − F)/η′² (η′ the index seen from ωo's side)
            const iris::sampled_spectrum<M> eta(ni);
            const iris::smooth_dielectric bxdf{std::get<iris::material::dielectric>(glass)};
            const auto spectra = iris::sampled_spectra<M>::with_eta(eta);
            const auto rb = bxdf.follow<M>(wo, wo, iris::lobe::reflection, spectra);
            const auto tb = bxdf.follow<M>(wo, wo, iris::lobe::transmission, spectra);
            const double et = c.cos_theta > 0.0 ? nd : 1.0 / nd;
            for (std::size_t k = 0; k < M; ++k) {
                EXPECT_NEAR(rb[k], c.r, tol) << c.what << ", n = " << nd << ", bins";
                const double t = (1.0 - c.r) / (et * et);
                EXPECT_NEAR(tb[k], t, 2e-5 * std::max(t, 1e-2)) << c.what << ", n = " << nd << ", bins T";
            }
        }
    }
}

namespace {
/// Conductor Fresnel from the complex amplitudes (independent of iris's real form).
double complex_conductor_fresnel(double c, double eta, double k) {
    const std::complex<double> n(eta, k);
    const std::complex<double> ct = std::sqrt(1.0 - (1.0 - c * c) / (n * n));
    const std::complex<double> rs = (c - n * ct) / (c + n * ct), rp = (n * c - ct) / (n * c + ct);
    return 0.5 * (std::norm(rs) + std::norm(rp));
}
}  // namespace

// The conductor Fresnel against the complex-amplitude formula over angles and indices
// (metals, a near-dielectric k = 0, and k → ∞, which reflects everything), and the named
// metals against their reflectance at normal incidence computed from the data files'
// rows (data/README.md: R = ((n − 1)² + k²)/((n + 1)² + k²) at the row nearest 550 nm).
TEST(Bsdf, ConductorFresnelIsExact) {
    for (const auto [eta, k] : {std::pair{0.2, 3.0}, std::pair{0.05, 3.6}, std::pair{1.2, 7.0}, std::pair{2.5, 0.0},
                                std::pair{1.5, 0.01}, std::pair{0.9, 1e-3}, std::pair{3.0, 30.0}}) {
        for (double c = 0.0; c <= 1.0; c += 1.0 / 64.0) {
            const double want = complex_conductor_fresnel(c, eta, k);
            EXPECT_NEAR(iris::detail::fresnel_conductor(static_cast<float>(c), static_cast<float>(eta), static_cast<float>(k)),
                        want, 2e-5 + 2e-5 * want)
                << "eta " << eta << " k " << k << " cos " << c;
        }
    }
    for (double c : {0.0, 1e-4, 0.3, 0.7, 1.0}) {
        EXPECT_NEAR(iris::detail::fresnel_conductor(static_cast<float>(c), 1.0f, 1e4f), 1.0, 1e-6) << c;
        EXPECT_NEAR(iris::detail::fresnel_conductor(static_cast<float>(c), 0.5f, 1e6f), 1.0, 1e-6) << c;
    }
    const struct {
        const char* metal;
        double lambda, r0;
    } rows[] = {{"Ag", 548.6, 0.9828}, {"Al", 563.57, 0.9147}, {"Au", 548.6, 0.7869}, {"Cu", 548.6, 0.6195}, {"CuZn", 550.0, 0.7887}};
    for (const auto& r : rows) {
        const auto m = iris::find_metal(r.metal);
        ASSERT_TRUE(m.has_value()) << r.metal;
        const auto f = iris::detail::fresnel_conductor(1.0f, static_cast<float>(m->eta_spectrum()(r.lambda)),
                                                       static_cast<float>(m->k_spectrum()(r.lambda)));
        EXPECT_NEAR(f, r.r0, 1e-4) << r.metal;
    }
    EXPECT_FALSE(iris::find_metal("gold").has_value());
}

// A smooth conductor with an index reflects with F(|cos θo|, η_k, k_k) at each wavelength,
// for the hero's sample and for the bins alike; without an index, with its reflectance.
TEST(Bsdf, SmoothConductorWeightsAreFresnel) {
    constexpr std::size_t M = 4;
    const auto au = iris::find_metal("Au");
    ASSERT_TRUE(au.has_value());
    iris::material::conductor gold{iris::tabulated_spectrum({360.0, 830.0}, {0.5, 0.5}, iris::outside::clamp)};
    gold.ior = iris::material::conductor_ior{"Au", au->eta_spectrum(), au->k_spectrum()};
    const iris::material_desc mat = gold;
    const sampled_wavelengths<M> wl({420.0f, 510.0f, 600.0f, 700.0f}, {1.0f, 1.0f, 1.0f, 1.0f});
    for (float co : {1.0f, 0.6f, 0.1f, -0.4f}) {
        const float s = std::sqrt(1.0f - co * co);
        const glm::vec3 wo(s, 0.0f, co);
        const auto hs = iris::bsdf_sample_hero(mat, n, wo, wl, 0.3f, {0.5f, 0.5f});
        ASSERT_TRUE(hs.has_value());
        EXPECT_TRUE(hs->delta);
        EXPECT_NEAR(hs->wi.z, co, 1e-6f);
        for (std::size_t k = 0; k < M; ++k) {
            const double l = wl[k];
            const double want = complex_conductor_fresnel(std::fabs(co), au->eta_spectrum()(l), au->k_spectrum()(l));
            EXPECT_NEAR(hs->f_cos[k], want, 1e-4) << co << " " << l;
            EXPECT_EQ(hs->pdf[k], 1.0f);
        }
    }
    iris::material::conductor mirror{iris::tabulated_spectrum({360.0, 830.0}, {0.3, 0.9}, iris::outside::clamp)};
    const auto ms = iris::bsdf_sample_hero(iris::material_desc{mirror}, n, glm::vec3(0.6f, 0.0f, 0.8f), wl, 0.3f, {0.5f, 0.5f});
    ASSERT_TRUE(ms.has_value());
    for (std::size_t k = 0; k < M; ++k) EXPECT_NEAR(ms->f_cos[k], mirror.reflectance(wl[k]), 1e-6) << k;
}
