#pragma once
/// \file
/// \brief `smooth_dielectric`: the BxDF of a `material::dielectric` that is smooth (or an
/// invisible interface of index 1): delta reflection and refraction, weighted by Fresnel.

#include <cstddef>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/materials/bxdf.hpp"
#include "iris/render/materials/fresnel.hpp"
#include "iris/render/scene.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief The hero reflects with probability F(λ₀) and refracts otherwise. A reflection
/// keeps every wavelength (had λ_k been the hero, it would have reflected with probability
/// F(λ_k)); a refraction through a dispersive interface keeps the hero alone (docs/method.md §3).
/// The bins follow with F(λ_b) or (1 − F(λ_b))/η′_b², read from tabulated η² and 1/η².
/// Under a thin film F is the film's reflectance (`fresnel_film_dielectric`): the
/// directions are the bare interface's, the weights the film's.
struct smooth_dielectric : delta_bxdf {
    const material::dielectric& data;

    explicit smooth_dielectric(const material::dielectric& d) noexcept : data(d) {}

    static constexpr bool reads_albedo = false;
    static constexpr bool reads_eta = true;

    const ior_model& ior() const noexcept { return data.ior; }
    const material::thin_film* film() const noexcept { return data.film ? &*data.film : nullptr; }

    template <std::size_t N, class S>
    std::optional<bsdf_sample<N>> sample(const glm::vec3& wo, const sampled_wavelengths<N>& /*wl*/, float u_lobe,
                                         glm::vec2 /*u*/, const S& s) const noexcept {
        const auto& eta = s.eta();
        const bool dispersive = is_dispersive(data.ior);
        const float co = wo.z;
        sampled_spectrum<N> fr;
        if (data.film) {
            const auto& l = s.wavelength();
            const auto& nf = s.film_eta();
            const auto d = static_cast<float>(data.film->thickness_nm);
            for (std::size_t k = 0; k < N; ++k) fr[k] = detail::fresnel_film_dielectric(co, eta[k], nf[k], d / l[k]);
        } else {
            for (std::size_t k = 0; k < N; ++k) fr[k] = detail::fresnel_dielectric(co, eta[k]);
        }
        bsdf_sample<N> out;
        out.delta = true;
        if (u_lobe < fr[0]) {
            out.wi = {-wo.x, -wo.y, wo.z};
            out.kind = lobe::reflection;
            out.f_cos = fr;
            out.pdf = fr;  // had λ_k been the hero, it would have reflected with probability F(λ_k)
            return out;
        }
        const auto t = detail::refract(wo, {0.0f, 0.0f, 1.0f}, eta[0]);
        if (!t) return std::nullopt;  // unreachable: TIR means F = 1
        out.wi = t->wt;
        out.kind = lobe::transmission;
        out.eta = co > 0.0f ? eta[0] : 1.0f / eta[0];
        for (std::size_t k = 0; k < N; ++k) {
            if (dispersive && k > 0) continue;  // λ-dependent direction: secondaries terminate
            const float e = co > 0.0f ? eta[k] : 1.0f / eta[k];
            out.f_cos[k] = (1.0f - fr[k]) / (e * e);
            out.pdf[k] = 1.0f - fr[k];
        }
        return out;
    }

    template <std::size_t M, class S>
    sampled_spectrum<M> follow(const glm::vec3& wo, const glm::vec3& /*wi*/, lobe kind, const S& s) const noexcept {
        if constexpr (film_source<S>)  // (every estimator's; bench/bterm_bench.cpp's film-free glass reads η² alone)
            if (data.film) return detail::film_follow<M>(wo.z, kind, s.eta(), s.wavelength(), s.film_eta(), data.film->thickness_nm);
        return detail::fresnel_follow<M>(wo.z, kind, s.eta2(), s.inv_eta2());
    }
};

}  // namespace iris
