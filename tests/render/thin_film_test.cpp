// Thin-film interference (iris/render/materials/fresnel.hpp, `film_reflectance`;
// docs/method.md §9) against an independent implementation: the characteristic (Abelès)
// matrix of the layer in double-precision std::complex, written from the textbook form
// (Macleod, *Thin-Film Optical Filters*, ch. 2: N = n − ik, tilted admittances, the
// fourth-quadrant root), which shares nothing with iris's Airy sum but the physics. Then the
// closed forms at normal incidence, the bare interface as the film vanishes, total internal
// reflection, energy conservation, and the BxDFs' and bins' weights under a film.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <vector>

#include <iris/render/bins.hpp>
#include <iris/render/bsdf.hpp>
#include <iris/render/materials/materials.hpp>
#include <iris/render/random.hpp>
#include <iris/spectrum/named.hpp>

#include "test_scenes.hpp"
#include "thin_film_oracle.hpp"

namespace {

using iris_test::cd;
using iris_test::matrix_method;
using iris_test::rt;

struct film_case {
    double n_film, d_nm, lambda;
};
std::vector<film_case> cases() {
    std::vector<film_case> out;
    for (double n : {1.2, 1.33, 1.6, 2.4})
        for (double d : {20.0, 150.0, 420.0, 1200.0})
            for (double l : {380.0, 455.0, 550.0, 633.0, 780.0}) out.push_back({n, d, l});
    return out;
}
const double cosines[] = {1.0, 0.97, 0.8, 0.5, 0.2, 0.03};

}  // namespace

// The matrix method's own check first: R + T = 1 for a lossless stack, from either side. Then
// iris's reflectance against it at 4 film indices × 4 thicknesses × 5 wavelengths × 6 angles
// on glass (n = 1.5), a high-index base (2.0), a base below the film (1.1), gold-like
// (0.2 + 3.3i) and chromium-like (3.2 + 3.3i) metals. The tolerance is float's: the phase
// reaches 4π·3.2·2.4 ≈ 96 rad, where a float's rounding moves R by ≈ 10⁻⁵; 3·10⁻⁵ absolute
// is exceeded by any error in the formula (a missing factor 2 in the phase moves R by up to 0.3).
TEST(ThinFilm, ReflectanceMatchesTheCharacteristicMatrixOfTheLayer) {
    double worst = 0.0;
    for (const cd base : {cd(1.5), cd(2.0), cd(1.1), cd(0.2, -3.3), cd(3.2, -3.3)})
        for (const film_case& f : cases())
            for (double c : cosines) {
                const double s0 = std::sqrt(1.0 - c * c);
                const rt m = matrix_method(1.0, f.n_film, f.d_nm, base, s0, f.lambda);
                if (base.imag() == 0.0) {
                    EXPECT_NEAR(m.r + m.t, 1.0, 1e-12) << "the oracle itself";
                }
                const float got = iris::detail::film_reflectance(
                    static_cast<float>(c), static_cast<float>(f.n_film), static_cast<float>(f.d_nm / f.lambda),
                    {static_cast<float>(base.real()), static_cast<float>(-base.imag())});
                worst = std::max(worst, std::fabs(got - m.r));
                EXPECT_NEAR(got, m.r, 3e-5) << "n_f " << f.n_film << " d " << f.d_nm << " λ " << f.lambda << " cos " << c
                                            << " base " << base;
            }
    std::printf("largest |R_iris − R_matrix| = %.2e\n", worst);
}

