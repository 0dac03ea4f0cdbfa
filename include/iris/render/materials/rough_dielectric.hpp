#pragma once
/// \file
/// \brief `rough_dielectric`: the BxDF of a `material::dielectric` with GGX roughness
/// α ≥ `smooth_alpha` (Walter et al. 2007, pbrt-v4's formulation).

#include <cstddef>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/materials/bxdf.hpp"
#include "iris/render/materials/fresnel.hpp"
#include "iris/render/materials/microfacet.hpp"
#include "iris/render/scene.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief The hero samples a visible microfacet normal and reflects or refracts through it
/// with probability F(λ₀); every wavelength keeps a finite p(ωi | λ_k) (rough events never
/// terminate the secondaries, docs/method.md §3), and the bins follow with f·|cos|. Under a
/// thin film F is the film's reflectance at the microfacet (`fresnel_film_dielectric`).
struct rough_dielectric : parts_of_eval<rough_dielectric> {
    const material::dielectric& data;

    explicit rough_dielectric(const material::dielectric& d) noexcept : data(d) {}

    static constexpr bool delta = false;
    static constexpr bool reads_albedo = false;
    static constexpr bool reads_eta = true;

    const ior_model& ior() const noexcept { return data.ior; }
    const material::thin_film* film() const noexcept { return data.film ? &*data.film : nullptr; }
    detail::ggx distribution() const noexcept { return {data.roughness}; }

    /// \brief f·|cos θi| and pdf from one evaluation of the microfacet terms per wavelength.
    template <std::size_t N, class S>
    bsdf_value<N> eval(const glm::vec3& wo, const glm::vec3& wi, const S& s) const noexcept {
        const detail::ggx m = distribution();
        const auto& e = s.eta();
        bsdf_value<N> out;
        for (std::size_t k = 0; k < N; ++k) {
            const auto v = value(m, wo, wi, e[k], k, s);
            out.f_cos[k] = v.f_cos;
            out.pdf[k] = v.pdf;
        }
        return out;
    }

    template <std::size_t N, class S>
    std::optional<bsdf_sample<N>> sample(const glm::vec3& wo, const sampled_wavelengths<N>& /*wl*/, float u_lobe,
                                         glm::vec2 u, const S& s) const noexcept {
        const auto& eta = s.eta();
        const glm::vec3 lo = wo;
        if (lo.z == 0.0f) return std::nullopt;
        const detail::ggx m = distribution();
        const glm::vec3 wm = m.sample_visible(lo, u);
        const float f0 = data.film ? detail::fresnel_film_dielectric(glm::dot(lo, wm), eta[0], layer(0, s).index,
                                                                     layer(0, s).thickness_over_lambda)
                                   : detail::fresnel_dielectric(glm::dot(lo, wm), eta[0]);
        bsdf_sample<N> out;
        glm::vec3 li;
        if (u_lobe < f0) {
            li = reflect_about(lo, wm);
            if (li.z * lo.z <= 0.0f) return std::nullopt;
            out.kind = lobe::reflection;
        } else {
            const auto t = detail::refract(lo, wm, eta[0]);
            if (!t || t->wt.z * lo.z >= 0.0f || t->wt.z == 0.0f) return std::nullopt;
            li = t->wt;
            out.kind = lobe::transmission;
            out.eta = lo.z > 0.0f ? eta[0] : 1.0f / eta[0];
        }
        out.wi = li;
        for (std::size_t k = 0; k < N; ++k) {
            const auto v = value(m, lo, li, eta[k], k, s);
            out.f_cos[k] = v.f_cos;
            out.pdf[k] = v.pdf;
        }
        if (!(out.pdf[0] > 0.0f)) return std::nullopt;
        return out;
    }

    template <std::size_t M, class S>
    sampled_spectrum<M> follow(const glm::vec3& wo, const glm::vec3& wi, lobe /*kind*/, const S& s) const noexcept {
        return this->template f_cos<M>(wo, wi, s);
    }

private:
    /// The film at wavelength k of the spectra source (only called when there is one).
    template <class S>
    detail::film_layer layer(std::size_t k, const S& s) const noexcept {
        return {s.film_eta()[k], static_cast<float>(data.film->thickness_nm) / s.wavelength()[k]};
    }
    template <class S>
    detail::rough_value value(const detail::ggx& m, const glm::vec3& wo, const glm::vec3& wi, float eta, std::size_t k,
                              const S& s) const noexcept {
        if (!data.film) return detail::rough_dielectric_value(m, wo, wi, eta);
        const detail::film_layer f = layer(k, s);
        return detail::rough_dielectric_value(m, wo, wi, eta, &f);
    }
};

}  // namespace iris
