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

#include "direction_fit.hpp"
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
    const std::complex<double> index(eta, k);
    const std::complex<double> ct = std::sqrt(1.0 - (1.0 - c * c) / (index * index));
    const std::complex<double> rs = (c - index * ct) / (c + index * ct), rp = (index * c - ct) / (index * c + ct);
    return 0.5 * (std::norm(rs) + std::norm(rp));
}
}  // namespace

// The conductor Fresnel against the complex-amplitude formula over angles and indices
// (metals, a near-dielectric k = 0, and k → ∞, which reflects everything), and the named
// metals against their reflectance at normal incidence computed from the data files'
// rows (data/README.md: R = ((n − 1)² + k²)/((n + 1)² + k²) at the row nearest 550 nm).
TEST(Bsdf, ConductorFresnelIsExact) {
    for (const auto& [eta, k] : {std::pair{0.2, 3.0}, std::pair{0.05, 3.6}, std::pair{1.2, 7.0}, std::pair{2.5, 0.0},
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

// ---- rough conductors ------------------------------------------------------------------
//
// χ² (direction_fit.hpp): the directions the rough conductor samples (a visible GGX normal,
// ωo reflected about it) against the pdf it claims for them, N = 200 000 per fit, for
// α ∈ {0.3, 0.08} and ωo at normal, oblique and grazing incidence and from below the
// shading normal; the rough dielectric (reflection and refraction) at two angles. Family:
// those 10 fits at family-wise α = 0.01, Šidák: α' = 1 − 0.99^(1/10) ≈ 1.0e-3. Negative
// controls: α = 0.3's samples against α = 0.33's pdf, and the pdf without its 1/(4|ωo·ωm|)
// Jacobian's ωo·ωm (that is, D_ωo(ωm)/4), must be rejected at α'.

namespace {

iris::material_desc rough_gold(float alpha) {
    const auto au = iris::find_metal("Au");
    iris::material::conductor m{iris::tabulated_spectrum({360.0, 830.0}, {0.5, 0.5}, iris::outside::clamp)};
    m.ior = iris::material::conductor_ior{"Au", au->eta_spectrum(), au->k_spectrum()};
    m.roughness = alpha;
    return m;
}

iris::material_desc rough_white(float alpha) {
    iris::material::conductor m{iris::tabulated_spectrum({360.0, 830.0}, {1.0, 1.0}, iris::outside::clamp)};
    m.roughness = alpha;
    return m;
}

glm::vec3 at_cos(float c) { return {std::sqrt(std::max(0.0f, 1.0f - c * c)), 0.0f, c}; }

glm::vec3 uniform_hemisphere(glm::vec2 u) {
    const float z = u.x, r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = 2.0f * std::numbers::pi_v<float> * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

constexpr std::size_t bsdf_chi2_family = 10;
const double bsdf_alpha = iris::test::sidak(0.01, bsdf_chi2_family);

iris::test::chi2_result bsdf_fit(const iris::material_desc& m, const glm::vec3& wo, std::uint64_t seed,
                                 const iris::material_desc* claimed = nullptr) {
    const sampled_wavelengths<1> wl({550.0f}, {1.0f});
    const iris::material_desc& c = claimed ? *claimed : m;
    iris::counter_rng lobe_rng(seed, 1);
    iris::test::direction_grid g;
    g.z_bands = 48;
    g.phi_sectors = 96;
    g.sub_z = 32;
    g.sub_phi = 4;
    return iris::test::direction_fit(
        [&](glm::vec2 u) -> std::optional<glm::vec3> {
            const auto s = iris::bsdf_sample_hero(m, n, wo, wl, lobe_rng.next(), u);
            if (!s) return std::nullopt;
            return s->wi;
        },
        [&](const glm::vec3& wi) { return static_cast<double>(iris::bsdf_pdf(c, n, wo, wi, wl)[0]); }, seed, g);
}

}  // namespace

TEST(Bsdf, RoughConductorSamplesItsPdf) {
    std::uint64_t seed = 100;
    for (float alpha : {0.3f, 0.08f})
        for (float c : {0.999f, 0.6f, 0.15f, -0.5f}) {
            const auto r = bsdf_fit(rough_gold(alpha), at_cos(c), ++seed);
            EXPECT_TRUE(r.impossible.empty()) << alpha << " " << c << ": " << r.impossible;
            EXPECT_GT(r.p_value, bsdf_alpha) << "α " << alpha << " cos θo " << c << ": χ² " << r.statistic << " dof " << r.dof;
        }
    const iris::material_desc glass = iris::material::dielectric{iris::cauchy_ior{1.5, 0.02}, 0.2f};
    for (float c : {0.8f, -0.35f}) {
        const auto r = bsdf_fit(glass, at_cos(c), ++seed);
        EXPECT_TRUE(r.impossible.empty()) << "rough glass " << c << ": " << r.impossible;
        EXPECT_GT(r.p_value, bsdf_alpha) << "rough glass, cos θo " << c << ": χ² " << r.statistic << " dof " << r.dof;
    }
    // negative control: a slightly wider lobe's pdf
    const auto wider = rough_gold(0.33f);
    const auto bad = bsdf_fit(rough_gold(0.3f), at_cos(0.6f), 200, &wider);
    EXPECT_LT(bad.p_value, bsdf_alpha) << "α = 0.3's samples against α = 0.33's pdf must be rejected";
}

// Reciprocity f(ωo, ωi) = f(ωi, ωo); a sample reports what eval gives for its direction, at
// every wavelength, with one pdf for all of them (the direction does not depend on λ); a
// white rough conductor reflects at most 1 — each sample's weight f·|cos|/pdf = G₂/G₁ ≤ 1 —
// and nearly 1 when nearly smooth; gold's weight is that times its Fresnel at the
// microfacet; sampled and quadrature directional albedo agree; no light passes to the far
// side.
TEST(Bsdf, RoughConductorIsReciprocalBoundedAndConsistent) {
    constexpr std::size_t M = 4;
    const sampled_wavelengths<M> wl({420.0f, 510.0f, 600.0f, 700.0f}, {1.0f, 1.0f, 1.0f, 1.0f});
    const auto au = iris::find_metal("Au");
    iris::sample_stream rng(8, 9, 10);
    for (float alpha : {0.5f, 0.1f, 0.01f}) {
        const auto gold = rough_gold(alpha), white = rough_white(alpha);
        for (int i = 0; i < 2000; ++i) {
            const glm::vec3 a = uniform_hemisphere(rng.next2()), b = uniform_hemisphere(rng.next2());
            const auto fab = iris::bsdf_eval(gold, n, a, b, wl), fba = iris::bsdf_eval(gold, n, b, a, wl);
            for (std::size_t k = 0; k < M; ++k)
                ASSERT_NEAR(fab[k] / b.z, fba[k] / a.z, 1e-4f * (1.0f + fab[k] / b.z)) << alpha << " " << k;
            const glm::vec3 below{b.x, b.y, -b.z};
            ASSERT_EQ(iris::bsdf_eval(gold, n, a, below, wl)[0], 0.0f);
            ASSERT_EQ(iris::bsdf_pdf(gold, n, a, below, wl)[0], 0.0f);
        }
        for (float c : {1.0f, 0.7f, 0.2f, -0.6f}) {
            const glm::vec3 wo = at_cos(c);
            double sum = 0.0;
            int n_samples = 0;
            for (int i = 0; i < 20000; ++i, ++n_samples) {
                const glm::vec2 u = rng.next2();
                const auto s = iris::bsdf_sample_hero(white, n, wo, wl, rng.next(), u);
                if (!s) continue;
                ASSERT_GT(s->wi.z * wo.z, 0.0f);
                const double w = s->f_cos[0] / s->pdf[0];
                ASSERT_LE(w, 1.0 + 1e-5) << alpha << " " << c;
                sum += w;
                const auto e = iris::bsdf_eval(white, n, wo, s->wi, wl);
                const auto p = iris::bsdf_pdf(white, n, wo, s->wi, wl);
                ASSERT_NEAR(e[0], s->f_cos[0], 2e-3f * (1.0f + e[0]));
                ASSERT_NEAR(p[0], s->pdf[0], 2e-3f * (1.0f + p[0]));
                // gold from the same u: the same visible normal and direction, its weight F(|ωo·ωm|, λ_k) times white's
                const auto gs = iris::bsdf_sample_hero(gold, n, wo, wl, 0.5f, u);
                ASSERT_TRUE(gs.has_value());
                ASSERT_NEAR(glm::length(gs->wi - s->wi), 0.0f, 1e-6f);
                const double cm = std::fabs(glm::dot(wo, glm::normalize(wo + s->wi)));
                for (std::size_t k = 0; k < M; ++k) {
                    ASSERT_EQ(gs->pdf[k], gs->pdf[0]);
                    const double l = wl[k];
                    const double f = complex_conductor_fresnel(cm, au->eta_spectrum()(l), au->k_spectrum()(l));
                    ASSERT_NEAR(gs->f_cos[k] / gs->pdf[k], f * w, 2e-4) << alpha << " " << c << " " << l;
                }
            }
            const double albedo = sum / n_samples;
            EXPECT_LE(albedo, 1.0) << alpha << " " << c;
            if (alpha == 0.01f && std::fabs(c) > 0.5f) {
                EXPECT_GT(albedo, 0.999) << c;
            }
        }
    }
}
