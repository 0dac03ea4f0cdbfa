#pragma once
/// \file
/// \brief Fresnel reflectance and refraction of a dielectric interface, for the hero
/// (one wavelength at a time, as it samples) and for the B term's bins (all at once,
/// from tabulated η² and 1/η²).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "iris/render/materials/bxdf.hpp"
#include "iris/render/scene.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris::detail {

/// \brief Unpolarised Fresnel reflectance of a dielectric interface from c = |cos θi| and
/// η′², the square of the relative index seen from the incident side (η_t/η_i), in the
/// form of Walter et al. 2007 (eq. 22) with g = √(η′² − 1 + c²) (= η′ cos θt):
///   F = ½ (g−c)² [(c(g−c)+1)² + (c(g+c)−1)²] / [(g+c)² (c(g−c)+1)²],  F = 1 if g² ≤ 0
/// (total internal reflection, and g + c = 0). One square root and one division, η′² read
/// rather than computed, no branch (the comparison is a select): the one Fresnel of iris,
/// for the hero (`fresnel_dielectric`) and for the B term's bins (`fresnel_follow`, where
/// the compiler vectorises it over 80 bins).
inline float fresnel_walter(float c, float eta2) noexcept {
    const float g2 = eta2 - 1.0f + c * c;
    const float g = std::sqrt(std::max(0.0f, g2));
    const float gm = g - c, gp = g + c;
    const float u = c * gm + 1.0f, v = c * gp - 1.0f;
    const float ratio = 0.5f * (gm * gm * (u * u + v * v)) / (gp * gp * (u * u));  // everywhere: a select, not a branch
    return g2 > 0.0f ? ratio : 1.0f;
}

/// \brief Unpolarised Fresnel reflectance of a dielectric interface. `cos_i` is measured
/// on the side of the incident direction's normal; eta = n_inside / n_outside.
inline float fresnel_dielectric(float cos_i, float eta) noexcept {
    cos_i = std::clamp(cos_i, -1.0f, 1.0f);
    const float eta2 = eta * eta;
    return fresnel_walter(std::fabs(cos_i), cos_i < 0.0f ? 1.0f / eta2 : eta2);
}

/// \brief Unpolarised Fresnel reflectance of a conductor of complex index η + ik seen
/// from vacuum at c = |cos θi| (Born & Wolf §14.2; the real form with a² + b² =
/// |η̃² − sin²θ|, a = Re √(η̃² − sin²θ)): with s² = 1 − c²,
///   R_s = (a² + b² − 2ac + c²) / (a² + b² + 2ac + c²),
///   R_p = R_s · (c²(a² + b²) − 2acs² + s⁴) / (c²(a² + b²) + 2acs² + s⁴),
/// F = (R_s + R_p)/2. Real arithmetic only, no division by c (F → 1 at grazing
/// incidence), so it vectorises over the bins like `fresnel_walter`; at normal incidence
/// F = ((η − 1)² + k²) / ((η + 1)² + k²).
inline float fresnel_conductor(float c, float eta, float k) noexcept {
    c = std::clamp(c, 0.0f, 1.0f);
    const float c2 = c * c, s2 = 1.0f - c2;
    const float e2 = eta * eta, k2 = k * k;
    const float t0 = e2 - k2 - s2;
    const float ab2 = std::sqrt(std::max(0.0f, t0 * t0 + 4.0f * e2 * k2));  // a² + b²
    const float a = std::sqrt(std::max(0.0f, 0.5f * (ab2 + t0)));
    const float t1 = ab2 + c2, t2 = 2.0f * a * c;
    const float rs = (t1 - t2) / (t1 + t2);
    const float t3 = c2 * ab2 + s2 * s2, t4 = t2 * s2;
    const float rp = rs * (t3 - t4) / (t3 + t4);
    const float f = 0.5f * (rs + rp);
    return f == f ? f : 1.0f;  // 0/0 only where η = k = 0 at grazing incidence
}

