#pragma once
/// \file
/// \brief Homogeneous scattering media (docs/method.md §10): the Henyey–Greenstein phase
/// function as a BxDF (`hg_phase`), and one free flight of the hero path through a medium
/// with the spectral MIS over the C hero-rotated wavelengths (`medium_flight`).
///
/// A flight samples the distance to the next scattering on the hero's σ_s(λ₀) alone,
/// p₀(t) = σ_s,0 e^{−σ_s,0 t}, and carries absorption as a weight, e^{−σ_a t} (weighted
/// tracking: in a medium that only absorbs nothing is sampled, and the path keeps the
/// Beer–Lambert factor of absorbing glass, docs/method.md §8). Every wavelength's own density of
/// the same event, p_k, enters the path's ratios ρ_k = p_k/p₀ (iris/render/integrator.hpp), so
/// the estimator F_R = Σ_j β_j / Σ_k ρ_k is the balance heuristic over the C wavelengths'
/// distance sampling too: a wavelength that scatters much less (or more) than the hero does
/// not add the colour noise of single-wavelength tracking. Homogeneous media need no null
/// collisions (the majorant is σ_s itself).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/materials/bxdf.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief The Henyey–Greenstein phase function of the angle between the incoming propagation
/// direction and the scattered one, cos θ (θ = 0: straight on), asymmetry g ∈ (−1, 1); it
/// integrates to 1 over the sphere.
inline float henyey_greenstein(float cos_theta, float g) noexcept {
    const float denom = 1.0f + g * g - 2.0f * g * cos_theta;
    return (1.0f - g * g) / (4.0f * std::numbers::pi_v<float> * denom * std::sqrt(std::fmax(denom, 0.0f)));
}

/// \brief cos θ distributed as Henyey–Greenstein with asymmetry g, from u ∈ [0, 1)
/// (the inverse of its CDF; isotropic below |g| = 10⁻³, where the closed form cancels).
inline float sample_henyey_greenstein_cos(float g, float u) noexcept {
    if (std::fabs(g) < 1e-3f) return 1.0f - 2.0f * u;
    const float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
    const float c = (1.0f + g * g - s * s) / (2.0f * g);
    return std::fmin(1.0f, std::fmax(-1.0f, c));
}

/// \brief A medium's scattering as a BxDF (iris/render/materials/bxdf.hpp): f = p_HG(ωo, ωi),
/// no cosine (a medium point has no surface), sampled exactly (f/p = 1). It takes world
/// directions: the integrators give it the identity frame. ωo points back along the ray, so
/// the angle is between −ωo and ωi.
struct hg_phase {
    float g = 0.0f;

    static constexpr bool delta = false;
    static constexpr bool reads_albedo = false;
    static constexpr bool reads_eta = false;
    static constexpr bool is_phase = true;  ///< the B term's bins follow it with weight 1 (propagation.hpp)

    float value(const glm::vec3& wo, const glm::vec3& wi) const noexcept { return henyey_greenstein(-glm::dot(wo, wi), g); }

    template <std::size_t N, class S>
    sampled_spectrum<N> f_cos(const glm::vec3& wo, const glm::vec3& wi, const S&) const noexcept {
        return sampled_spectrum<N>(value(wo, wi));
    }
    template <std::size_t N, class S>
    sampled_spectrum<N> pdf(const glm::vec3& wo, const glm::vec3& wi, const S&) const noexcept {
        return sampled_spectrum<N>(value(wo, wi));
    }
    template <std::size_t N, class S>
    bsdf_value<N> eval(const glm::vec3& wo, const glm::vec3& wi, const S&) const noexcept {
        const sampled_spectrum<N> v(value(wo, wi));
        return {v, v};
    }
    template <std::size_t N, class S>
    std::optional<bsdf_sample<N>> sample(const glm::vec3& wo, const sampled_wavelengths<N>&, float /*u_lobe*/,
                                         glm::vec2 u, const S&) const noexcept {
        const float c = sample_henyey_greenstein_cos(g, u.x);
        const float s = std::sqrt(std::fmax(0.0f, 1.0f - c * c));
        const float phi = 2.0f * std::numbers::pi_v<float> * u.y;
        const frame f = frame::from_normal(-wo);
        bsdf_sample<N> out;
        out.wi = glm::normalize(f.to_world({s * std::cos(phi), s * std::sin(phi), c}));
        const float p = henyey_greenstein(c, g);
        out.f_cos = sampled_spectrum<N>(p);
        out.pdf = sampled_spectrum<N>(p);
        out.kind = lobe::diffuse;
        return out;
    }
    template <std::size_t N, class S>
    sampled_spectrum<N> follow(const glm::vec3& wo, const glm::vec3& wi, lobe, const S& s) const noexcept {
        return f_cos<N>(wo, wi, s);
    }
};

