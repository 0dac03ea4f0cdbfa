#pragma once
/// \file
/// \brief The scene's materials as BSDFs, one call at a time: each function visits the
/// material's BxDF (iris/render/materials/materials.hpp) with the scene's own spectra at
/// `wl`. For the independent estimator and the tests; the path integrator visits once per
/// vertex and reads its lattice tables instead.

#include <cstddef>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/materials/materials.hpp"
#include "iris/render/scene.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// Directions are in world space and unit; the shading frame `fr` (its `n` the shading
/// normal) takes them to the BxDF's local frame and the sampled one back. The overloads
/// taking a normal `n` build the frame around it (`frame::from_normal`).

/// \brief f(ωo, ωi, λ_k)·|cos θi| for non-delta materials (0 for delta ones).
template <std::size_t N>
sampled_spectrum<N> bsdf_eval(const material_desc& mat, const frame& fr, const glm::vec3& wo, const glm::vec3& wi,
                              const sampled_wavelengths<N>& wl) noexcept {
    const glm::vec3 lo = fr.to_local(wo), li = fr.to_local(wi);
    return visit_bxdf(mat, [&](const auto& b) { return b.template f_cos<N>(lo, li, scene_spectra(b, wl)); });
}

/// \brief p(ωi | ωo, λ_k) in solid angle for non-delta materials (0 for delta ones).
template <std::size_t N>
sampled_spectrum<N> bsdf_pdf(const material_desc& mat, const frame& fr, const glm::vec3& wo, const glm::vec3& wi,
                             const sampled_wavelengths<N>& wl) noexcept {
    const glm::vec3 lo = fr.to_local(wo), li = fr.to_local(wi);
    return visit_bxdf(mat, [&](const auto& b) { return b.template pdf<N>(lo, li, scene_spectra(b, wl)); });
}

/// \brief Sample a direction with the hero wavelength wl[0]; report f·|cos| and pdf for
/// every wavelength along it (its `wi` in world space, unit). `u_lobe` picks
/// reflection/transmission, `u` the direction. Returns nothing when the sample is absorbed
/// or degenerate.
template <std::size_t N>
std::optional<bsdf_sample<N>> bsdf_sample_hero(const material_desc& mat, const frame& fr, const glm::vec3& wo,
                                               const sampled_wavelengths<N>& wl, float u_lobe, glm::vec2 u) noexcept {
    const glm::vec3 lo = fr.to_local(wo);
    auto s = visit_bxdf(mat, [&](const auto& b) { return b.template sample<N>(lo, wl, u_lobe, u, scene_spectra(b, wl)); });
    if (s) s->wi = glm::normalize(fr.to_world(s->wi));
    return s;
}

template <std::size_t N>
sampled_spectrum<N> bsdf_eval(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi,
                              const sampled_wavelengths<N>& wl) noexcept {
    return bsdf_eval(mat, frame::from_normal(n), wo, wi, wl);
}
template <std::size_t N>
sampled_spectrum<N> bsdf_pdf(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi,
                             const sampled_wavelengths<N>& wl) noexcept {
    return bsdf_pdf(mat, frame::from_normal(n), wo, wi, wl);
}
template <std::size_t N>
std::optional<bsdf_sample<N>> bsdf_sample_hero(const material_desc& mat, const glm::vec3& n, const glm::vec3& wo,
                                               const sampled_wavelengths<N>& wl, float u_lobe, glm::vec2 u) noexcept {
    return bsdf_sample_hero(mat, frame::from_normal(n), wo, wl, u_lobe, u);
}

}  // namespace iris