/// \brief A complex number in float with the few operations the film's reflectance needs,
/// written out (std::complex's operators call the libgcc routines that handle infinities;
/// nothing here is infinite).
struct cfloat {
    float re = 0.0f, im = 0.0f;
};
inline cfloat operator+(cfloat a, cfloat b) noexcept { return {a.re + b.re, a.im + b.im}; }
inline cfloat operator-(cfloat a, cfloat b) noexcept { return {a.re - b.re, a.im - b.im}; }
inline cfloat operator*(cfloat a, cfloat b) noexcept { return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re}; }
inline float norm2(cfloat a) noexcept { return a.re * a.re + a.im * a.im; }
inline cfloat quotient(cfloat a, cfloat b) noexcept {
    const float d = norm2(b);
    return {(a.re * b.re + a.im * b.im) / d, (a.im * b.re - a.re * b.im) / d};
}
/// \brief √z with Im ≥ 0, for Im z ≥ 0: the root whose wave decays into the layer (an
/// absorbing metal, or an evanescent wave beyond the critical angle).
inline cfloat sqrt_decaying(cfloat z) noexcept {
    const float r = std::sqrt(norm2(z));
    if (!(r > 0.0f)) return {};
    if (z.re >= 0.0f) {
        const float a = std::sqrt(0.5f * (r + z.re));
        return {a, std::fabs(z.im) / (2.0f * a)};
    }
    const float b = std::sqrt(0.5f * (r - z.re));
    return {std::fabs(z.im) / (2.0f * b), b};
}

/// \brief Unpolarised reflectance of a thin film of real index n_f ≥ 1 and thickness d on a
/// base of complex index n_b = η + ik (both relative to the outside), lit from the outside at
/// c = cos θ₀ ∈ [0, 1], at a wavelength with d/λ = `thickness_over_lambda` (docs/method.md §9).
/// With q_j = n_j cos θ_j = √(n_j² − sin²θ₀) (the decaying root), each polarisation's
/// amplitude is the Airy sum of the film's multiple reflections,
///   r = (r₀₁ + r₁₂ e^{2iδ}) / (1 + r₀₁ r₁₂ e^{2iδ}),  δ = 2π (d/λ) q_f,
/// with r_ij = (q_i − q_j)/(q_i + q_j) (s) and (n_j² q_i − n_i² q_j)/(n_j² q_i + n_i² q_j) (p);
/// R = (|r_s|² + |r_p|²)/2. d = 0 or n_f = 1 give the bare base's Fresnel reflectance.
inline float film_reflectance(float c, float film_index, float thickness_over_lambda, cfloat base) noexcept {
    c = std::clamp(c, 0.0f, 1.0f);
    if (!(c > 0.0f)) return 1.0f;  // grazing incidence: everything is reflected
    const float s2 = 1.0f - c * c;
    const cfloat n1{film_index * film_index, 0.0f};
    const cfloat n2 = base * base;
    const cfloat q0{c, 0.0f};
    const cfloat q1 = sqrt_decaying({n1.re - s2, 0.0f});
    const cfloat q2 = sqrt_decaying({n2.re - s2, n2.im});
    // e^{2iδ} = e^{i·4π(d/λ)q_f}: a phase, and a decay where the wave in the film is evanescent
    constexpr float four_pi = 12.566370614359172f;
    const float a = four_pi * thickness_over_lambda;
    const float decay = std::exp(-a * q1.im);
    const cfloat e{decay * std::cos(a * q1.re), decay * std::sin(a * q1.re)};
    const auto airy = [&](cfloat r01, cfloat r12) {
        const cfloat t = r12 * e;
        return norm2(r01 + t) / norm2(cfloat{1.0f, 0.0f} + r01 * t);
    };
    const float rs = airy(quotient(q0 - q1, q0 + q1), quotient(q1 - q2, q1 + q2));
    const cfloat p0 = n1 * q0, p1 = q1, p2 = n2 * q1, p3 = n1 * q2;  // n₀ = 1
    const float rp = airy(quotient(p0 - p1, p0 + p1), quotient(p2 - p3, p2 + p3));
    const float f = 0.5f * (rs + rp);
    return f == f ? std::min(f, 1.0f) : 1.0f;
}

/// \brief The reflectance of a dielectric of relative index η under a thin film (n_f, d/λ),
/// from either side: `cos_i` on the side of the incident direction's normal, as
/// `fresnel_dielectric`. The film is lossless, so its reflectance from the inside equals the
/// reflectance from the outside at the angle Snell's law pairs with it (T is reciprocal and
/// R = 1 − T on both sides), and 1 beyond the critical angle (no wave leaves into the outside).
inline float fresnel_film_dielectric(float cos_i, float eta, float film_index, float thickness_over_lambda) noexcept {
    cos_i = std::clamp(cos_i, -1.0f, 1.0f);
    float c = std::fabs(cos_i);
    if (cos_i < 0.0f) {
        const float s2 = eta * eta * (1.0f - c * c);
        if (s2 >= 1.0f) return 1.0f;
        c = std::sqrt(1.0f - s2);
    }
    return film_reflectance(c, film_index, thickness_over_lambda, {eta, 0.0f});
}