// Lit from inside the glass (the stack read backwards: glass | film | outside), at angles
// below and beyond the critical one: iris's `fresnel_film_dielectric` with cos θ < 0 against
// the matrix method from the glass side, and R + T = 1 there too.
TEST(ThinFilm, FromInsideTheGlassMatchesTheMatrixAndReflectsTotallyBeyondTheCriticalAngle) {
    for (double eta : {1.5, 1.9})
        for (const film_case& f : cases())
            for (double c : {1.0, 0.9, 0.8, 0.7, 0.6, 0.4, 0.1}) {
                const double s = std::sqrt(1.0 - c * c);
                // the stack from the glass: incident medium η, the film, then the outside (1)
                const rt m = matrix_method(eta, f.n_film, f.d_nm, cd(1.0), s, f.lambda);
                const float got = iris::detail::fresnel_film_dielectric(-static_cast<float>(c), static_cast<float>(eta),
                                                                        static_cast<float>(f.n_film),
                                                                        static_cast<float>(f.d_nm / f.lambda));
                if (eta * s >= 1.0) {
                    EXPECT_EQ(got, 1.0f) << "beyond the critical angle";
                    EXPECT_NEAR(m.r, 1.0, 1e-9);
                    continue;
                }
                EXPECT_NEAR(m.r + m.t, 1.0, 1e-12);
                EXPECT_NEAR(got, m.r, 3e-5) << "η " << eta << " n_f " << f.n_film << " d " << f.d_nm << " λ " << f.lambda
                                            << " cos " << c;
            }
}

// Normal incidence on glass (n₂ = 1.5) has a closed form (Born & Wolf §1.6, eq. 59):
//   R = [(1 − n₂)² cos²φ + (n₂/n₁ − n₁)² sin²φ] / [(1 + n₂)² cos²φ + (n₂/n₁ + n₁)² sin²φ],
// φ = 2π n₁ d / λ; a quarter-wave layer of n₁ = √n₂ reflects nothing at its design wavelength,
// a half-wave layer is absent there, and d = 0 or n₁ = 1 is the bare interface at every angle
// (dielectric and conductor: iris's own `fresnel_dielectric` and `fresnel_conductor`).
TEST(ThinFilm, ClosedFormsAtNormalIncidenceAndTheBareInterfaceWhenTheFilmVanishes) {
    const double n2 = 1.5;
    for (const film_case& f : cases()) {
        const double phi = 2.0 * std::numbers::pi * f.n_film * f.d_nm / f.lambda, c2 = std::pow(std::cos(phi), 2.0),
                     s2 = std::pow(std::sin(phi), 2.0);
        const double want = ((1 - n2) * (1 - n2) * c2 + std::pow(n2 / f.n_film - f.n_film, 2.0) * s2) /
                            ((1 + n2) * (1 + n2) * c2 + std::pow(n2 / f.n_film + f.n_film, 2.0) * s2);
        EXPECT_NEAR(iris::detail::film_reflectance(1.0f, static_cast<float>(f.n_film), static_cast<float>(f.d_nm / f.lambda),
                                                   {1.5f, 0.0f}),
                    want, 2e-5);
    }
    const float n1 = std::sqrt(1.5f), lambda0 = 550.0f;
    EXPECT_LT(iris::detail::film_reflectance(1.0f, n1, 1.0f / (4.0f * n1), {1.5f, 0.0f}), 1e-6f) << "quarter-wave";
    EXPECT_GT(iris::detail::film_reflectance(1.0f, n1, 550.0f / (4.0f * n1 * 450.0f), {1.5f, 0.0f}), 1e-3f)
        << "a quarter-wave layer reflects away from its design wavelength";
    (void)lambda0;
    EXPECT_NEAR(iris::detail::film_reflectance(1.0f, 1.38f, 1.0f / (2.0f * 1.38f), {1.5f, 0.0f}), 0.04f, 1e-6f) << "half-wave";
    for (float c : {1.0f, 0.7f, 0.3f, 0.05f})
        for (float e : {1.33f, 1.5f, 2.2f}) {
            EXPECT_NEAR(iris::detail::fresnel_film_dielectric(c, e, 1.45f, 0.0f), iris::detail::fresnel_dielectric(c, e), 2e-6f);
            EXPECT_NEAR(iris::detail::fresnel_film_dielectric(c, e, 1.0f, 0.8f), iris::detail::fresnel_dielectric(c, e), 2e-6f);
            EXPECT_NEAR(iris::detail::fresnel_film_dielectric(-c, e, 1.45f, 0.0f), iris::detail::fresnel_dielectric(-c, e), 2e-6f);
            EXPECT_NEAR(iris::detail::film_reflectance(c, 1.0f, 0.6f, {e * 0.1f, e}), iris::detail::fresnel_conductor(c, e * 0.1f, e),
                        2e-6f);
        }
    EXPECT_EQ(iris::detail::film_reflectance(0.0f, 1.33f, 0.5f, {1.5f, 0.0f}), 1.0f) << "grazing";
}

