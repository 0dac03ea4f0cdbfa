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

}  // namespace iris::detail