/// \brief Is B a medium's phase function (`hg_phase`)?
template <class B>
inline constexpr bool is_phase_v = requires { requires B::is_phase; };

/// \brief The coefficients of one medium at C wavelengths (per scene unit).
template <std::size_t C>
struct medium_coefficients {
    sampled_spectrum<C> sigma_a, sigma_s;
    float g = 0.0f;
    bool scatters = false;  ///< σ_s is not zero everywhere (otherwise only Beer–Lambert applies)
};

/// \brief One free flight of the hero path through a homogeneous medium, up to the surface at
/// t_max (∞ if the ray escapes): where it ends and what it multiplies the path's weights by.
template <std::size_t C>
struct flight {
    bool scattered = false;
    float t = 0.0f;             ///< the distance flown: to the scattering, or t_max
    sampled_spectrum<C> beta;   ///< β_k ← β_k · this: f_k(event) / p₀(event)
    sampled_spectrum<C> ratio;  ///< ρ_k ← ρ_k · this: p_k(event) / p₀(event)
    float hero_pass = 1.0f;     ///< passing through: the hero's probability of it, e^{−σ_s,0 t_max}
};

/// \brief e^{−x·t} for x·t ≥ 0 or not, with x = 0 → 1 also for t = ∞.
inline float exp_neg(float x, float t) noexcept { return x != 0.0f ? std::exp(-x * t) : 1.0f; }

/// \brief The flight of `m`'s hero path from a point, the surface ahead at t_max, u ∈ [0, 1).
/// The hero (index 0) scatters at t = −ln(1 − u)/σ_s,0 if that is before t_max:
///   β_k ← σ_s,k e^{−σ_t,k t} / (σ_s,0 e^{−σ_s,0 t}),  ρ_k ← σ_s,k e^{−σ_s,k t} / (σ_s,0 e^{−σ_s,0 t});
/// else it reaches the surface:
///   β_k ← e^{−σ_t,k t_max} / e^{−σ_s,0 t_max},      ρ_k ← e^{−σ_s,k t_max} / e^{−σ_s,0 t_max}.
/// The exponents are taken as differences, so the factors stay finite where either
/// exponential alone would underflow.
template <std::size_t C>
flight<C> medium_flight(const medium_coefficients<C>& m, float t_max, float u) noexcept {
    flight<C> out;
    const float s0 = m.sigma_s[0];
    float t = std::numeric_limits<float>::infinity();
    if (s0 > 0.0f) t = -std::log1p(-u) / s0;
    if (t < t_max) {
        out.scattered = true;
        out.t = t;
        for (std::size_t k = 0; k < C; ++k) {
            const float sk = m.sigma_s[k];
            const float r = sk / s0 * std::exp(-(sk - s0) * t);
            out.ratio[k] = r;
            out.beta[k] = r * exp_neg(m.sigma_a[k], t);
        }
        return out;
    }
    out.t = t_max;
    out.hero_pass = exp_neg(s0, t_max);
    for (std::size_t k = 0; k < C; ++k) {
        const float d = m.sigma_s[k] - s0;  // ≥ 0 whenever t_max = ∞ (then s0 = 0)
        const float r = exp_neg(d, t_max);
        out.ratio[k] = r;
        out.beta[k] = r * exp_neg(m.sigma_a[k], t_max);
    }
    return out;
}

}  // namespace iris
