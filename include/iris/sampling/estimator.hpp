#pragma once
/// \file
/// \brief `spectral_estimate`: one sample of F = F_R (+ B) for ∫Λ f(λ) dλ with a
/// path-independent integrand (p(x̄ | λ) ≡ 1) — the combination the integrator forms per
/// path, through the same functions (`restricted_factor`, `hwss_ratio_sum`), with the path
/// factors taken out, so that a policy's claims can be
/// tested at the spectral level (docs/method.md §4, U1: E[F] = ∫ f for `propagate_unused` at every α).
///
///     F_R = Σ_j r_α(λ_j) f(λ_j) / (p_α(λ_j) · C)        (÷ Z_α for `scaled_pdf`)
///     B   = Σ_b (1 − r_α(λ_b)) f(λ_b) Δλ_b              (`propagate_unused` only)
///
/// E[F_R] = ∫ r_α f (÷ Z_α) because each λ_j is marginally p_α-distributed and
/// r_α f / p_α vanishes wherever p_α does; E[B] = ∫ (1 − r_α) f because λ_b is uniform in
/// its bin. Their sum is ∫ f: r and 1 − r partition unity (the r(λ) factor, docs/method.md §4, fix 2).

#include <cstddef>

#include "iris/sampling/bias/bin_layout.hpp"
#include "iris/sampling/bias/concept.hpp"
#include "iris/sampling/hwss.hpp"

namespace iris {

/// \brief One sample of F for the bias policy `Bias` with C hero-rotated wavelengths.
/// `u` drives the wavelengths, `u_jitter` the B term's bins; `f(λ)` → double.
template <BiasPolicy Bias, std::size_t C, class Distribution, class F>
double spectral_estimate(const Distribution& dist, const bias::bin_layout& bins, F&& f, float u, float u_jitter) {
    const auto wl = dist.template sample_wavelengths<C>(u);
    const sampled_spectrum<C> rho(1.0f);  // p(x̄ | λ_k) = 1 for every k: no path, every ratio 1
    const float z = Bias::scales_pdf ? dist.normalisation() : 1.0f;
    double estimate = 0.0;
    for (std::size_t j = 0; j < C; ++j) {  // the path integrator's F_R, with β_j = f(λ_j)
        const double w = Bias::restricted_factor(dist.restriction(wl[j]), wl.pdf(j), z);
        if (w == 0.0) continue;
        estimate += w * f(wl[j]) / static_cast<double>(hwss_ratio_sum(rho));
    }
    if constexpr (Bias::propagates) {
        for (std::size_t b = 0; b < bins.count(); ++b) {
            const float l = bins.lambda(b, u_jitter);
            const double keep = 1.0 - static_cast<double>(dist.restriction(l));
            if (keep > 0.0) estimate += keep * f(l) * bins.width(b);
        }
    }
    return estimate;
}

}  // namespace iris