namespace {

iris::material::thin_film soap(double d) { return {d, iris::constant_ior{1.33}}; }

/// \brief The bins' spectra of material m as the B term reads them (propagation's view).
struct bins_source {
    const iris::bin_tables<80>& t;
    std::uint32_t m;
    iris::bin_position p;
    mutable std::array<std::array<float, 80>, 6> scratch{};  // one per spectrum: off the lattice each is evaluated into its own
    const iris::sampled_spectrum<80>& albedo() const noexcept { return none; }
    iris::sampled_spectrum<80> none{};
    auto eta() const { return t.eta[m].at(p, scratch[0]); }
    auto eta2() const { return t.eta2[m].at(p, scratch[1]); }
    auto inv_eta2() const { return t.inv_eta2[m].at(p, scratch[2]); }
    auto k() const { return t.k[m].at(p, scratch[3]); }
    auto wavelength() const { return t.lambda.at(p, scratch[4]); }
    auto film_eta() const { return t.film_eta[m].at(p, scratch[5]); }
};

}  // namespace

// The BxDFs weigh by the film's reflectance at every hero wavelength: a smooth dielectric's
// reflection F(λ_k) and transmission (1 − F(λ_k))/η′² (with the pdfs), from both sides, and
// a specular conductor's F(λ_k) — and the B term's `follow` at 80 bins (the spectra read
// through the bins' tables, λ_b and the film's index included) gives `film_reflectance` at
// each λ_b.
TEST(ThinFilm, TheBxdfsAndTheBinsWeighByTheFilmsReflectance) {
    iris::scene_desc s;
    iris::material::dielectric glass{iris::constant_ior{1.5}, 0.0f};
    glass.film = soap(380.0);
    const auto au = iris::find_metal("Au");
    ASSERT_TRUE(au.has_value());
    iris::material::conductor gold{iris::test::flat(1.0)};
    const iris::tabulated_spectrum au_eta = au->eta_spectrum(), au_k = au->k_spectrum();
    gold.ior = iris::material::conductor_ior{"Au", au_eta, au_k};
    gold.film = iris::material::thin_film{250.0, iris::cauchy_ior{1.40, 0.0045}};  // a dispersive film
    s.materials = {glass, gold};
    const iris::sampled_wavelengths<4> wl({430.0f, 520.0f, 610.0f, 700.0f}, {1.0f, 1.0f, 1.0f, 1.0f});
    const iris::bin_tables<80> t(s);
    ASSERT_EQ(t.film_eta.size(), 2u);
    for (float co : {0.9f, 0.35f, -0.9f, -0.5f}) {
        const glm::vec3 wo(std::sqrt(1.0f - co * co), 0.0f, co);
        const iris::smooth_dielectric b{glass};
        const auto spectra = iris::scene_spectra(b, wl);
        for (float u_lobe : {0.0f, 0.999f}) {
            const auto smp = b.sample<4>(wo, wl, u_lobe, {0.5f, 0.5f}, spectra);
            ASSERT_TRUE(smp.has_value());
            for (std::size_t k = 0; k < 4; ++k) {
                const float f = iris::detail::fresnel_film_dielectric(co, 1.5f, 1.33f, 380.0f / wl[k]);
                if (smp->kind == iris::lobe::reflection) {
                    EXPECT_NEAR(smp->f_cos[k], f, 1e-6f);
                    EXPECT_NEAR(smp->pdf[k], f, 1e-6f);
                } else {
                    const float e2 = co > 0.0f ? 1.5f * 1.5f : 1.0f / (1.5f * 1.5f);
                    EXPECT_NEAR(smp->f_cos[k], (1.0f - f) / e2, 1e-6f);
                    EXPECT_NEAR(smp->pdf[k], 1.0f - f, 1e-6f);
                }
            }
            for (float u : {0.0f, 0.37f, 0.999f}) {
                const bins_source src{t, 0, t.lattice.position(u)};
                const auto w = b.follow<80>(wo, smp->wi, smp->kind, src);
                for (std::size_t k = 0; k < 80; ++k) {
                    const float l = t.lattice.lambda(k, u);
                    const float f = iris::detail::fresnel_film_dielectric(co, 1.5f, 1.33f, 380.0f / l);
                    const float want = smp->kind == iris::lobe::reflection ? f : (1.0f - f) * (co > 0.0f ? 1.0f / 2.25f : 2.25f);
                    ASSERT_NEAR(w[k], want, 2e-5f) << "bin " << k << " cos " << co;
                }
            }
        }
    }
    const iris::specular_conductor c{gold};
    const auto spectra = iris::scene_spectra(c, wl);
    for (float co : {1.0f, 0.6f, 0.2f}) {
        const glm::vec3 wo(std::sqrt(1.0f - co * co), 0.0f, co);
        const auto smp = c.sample<4>(wo, wl, 0.5f, {0.5f, 0.5f}, spectra);
        ASSERT_TRUE(smp.has_value());
        float change = 0.0f;
        for (std::size_t k = 0; k < 4; ++k) {
            const double l = wl[k];
            const float nf = static_cast<float>(1.40 + 0.0045 / (l * l * 1e-6));
            const float want = iris::detail::film_reflectance(co, nf, 250.0f / wl[k],
                                                              {static_cast<float>(au_eta(l)), static_cast<float>(au_k(l))});
            EXPECT_NEAR(smp->f_cos[k], want, 2e-5f) << "λ " << l;
            change = std::max(change, std::fabs(smp->f_cos[k] - iris::detail::fresnel_conductor(co, static_cast<float>(au_eta(l)),
                                                                                                static_cast<float>(au_k(l)))));
        }
        EXPECT_GT(change, 0.02f) << "the film changes gold's reflectance";
        const bins_source src{t, 1, t.lattice.position(0.61f)};
        const auto w = c.follow<80>(wo, smp->wi, smp->kind, src);
        for (std::size_t k = 0; k < 80; ++k) {
            const double l = t.lattice.lambda(k, 0.61f);
            const float nf = static_cast<float>(1.40 + 0.0045 / (l * l * 1e-6));
            const float want = iris::detail::film_reflectance(co, nf, 250.0f / static_cast<float>(l),
                                                              {static_cast<float>(au_eta(l)), static_cast<float>(au_k(l))});
            ASSERT_NEAR(w[k], want, 2e-4f) << "bin " << k;  // (η, k and the film's index on the lattice)
        }
    }
}

