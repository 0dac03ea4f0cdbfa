#pragma once
/// \file
/// \brief `specular_conductor`: the BxDF of `material::conductor`, a perfect mirror with
/// a spectral reflectance.

#include <cstddef>
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/materials/bxdf.hpp"
#include "iris/render/scene.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief A delta reflection with weight R(λ) at every wavelength: its direction does not
/// depend on λ, so every wavelength (and every bin) follows the hero with weight R.
struct specular_conductor : delta_bxdf {
    const material::conductor& data;

    explicit specular_conductor(const material::conductor& d) noexcept : data(d) {}

    static constexpr bool reads_albedo = true;
    static constexpr bool reads_eta = false;

    const tabulated_spectrum& reflectance() const noexcept { return data.reflectance; }

    template <std::size_t N, class S>
    std::optional<bsdf_sample<N>> sample(const glm::vec3& wo, const sampled_wavelengths<N>& /*wl*/, float /*u_lobe*/,
                                         glm::vec2 /*u*/, const S& s) const noexcept {
        bsdf_sample<N> out;
        out.wi = {-wo.x, -wo.y, wo.z};  // the mirror about the local normal
        out.f_cos = sampled_spectrum<N>(s.albedo());
        out.pdf = sampled_spectrum<N>(1.0f);
        out.kind = lobe::reflection;
        out.delta = true;
        return out;
    }

    template <std::size_t M, class S>
    sampled_spectrum<M> follow(const glm::vec3&, const glm::vec3&, lobe, const S& s) const noexcept {
        return sampled_spectrum<M>(s.albedo());
    }
};

}  // namespace iris
