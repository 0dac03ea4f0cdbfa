#pragma once
/// \file
/// \brief Hero wavelength sampling with a restricted pdf (docs/method.md §3): the rotation of the
/// hero's primary sample and the MIS weight of wavelength j.
///
///     F_R = Σ_j r_α(λ_j) f(x̄, λ_j) · w_j,   w_j = 1 / (p_α(λ_j) · Σ_k p(x̄ | λ_k))
///
/// **[fix 1, docs/method.md §4]** p_α(λ_j) stands outside the sum over k. The paper's Eq. 4 puts
/// p_α(λ_k) inside it, which is the same only when p_α is uniform: the rotation
/// u_j = frac(u + j/C) preserves p_α(λ) dλ, not dλ, so the balance heuristic over the C
/// rotations compares the path densities p(x̄ | λ_k) alone. tests/sampling keeps the
/// paper's form in one test, which shows it biased for a non-uniform p_α.

#include <cmath>
#include <cstddef>
#include <span>

#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief u_j = frac(u + j/C) in double (so it is never 1), for C ≥ 1; u outside [0, 1) is clamped
/// first (NaN → 0). The C values are stratified: exactly one falls in each [k/C, (k+1)/C).
constexpr double hwss_rotation(float u, std::size_t j, std::size_t C) noexcept {
    double x = static_cast<double>(u);
    if (!(x >= 0.0)) x = 0.0;
    if (x >= 1.0) x = 0x1.fffffffffffffp-1;
    x += static_cast<double>(j % C) / static_cast<double>(C);
    return x >= 1.0 ? x - 1.0 : x;
}

/// \brief w_j = 1 / (p_α(λ_j) Σ_k p(x̄ | λ_k)) (docs/method.md §3). Non-positive or NaN path pdfs
/// count as 0 (a terminated secondary wavelength); the weight is 0 — never NaN or Inf —
/// when p_α(λ_j) ≤ 0, the sum is 0, or the weight would overflow.
inline float hwss_mis_weight(float restricted_pdf_j, std::span<const float> path_pdfs) noexcept {
    double sum = 0.0;
    for (float p : path_pdfs) sum += p > 0.0f ? static_cast<double>(p) : 0.0;
    const double den = static_cast<double>(restricted_pdf_j) * sum;
    if (!(restricted_pdf_j > 0.0f) || !(den > 0.0)) return 0.0f;
    const double w = 1.0 / den;
    return w <= 3.0e38 ? static_cast<float>(w) : 0.0f;
}

/// \brief The same for the C path pdfs of a `sampled_spectrum<C>`.
template <std::size_t C>
float hwss_mis_weight(float restricted_pdf_j, const sampled_spectrum<C>& path_pdfs) noexcept {
    return hwss_mis_weight(restricted_pdf_j, std::span<const float>(path_pdfs.values()));
}

/// \name The same weight in ratio form, as the path integrator tracks a path (pbrt-v4's form)
/// With β_j = f(x̄, λ_j) / p(x̄ | λ₀) and ρ_k = p(x̄ | λ_k) / p(x̄ | λ₀) along the path so far,
///     f(x̄, λ_j) · p_α(λ_j) · w_j = β_j / Σ_k ρ_k,
/// so the integrator never forms a path pdf (it under- or overflows on long paths) and
/// divides by `hwss_mis_weight`'s sum, over p(x̄ | λ₀). When two strategies can make the
/// last vertex (BSDF sampling, with pdf p_b(λ_k), and light sampling, p_l, the same for
/// every λ), each p(x̄ | λ_k) is the sum of both and so is each ratio. The division by
/// p_α(λ_j) is the bias policy's `restricted_factor`. tests/sampling/laws_test.cpp checks
/// these against `hwss_mis_weight`; they are what renders.
/// @{

/// \brief Σ_k ρ_k: one strategy made the last vertex (the camera ray, a delta bounce, the
/// environment).
template <std::size_t C>
float hwss_ratio_sum(const sampled_spectrum<C>& rho) noexcept {
    return rho.sum();
}

/// \brief Σ_k ρ_k (1 + p_b(λ_k) / p_l): the last vertex was light-sampled with solid-angle
/// pdf p_l (the ratios of the path up to the vertex before it); the contribution is
/// β_j f_j L_j / (p_l · this).
template <std::size_t C>
float hwss_light_ratio_sum(const sampled_spectrum<C>& rho, const sampled_spectrum<C>& pdf_bsdf, float pdf_light) noexcept {
    float denom = 0.0f;
    for (std::size_t k = 0; k < C; ++k) denom += rho[k] * (1.0f + pdf_bsdf[k] / pdf_light);
    return denom;
}

/// \brief Σ_k ρ_k + (p_l / p_b(λ₀)) Σ_k ρ′_k: BSDF sampling (hero pdf p_b(λ₀)) found an
/// emitter that light sampling reaches with pdf p_l; ρ are the ratios including the last
/// scattering, ρ′ those before it.
template <std::size_t C>
float hwss_emission_ratio_sum(const sampled_spectrum<C>& rho, const sampled_spectrum<C>& rho_before, float pdf_light,
                              float pdf_bsdf_hero) noexcept {
    return rho.sum() + (pdf_light / pdf_bsdf_hero) * rho_before.sum();
}

/// \brief The balance heuristic of one wavelength between two strategies, p / (p + q): the
/// hero's own weight, which the B term carries.
inline float balance_heuristic(float p, float q) noexcept { return p / (p + q); }
/// @}

}  // namespace iris