/// \brief A film's index and d/λ at one wavelength (what `fresnel_film_dielectric` needs
/// beside the base's index).
struct film_layer {
    float index = 1.0f;
    float thickness_over_lambda = 0.0f;
};

/// \brief Refract `wi` (pointing away) through a surface with normal `n`; eta = n_inside /
/// n_outside with `n` pointing outside. Returns the transmitted direction and the relative
/// eta it saw (η_t/η_i), or nothing on total internal reflection.
struct refraction {
    glm::vec3 wt;
    float eta;
};
inline std::optional<refraction> refract(const glm::vec3& wi, glm::vec3 n, float eta) noexcept {
    float cos_i = glm::dot(n, wi);
    if (cos_i < 0.0f) {
        eta = 1.0f / eta;
        cos_i = -cos_i;
        n = -n;
    }
    const float sin2_i = std::max(0.0f, 1.0f - cos_i * cos_i);
    const float sin2_t = sin2_i / (eta * eta);
    if (sin2_t >= 1.0f) return std::nullopt;
    const float cos_t = std::sqrt(1.0f - sin2_t);
    return refraction{glm::normalize(-wi / eta + (cos_i / eta - cos_t) * n), eta};
}

template <std::size_t N>
sampled_spectrum<N> etas(const ior_model& ior, const sampled_wavelengths<N>& wl) noexcept {
    sampled_spectrum<N> e;
    for (std::size_t k = 0; k < N; ++k) e[k] = static_cast<float>(refractive_index(ior, static_cast<double>(wl[k])));
    return e;
}

/// \brief The weight of a delta event at dielectric at M wavelengths that follow the hero's
/// lobe `kind`: F(λ_b) for reflection, (1 − F(λ_b))/η′_b² for transmission, with `co` =
/// cos θo on the normal's side and η², 1/η² given (anything indexable by k < M). F is
/// `fresnel_walter`; the side (co's sign) is the same for all wavelengths, so the loop is
/// branch-free arithmetic and selects, which the compiler vectorises (80 bins at every
/// glass vertex: this is the B term's hot loop; choosing the tables once, outside the loop,
/// stops GCC vectorising it).
template <std::size_t M, class Eta2, class InvEta2>
sampled_spectrum<M> fresnel_follow(float co, lobe kind, const Eta2& sq, const InvEta2& isq) noexcept {
    co = std::clamp(co, -1.0f, 1.0f);
    const bool flip = co < 0.0f, from_outside = co > 0.0f;  // as fresnel_dielectric and the hero's sample
    const bool reflection = kind == lobe::reflection;
    const float c = std::fabs(co);
    sampled_spectrum<M> w;
    for (std::size_t k = 0; k < M; ++k) {
        const float e2 = sq[k], ie2 = isq[k];
        const float ef2 = flip ? ie2 : e2;              // η′²: the relative index seen from ωo's side
        const float inv_et2 = from_outside ? ie2 : e2;  // 1/η′² of the hero's transmission
        const float f = fresnel_walter(c, ef2);
        w[k] = reflection ? f : (1.0f - f) * inv_et2;
    }
    return w;
}

/// \brief `fresnel_follow` for a dielectric under a thin film of thickness `thickness_nm`:
/// R(λ_b) from `fresnel_film_dielectric` with η, the wavelengths and the film's index
/// read from the spectra source (a film is rare: this loop is not the vectorised one).
template <std::size_t M, class Eta, class Lambda, class FilmEta>
sampled_spectrum<M> film_follow(float co, lobe kind, const Eta& eta, const Lambda& lambda, const FilmEta& film_eta,
                                double thickness_nm) noexcept {
    co = std::clamp(co, -1.0f, 1.0f);
    const bool from_outside = co > 0.0f;
    const float d = static_cast<float>(thickness_nm);
    sampled_spectrum<M> w;
    for (std::size_t k = 0; k < M; ++k) {
        const float e = eta[k];
        const float f = fresnel_film_dielectric(co, e, film_eta[k], d / lambda[k]);
        w[k] = kind == lobe::reflection ? f : (1.0f - f) * (from_outside ? 1.0f / (e * e) : e * e);
    }
    return w;
}

}  // namespace iris::detail
