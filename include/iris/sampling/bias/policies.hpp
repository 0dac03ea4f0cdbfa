#pragma once
/// \file
/// \brief The bias policies of SPEC §3: `none` (restriction only), `scaled_pdf` (the
/// paper's "scaling PDFs") and `propagate_unused` (the paper's propagation, with SPEC's
/// r(λ) numerator factor, so r and 1 − r partition unity).

#include <cmath>
#include <string_view>

#include "iris/sampling/bias/concept.hpp"

namespace iris::bias {

namespace detail {
/// \brief num / den, or 0 when den ≤ 0 or the quotient is not finite.
inline float safe_ratio(double num, double den) noexcept {
    if (!(den > 0.0)) return 0.0f;
    const double q = num / den;
    return q >= 0.0 && q <= 3.0e38 ? static_cast<float>(q) : 0.0f;
}
}  // namespace detail

/// \brief F = F_R, w_j = r_α(λ_j) / p_α(λ_j). Estimates ∫ r_α f: unbiased only at α = 1;
/// before that, dim wherever the restriction cuts the spectrum (paper Figs. 5–6).
struct none {
    static constexpr std::string_view name = "none";
    static constexpr bool propagates = false;
    static constexpr bool scales_pdf = false;
    static float restricted_factor(float r, float pdf, float /*z*/) noexcept {
        return detail::safe_ratio(static_cast<double>(r), static_cast<double>(pdf));
    }
};

/// \brief F = F_R / Z_α, w_j = r_α(λ_j) / (p_α(λ_j) Z_α) = r_α(λ_j) / p(λ_j): the sampled
/// part stands in for the whole spectrum. Right brightness for flat spectra, a colour
/// bias that depends on where the windows sit (paper Fig. 7); unbiased at α = 1 (Z_1 = 1).
struct scaled_pdf {
    static constexpr std::string_view name = "scaled";
    static constexpr bool propagates = false;
    static constexpr bool scales_pdf = true;
    static float restricted_factor(float r, float pdf, float z) noexcept {
        return detail::safe_ratio(static_cast<double>(r), static_cast<double>(pdf) * static_cast<double>(z));
    }
};

/// \brief F = F_R + B, w_j = r_α(λ_j) / p_α(λ_j) and
/// B = Σ_b (1 − r_α(λ_b)) f_h(x̄, λ_b) Δλ_b / p(x̄ | λ_0) over the bins of a `bin_layout`,
/// λ_b jittered in its bin. Unbiased at every α in scenes without specular dispersion
/// (SPEC U1); the only bias is the hero's direction for λ_b at specular dispersive events.
struct propagate_unused {
    static constexpr std::string_view name = "propagate";
    static constexpr bool propagates = true;
    static constexpr bool scales_pdf = false;
    static float restricted_factor(float r, float pdf, float /*z*/) noexcept {
        return detail::safe_ratio(static_cast<double>(r), static_cast<double>(pdf));
    }
};

static_assert(BiasPolicy<none> && BiasPolicy<scaled_pdf> && BiasPolicy<propagate_unused>);

}  // namespace iris::bias
