#pragma once
/// \file
/// \brief `lambertian`: the BxDF of `material::diffuse`, a two-sided Lambertian reflector.

#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/materials/bxdf.hpp"
#include "iris/render/scene.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief f(λ) = R(λ)/π on ωo's side of the surface (two-sided), 0 across it; sampled
/// cosine-weighted. Separable: f·|cos θi| = R(λ)·`cos_factor`.
struct lambertian {
    const material::diffuse& data;

    static constexpr bool delta = false;
    static constexpr bool reads_albedo = true;
    static constexpr bool reads_eta = false;

    const tabulated_spectrum& reflectance() const noexcept { return data.reflectance; }

    /// \brief |cos θi|/π on ωo's side of the surface, 0 across it.
    static float cos_factor(const glm::vec3& wo, const glm::vec3& wi) noexcept {
        return wo.z * wi.z > 0.0f ? std::fabs(wi.z) * detail::inv_pi : 0.0f;
    }

    template <std::size_t N, class S>
    sampled_spectrum<N> f_cos(const glm::vec3& wo, const glm::vec3& wi, const S& s) const noexcept {
        const float c = cos_factor(wo, wi);
        if (c == 0.0f) return {};
        return sampled_spectrum<N>(s.albedo()) * c;
    }

    template <std::size_t N, class S>
    sampled_spectrum<N> pdf(const glm::vec3& wo, const glm::vec3& wi, const S& /*s*/) const noexcept {
        return sampled_spectrum<N>(cos_factor(wo, wi));
    }

    template <std::size_t N, class S>
    bsdf_value<N> eval(const glm::vec3& wo, const glm::vec3& wi, const S& s) const noexcept {
        const float c = cos_factor(wo, wi);
        if (c == 0.0f) return {};
        return {sampled_spectrum<N>(s.albedo()) * c, sampled_spectrum<N>(c)};
    }

    template <std::size_t N, class S>
    std::optional<bsdf_sample<N>> sample(const glm::vec3& wo, const sampled_wavelengths<N>& /*wl*/, float /*u_lobe*/,
                                         glm::vec2 u, const S& s) const noexcept {
        if (wo.z == 0.0f) return std::nullopt;
        // cosine-weighted hemisphere on wo's side (Malley: concentric disk → lift)
        const float r = std::sqrt(u.x), phi = 2.0f * std::numbers::pi_v<float> * u.y;
        const float x = r * std::cos(phi), y = r * std::sin(phi), z = std::sqrt(std::max(0.0f, 1.0f - u.x));
        if (!(z > 0.0f)) return std::nullopt;
        bsdf_sample<N> out;
        out.wi = {x, y, wo.z > 0.0f ? z : -z};
        out.f_cos = sampled_spectrum<N>(s.albedo()) * (z * detail::inv_pi);
        out.pdf = sampled_spectrum<N>(z * detail::inv_pi);
        out.kind = lobe::diffuse;
        return out;
    }

    template <std::size_t M, class S>
    sampled_spectrum<M> follow(const glm::vec3& wo, const glm::vec3& wi, lobe /*kind*/, const S& s) const noexcept {
        return f_cos<M>(wo, wi, s);
    }
};

}  // namespace iris
