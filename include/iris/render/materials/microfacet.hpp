#pragma once
/// \file
/// \brief The GGX microfacet distribution and the rough dielectric's value at one
/// wavelength (Walter et al. 2007, with Heitz 2018's visible-normal sampling).

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/materials/fresnel.hpp"

namespace iris::detail {

/// \brief Isotropic GGX (Trowbridge–Reitz) in the local frame (n = +z), for unit directions.
/// tan²θ is (x² + y²)/z², not (1 − z²)/z²: near the normal 1 − z² cancels to a multiple of
/// 6·10⁻⁸, and at α = 0.01 that step moved D by 0.5 % between two float roundings of one
/// direction (sampling and evaluating it disagreed; Bsdf.RoughConductor* checks it).
struct ggx {
    float alpha;

    static float tan2(const glm::vec3& w) noexcept { return (w.x * w.x + w.y * w.y) / (w.z * w.z); }

    float d(const glm::vec3& wm) const noexcept {
        const float c2 = wm.z * wm.z;
        if (c2 <= 0.0f) return 0.0f;
        const float e = 1.0f + ggx::tan2(wm) / (alpha * alpha);
        return 1.0f / (std::numbers::pi_v<float> * alpha * alpha * c2 * c2 * e * e);
    }
    float lambda(const glm::vec3& w) const noexcept {
        if (w.z * w.z <= 0.0f) return 0.0f;
        return 0.5f * (std::sqrt(1.0f + alpha * alpha * ggx::tan2(w)) - 1.0f);
    }
    float g1(const glm::vec3& w) const noexcept { return 1.0f / (1.0f + lambda(w)); }
    float g(const glm::vec3& wo, const glm::vec3& wi) const noexcept { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }
    /// \brief Density of visible normals D_ωo(ωm) (Heitz 2018).
    float d_visible(const glm::vec3& wo, const glm::vec3& wm) const noexcept {
        return wo.z == 0.0f ? 0.0f : g1(wo) / std::fabs(wo.z) * d(wm) * std::fabs(glm::dot(wo, wm));
    }
    /// \brief Sample a visible normal (Heitz 2018, "Sampling the GGX distribution of visible normals").
    glm::vec3 sample_visible(glm::vec3 wo, glm::vec2 u) const noexcept {
        glm::vec3 wh = glm::normalize(glm::vec3(alpha * wo.x, alpha * wo.y, wo.z));
        if (wh.z < 0.0f) wh = -wh;
        const glm::vec3 t1 = wh.z < 0.99999f ? glm::normalize(glm::cross(glm::vec3(0, 0, 1), wh)) : glm::vec3(1, 0, 0);
        const glm::vec3 t2 = glm::cross(wh, t1);
        const float r = std::sqrt(u.x);
        const float phi = 2.0f * std::numbers::pi_v<float> * u.y;
        float px = r * std::cos(phi);
        float py = r * std::sin(phi);
        const float h = std::sqrt(std::max(0.0f, 1.0f - px * px));
        py = (1.0f - (1.0f + wh.z) / 2.0f) * h + (1.0f + wh.z) / 2.0f * py;
        const float pz = std::sqrt(std::max(0.0f, 1.0f - px * px - py * py));
        const glm::vec3 nh = px * t1 + py * t2 + pz * wh;
        return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
    }
};

/// \brief f·|cos θi| and pdf of the rough dielectric for one wavelength (local frame),
/// with the generalised half vector of Walter et al. 2007 (pbrt-v4's formulation).
struct rough_value {
    float f_cos = 0.0f;
    float pdf = 0.0f;        ///< the lobe's density times the probability of choosing it (`selection`)
    float selection = 0.0f;  ///< that probability: F at the microfacet for reflection, 1 − F for transmission
};
inline rough_value rough_dielectric_value(const ggx& m, const glm::vec3& wo, const glm::vec3& wi, float eta,
                                          const film_layer* film = nullptr) noexcept {
    const float cos_o = wo.z, cos_i = wi.z;
    if (cos_o == 0.0f || cos_i == 0.0f) return {};
    const bool reflect = cos_i * cos_o > 0.0f;
    const float etap = reflect ? 1.0f : (cos_o > 0.0f ? eta : 1.0f / eta);
    glm::vec3 wm = wi * etap + wo;
    const float len2 = glm::dot(wm, wm);
    if (!(len2 > 0.0f)) return {};
    wm = wm / std::sqrt(len2);
    if (wm.z < 0.0f) wm = -wm;
    if (glm::dot(wm, wi) * cos_i < 0.0f || glm::dot(wm, wo) * cos_o < 0.0f) return {};  // back-facing microfacet
    const float fr = film ? fresnel_film_dielectric(glm::dot(wo, wm), eta, film->index, film->thickness_over_lambda)
                          : fresnel_dielectric(glm::dot(wo, wm), eta);
    if (reflect) {
        const float f = m.d(wm) * m.g(wo, wi) * fr / std::fabs(4.0f * cos_i * cos_o);
        const float pdf = m.d_visible(wo, wm) / (4.0f * std::fabs(glm::dot(wo, wm))) * fr;
        return {f * std::fabs(cos_i), pdf, fr};
    }
    const float s = glm::dot(wi, wm) + glm::dot(wo, wm) / etap;
    const float denom = s * s * cos_i * cos_o;
    if (denom == 0.0f) return {};
    float ft = m.d(wm) * (1.0f - fr) * m.g(wo, wi) * std::fabs(glm::dot(wi, wm) * glm::dot(wo, wm) / denom);
    ft /= etap * etap;  // radiance is compressed/expanded across the interface
    const float dwm_dwi = std::fabs(glm::dot(wi, wm)) / (s * s);
    const float pdf = m.d_visible(wo, wm) * dwm_dwi * (1.0f - fr);
    return {ft * std::fabs(cos_i), pdf, 1.0f - fr};
}

}  // namespace iris::detail
