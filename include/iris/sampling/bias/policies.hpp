#pragma once
/// \file
/// \brief The bias policies of docs/method.md §2: `none` (restriction only), `scaled_pdf`
/// (the paper's "scaling PDFs") and `propagate_unused` (the paper's propagation, with the
/// r(λ) numerator factor of docs/method.md §4, fix 2, so r and 1 − r partition unity).

#include <cmath>
#include <cstddef>
#include <string_view>

#include "iris/sampling/detail/name.hpp"

#include "iris/sampling/bias/concept.hpp"

namespace iris::bias {

namespace detail {
/// \brief num / den in double, or 0 when den ≤ 0 or the quotient is negative, NaN or past
/// float's range.
inline double safe_ratio(double num, double den) noexcept {
    if (!(den > 0.0)) return 0.0;
    const double q = num / den;
    return q >= 0.0 && q <= 3.0e38 ? q : 0.0;
}
}  // namespace detail

/// \brief F = F_R, w_j = r_α(λ_j) / p_α(λ_j). Estimates ∫ r_α f: unbiased only at α = 1;
/// before that, dim wherever the restriction cuts the spectrum (paper Figs. 5–6).
struct none {
    static constexpr std::string_view name = "none";
    static constexpr bool propagates = false;
    static constexpr bool scales_pdf = false;
    static double restricted_factor(float r, float pdf, float /*z*/) noexcept {
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
    static double restricted_factor(float r, float pdf, float z) noexcept {
        return detail::safe_ratio(static_cast<double>(r), static_cast<double>(pdf) * static_cast<double>(z));
    }
};

/// \brief F = F_R + B, w_j = r_α(λ_j) / p_α(λ_j) and
/// B = Σ_b (1 − r_α(λ_b)) f_h(x̄, λ_b) Δλ_b / p(x̄ | λ_0) over the bins of a `bin_layout`,
/// λ_b jittered in its bin. Unbiased at every α in scenes without specular dispersion
/// (docs/method.md §4, U1); the only bias is the hero's direction for λ_b at specular dispersive events.
struct propagate_unused {
    static constexpr std::string_view name = "propagate";
    static constexpr bool propagates = true;
    static constexpr bool scales_pdf = false;
    /// \brief Bins of the B term the integrator evaluates along the hero path (5 nm on
    /// 380–780 nm): what it costs per vertex is proportional to this.
    static constexpr std::size_t bins = 80;
    static double restricted_factor(float r, float pdf, float /*z*/) noexcept {
        return detail::safe_ratio(static_cast<double>(r), static_cast<double>(pdf));
    }
};

/// \brief PropagateUnused with B bins instead of 80 (`propagate8`: 50 nm bins on
/// 380–780 nm): the same estimator — one jittered wavelength per bin, so still an
/// unbiased estimate of ∫ (1 − r_α) f — with fewer, wider strata. The B term costs in
/// proportion to B; its variance (the colour noise the method removes) grows as B falls.
/// `docs/results.md` measures the trade.
template <std::size_t B>
struct propagate_coarse : propagate_unused {
    static_assert(B >= 1 && B <= 400, "the B term needs between 1 and 400 bins");
    static constexpr std::string_view name = iris::detail::numbered_name_v<"propagate", B>.view();
    static constexpr std::size_t bins = B;
};

static_assert(BiasPolicy<none> && BiasPolicy<scaled_pdf> && BiasPolicy<propagate_unused> &&
              BiasPolicy<propagate_coarse<8>>);

}  // namespace iris::bias