// A rough dielectric under a film: what it samples agrees with what it evaluates, f and pdf
// at every wavelength (what MIS and the B term rely on), through both lobes and both sides.
TEST(ThinFilm, ARoughFilmCoatedDielectricSamplesWhatItEvaluates) {
    iris::material::dielectric glass{iris::constant_ior{1.5}, 0.3f};
    glass.film = soap(420.0);
    const iris::material_desc m = glass;
    const glm::vec3 n{0.0f, 0.0f, 1.0f};
    const iris::sampled_wavelengths<4> wl({450.0f, 530.0f, 610.0f, 690.0f}, {1.0f, 1.0f, 1.0f, 1.0f});
    iris::sample_stream rng(5, 6, 7);
    int reflected = 0, transmitted = 0;
    for (const glm::vec3 wo : {glm::normalize(glm::vec3(0.3f, -0.2f, 0.9f)), glm::normalize(glm::vec3(0.5f, 0.1f, -0.4f))})
        for (int i = 0; i < 4000; ++i) {
            const auto smp = iris::bsdf_sample_hero(m, n, wo, wl, rng.next(), rng.next2());
            if (!smp) continue;
            (smp->kind == iris::lobe::reflection ? reflected : transmitted)++;
            const auto f = iris::bsdf_eval(m, n, wo, smp->wi, wl);
            const auto p = iris::bsdf_pdf(m, n, wo, smp->wi, wl);
            for (std::size_t k = 0; k < 4; ++k) {
                ASSERT_NEAR(f[k], smp->f_cos[k], 1e-4f * std::max(1.0f, f[k]));
                ASSERT_NEAR(p[k], smp->pdf[k], 1e-4f * std::max(1.0f, p[k]));
            }
        }
    EXPECT_GT(reflected, 100);
    EXPECT_GT(transmitted, 1000);
}
