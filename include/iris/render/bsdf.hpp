#pragma once
/// \file
/// \brief The scene's materials as BSDFs, one call at a time: each function visits the
/// material's BxDF (iris/render/materials/materials.hpp) with the scene's own spectra at
/// `wl`. For the independent estimator and the tests; the path integrator visits once per
/// vertex and reads its lattice tables instead.

#include <cstddef>
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/materials/materials.hpp"
#include "iris/render/scene.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief f(ωo, ωi, λ_k)·|cos θi| for non-delta materials (0 for delta ones).
template <std::size_t N>
sampled_spectrum<N> bsdf_eval(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi,
                              const sampled_wavelengths<N>& wl) noexcept {
    return visit_bxdf(mat, [&](const auto& b) { return b.template f_cos<N>(n, wo, wi, scene_spectra(b, wl)); });
}

/// \brief p(ωi | ωo, λ_k) in solid angle for non-delta materials (0 for delta ones).
template <std::size_t N>
sampled_spectrum<N> bsdf_pdf(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi,
                             const sampled_wavelengths<N>& wl) noexcept {
    return visit_bxdf(mat, [&](const auto& b) { return b.template pdf<N>(n, wo, wi, scene_spectra(b, wl)); });
}

/// \brief Sample a direction with the hero wavelength wl[0]; report f·|cos| and pdf for
/// every wavelength along it. `u_lobe` picks reflection/transmission, `u` the direction.
/// Returns nothing when the sample is absorbed or degenerate.
template <std::size_t N>
std::optional<bsdf_sample<N>> bsdf_sample_hero(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo,
                                               const sampled_wavelengths<N>& wl, float u_lobe, glm::vec2 u) noexcept {
    return visit_bxdf(mat, [&](const auto& b) { return b.template sample<N>(n, wo, wl, u_lobe, u, scene_spectra(b, wl)); });
}

}  // namespace iris
