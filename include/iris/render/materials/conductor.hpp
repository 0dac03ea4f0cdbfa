#pragma once
/// \file
/// \brief The BxDFs of `material::conductor`: `specular_conductor`, a perfect mirror, and
/// `rough_conductor`, a GGX microfacet reflector (roughness α ≥ `smooth_alpha`). Both
/// reflect with the exact Fresnel reflectance of a complex index η + ik (a named or
/// tabulated metal) or with an angle-independent spectral reflectance.

#include <cmath>
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

/// \brief What both conductor BxDFs read: the reflectance, or η and k, and the Fresnel
/// weight they make at the N wavelengths of a spectra source.
struct conductor_spectra {
    const material::conductor& data;

    static constexpr bool reads_albedo = true;
    static constexpr bool reads_eta = false;
    /// reads η and k (`eta()`, `k()`) when `has_ior()`
    static constexpr bool reads_conductor = true;

    const tabulated_spectrum& reflectance() const noexcept { return data.reflectance; }
    bool has_ior() const noexcept { return data.ior.has_value(); }
    const tabulated_spectrum& conductor_eta() const noexcept { return data.ior->eta; }
    const tabulated_spectrum& conductor_k() const noexcept { return data.ior->k; }
    const material::thin_film* film() const noexcept { return data.film ? &*data.film : nullptr; }

    /// F(c, η(λ_k), k(λ_k)) with a complex index (under a film: the film-on-metal
    /// reflectance, `film_reflectance`), R(λ_k) without, each times `scale`;
    /// c = |cos| of the angle of incidence on the (micro)surface.
    template <std::size_t N, class S>
    sampled_spectrum<N> fresnel(float c, const S& s, float scale = 1.0f) const noexcept {
        sampled_spectrum<N> f;
        if (!has_ior()) {
            const auto& r = s.albedo();
            for (std::size_t i = 0; i < N; ++i) f[i] = scale * r[i];
            return f;
        }
        const auto& e = s.eta();
        const auto& k = s.k();
        if constexpr (film_source<S>)  // (a coat's base, the one source without, has no film)
            if (data.film) {
                const auto& l = s.wavelength();
                const auto& nf = s.film_eta();
                const auto d = static_cast<float>(data.film->thickness_nm);
                for (std::size_t i = 0; i < N; ++i)
                    f[i] = scale * detail::film_reflectance(c, nf[i], d / l[i], {e[i], k[i]});
                return f;
            }
        for (std::size_t i = 0; i < N; ++i) f[i] = scale * detail::fresnel_conductor(c, e[i], k[i]);
        return f;
    }
};

/// \brief A delta reflection with weight F(λ) at every wavelength: F(|cos θo|, η(λ), k(λ))
/// with a complex index, R(λ) without. Its direction does not depend on λ, so every
/// wavelength (and every bin) follows the hero with its own weight.
struct specular_conductor : delta_bxdf, conductor_spectra {
    explicit specular_conductor(const material::conductor& d) noexcept : conductor_spectra{d} {}

    template <std::size_t N, class S>
    std::optional<bsdf_sample<N>> sample(const glm::vec3& wo, const sampled_wavelengths<N>& /*wl*/, float /*u_lobe*/,
                                         glm::vec2 /*u*/, const S& s) const noexcept {
        bsdf_sample<N> out;
        out.wi = {-wo.x, -wo.y, wo.z};  // the mirror about the local normal
        out.f_cos = fresnel<N>(std::fabs(wo.z), s);
        out.pdf = sampled_spectrum<N>(1.0f);
        out.kind = lobe::reflection;
        out.delta = true;
        return out;
    }

    template <std::size_t M, class S>
    sampled_spectrum<M> follow(const glm::vec3& wo, const glm::vec3&, lobe, const S& s) const noexcept {
        return fresnel<M>(std::fabs(wo.z), s);
    }
};

/// \brief Isotropic GGX reflection (Torrance–Sparrow with Smith's height-correlated
/// masking–shadowing, as pbrt-v4's conductor): f(ωo, ωi, λ) = D(ωm) G(ωo, ωi) F(|ωo·ωm|,
/// λ) / (4 |cos θo| |cos θi|), ωm the half vector. The hero samples a visible normal
/// (Heitz 2018) and reflects about it; the direction does not depend on λ, so every
/// wavelength has the same pdf D_ωo(ωm)/(4|ωo·ωm|) and keeps it (no secondary ends
/// here), and the bins follow with f·|cos|. ωo and ωi on opposite sides reflect nothing.
struct rough_conductor : conductor_spectra, parts_of_eval<rough_conductor> {
    explicit rough_conductor(const material::conductor& d) noexcept : conductor_spectra{d} {}

    static constexpr bool delta = false;

    detail::ggx distribution() const noexcept { return {data.roughness}; }

    template <std::size_t N, class S>
    bsdf_value<N> eval(const glm::vec3& wo, const glm::vec3& wi, const S& s) const noexcept {
        const auto wm = half_vector(wo, wi);
        if (!wm) return {};
        return value<N>(wo, wi, *wm, s);
    }

    template <std::size_t N, class S>
    std::optional<bsdf_sample<N>> sample(const glm::vec3& wo, const sampled_wavelengths<N>& /*wl*/, float /*u_lobe*/,
                                         glm::vec2 u, const S& s) const noexcept {
        if (wo.z == 0.0f) return std::nullopt;
        const glm::vec3 wi = reflect_about(wo, distribution().sample_visible(wo, u));
        // f and pdf as `eval` gives them for the direction returned (the half vector
        // recomputed from it): light sampling's MIS weight for that direction is the same
        const auto v = eval<N>(wo, wi, s);
        if (!(v.pdf[0] > 0.0f)) return std::nullopt;
        bsdf_sample<N> out;
        out.wi = wi;
        out.f_cos = v.f_cos;
        out.pdf = v.pdf;
        out.kind = lobe::reflection;
        return out;
    }

    template <std::size_t M, class S>
    sampled_spectrum<M> follow(const glm::vec3& wo, const glm::vec3& wi, lobe /*kind*/, const S& s) const noexcept {
        return this->template f_cos<M>(wo, wi, s);
    }

private:
    /// The microfacet normal that reflects ωo into ωi, on the +z side; none when they are
    /// on opposite sides or opposite each other.
    static std::optional<glm::vec3> half_vector(const glm::vec3& wo, const glm::vec3& wi) noexcept {
        if (!(wo.z * wi.z > 0.0f)) return std::nullopt;
        glm::vec3 wm = wo + wi;
        const float len2 = glm::dot(wm, wm);
        if (!(len2 > 0.0f)) return std::nullopt;
        wm /= std::sqrt(len2);
        return wm.z < 0.0f ? -wm : wm;
    }

    /// f·|cos θi| and pdf of (ωo, ωi) with half vector ωm: one evaluation of D, G and D_ωo
    /// for every wavelength, which differ only in F.
    template <std::size_t N, class S>
    bsdf_value<N> value(const glm::vec3& wo, const glm::vec3& wi, const glm::vec3& wm, const S& s) const noexcept {
        const detail::ggx m = distribution();
        const float c = std::fabs(glm::dot(wo, wm));
        if (!(c > 0.0f)) return {};
        const float d = m.d(wm);
        const float geometric = d * m.g(wo, wi) / (4.0f * std::fabs(wo.z));  // f·|cos θi| / F
        const float p = m.d_visible(wo, wm) / (4.0f * c);
        bsdf_value<N> out;
        out.f_cos = fresnel<N>(c, s, geometric);
        out.pdf = sampled_spectrum<N>(p);
        return out;
    }
};

}  // namespace iris
