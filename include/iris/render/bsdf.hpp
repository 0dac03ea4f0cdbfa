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
#include "iris/spectrum/rgb_upsampling.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// A textured material's reflectance comes as the texture's weights at the hit (`texel`,
/// iris/render/texture.hpp), mixed here from the analytic basis functions of
/// iris/spectrum/rgb_upsampling.hpp rather than the integrator's tables.
///
/// Directions are in world space and unit; the shading frame `fr` (its `n` the shading
/// normal) takes them to the BxDF's local frame and the sampled one back. The overloads
/// taking a normal `n` build the frame around it (`frame::from_normal`).

/// \brief The spectra of BxDF `b` at `wl`: `scene_spectra`, with the reflectance of a
/// texture's weights `texel` where there is one.
template <std::size_t N, bxdf B>
sampled_spectra<N> hit_spectra(const B& b, const sampled_wavelengths<N>& wl, const std::optional<glm::vec3>& texel) noexcept {
    if constexpr (B::reads_albedo) {
        if (texel) {
            sampled_spectrum<N> r;
            for (std::size_t k = 0; k < N; ++k) {
                const auto l = static_cast<double>(wl[k]);
                r[k] = static_cast<float>(texel->x * rgb_upsampling::red_basis(l) + texel->y * rgb_upsampling::green_basis(l) +
                                          texel->z * rgb_upsampling::blue_basis(l));
            }
            return sampled_spectra<N>::with_albedo(r);
        }
    }
    return scene_spectra(b, wl);
}

/// \brief f(ωo, ωi, λ_k)·|cos θi| for non-delta materials (0 for delta ones).
template <std::size_t N>
sampled_spectrum<N> bsdf_eval(const material_desc& mat, const frame& fr, const glm::vec3& wo, const glm::vec3& wi,
                              const sampled_wavelengths<N>& wl, const std::optional<glm::vec3>& texel = std::nullopt) noexcept {
    const glm::vec3 lo = fr.to_local(wo), li = fr.to_local(wi);
    return visit_bxdf(mat, [&](const auto& b) { return b.template f_cos<N>(lo, li, hit_spectra(b, wl, texel)); });
}

/// \brief p(ωi | ωo, λ_k) in solid angle for non-delta materials (0 for delta ones).
template <std::size_t N>
sampled_spectrum<N> bsdf_pdf(const material_desc& mat, const frame& fr, const glm::vec3& wo, const glm::vec3& wi,
                             const sampled_wavelengths<N>& wl, const std::optional<glm::vec3>& texel = std::nullopt) noexcept {
    const glm::vec3 lo = fr.to_local(wo), li = fr.to_local(wi);
    return visit_bxdf(mat, [&](const auto& b) { return b.template pdf<N>(lo, li, hit_spectra(b, wl, texel)); });
}

/// \brief Sample a direction with the hero wavelength wl[0]; report f·|cos| and pdf for
/// every wavelength along it (its `wi` in world space, unit). `u_lobe` picks
/// reflection/transmission, `u` the direction. Returns nothing when the sample is absorbed
/// or degenerate.
template <std::size_t N>
std::optional<bsdf_sample<N>> bsdf_sample_hero(const material_desc& mat, const frame& fr, const glm::vec3& wo,
                                               const sampled_wavelengths<N>& wl, float u_lobe, glm::vec2 u,
                                               const std::optional<glm::vec3>& texel = std::nullopt) noexcept {
    const glm::vec3 lo = fr.to_local(wo);
    auto s = visit_bxdf(mat, [&](const auto& b) { return b.template sample<N>(lo, wl, u_lobe, u, hit_spectra(b, wl, texel)); });
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
