#pragma once
/// \file
/// \brief `specular_conductor`: the BxDF of `material::conductor`, a perfect mirror whose
/// reflectance is either the exact Fresnel reflectance of a complex index η + ik (a named
/// or tabulated metal) or an angle-independent spectral reflectance.

#include <cmath>
#include <cstddef>
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/materials/bxdf.hpp"
#include "iris/render/materials/fresnel.hpp"
#include "iris/render/scene.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief A delta reflection with weight F(λ) at every wavelength: F(|cos θo|, η(λ), k(λ))
/// with a complex index, R(λ) without. Its direction does not depend on λ, so every
/// wavelength (and every bin) follows the hero with its own weight.
struct specular_conductor : delta_bxdf {
    const material::conductor& data;

    explicit specular_conductor(const material::conductor& d) noexcept : data(d) {}

    static constexpr bool reads_albedo = true;
    static constexpr bool reads_eta = false;
    /// reads η and k (`eta()`, `k()`) when `has_ior()`
    static constexpr bool reads_conductor = true;

    const tabulated_spectrum& reflectance() const noexcept { return data.reflectance; }
    bool has_ior() const noexcept { return data.ior.has_value(); }
    const tabulated_spectrum& conductor_eta() const noexcept { return data.ior->eta; }
    const tabulated_spectrum& conductor_k() const noexcept { return data.ior->k; }

    template <std::size_t N, class S>
    std::optional<bsdf_sample<N>> sample(const glm::vec3& wo, const sampled_wavelengths<N>& /*wl*/, float /*u_lobe*/,
                                         glm::vec2 /*u*/, const S& s) const noexcept {
        bsdf_sample<N> out;
        out.wi = {-wo.x, -wo.y, wo.z};  // the mirror about the local normal
        out.f_cos = weight<N>(wo, s);
        out.pdf = sampled_spectrum<N>(1.0f);
        out.kind = lobe::reflection;
        out.delta = true;
        return out;
    }

    template <std::size_t M, class S>
    sampled_spectrum<M> follow(const glm::vec3& wo, const glm::vec3&, lobe, const S& s) const noexcept {
        return weight<M>(wo, s);
    }

private:
    /// F(λ_k) at the N wavelengths of `s`.
    template <std::size_t N, class S>
    sampled_spectrum<N> weight(const glm::vec3& wo, const S& s) const noexcept {
        if (!has_ior()) return sampled_spectrum<N>(s.albedo());
        const auto& e = s.eta();
        const auto& k = s.k();
        const float c = std::fabs(wo.z);
        sampled_spectrum<N> f;
        for (std::size_t i = 0; i < N; ++i) f[i] = detail::fresnel_conductor(c, e[i], k[i]);
        return f;
    }
};

}  // namespace iris
