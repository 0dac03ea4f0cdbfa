#pragma once
/// \file
/// \brief `restriction::gaussian`: r_α(λ) = s + (1 − s) g(λ), g = exp(−(λ − c)² / 2σ²),
/// with s(α) = α and σ(α) = σ0 + α |Λ|. A Gaussian never reaches 1 everywhere, so the
/// floor s takes it there: r_1 = 1 + 0·g = 1 exactly (law 1). Both s and σ grow with α,
/// so r does too (law 2); r ≥ g > 0 near c (law 3).
///
/// Parameters (nm)  | default | note
/// -----------------|---------|--------------------------------------------------------
/// `centre_nm`      | 580     | as `box` (clamped into Λ)
/// `sigma_nm` (σ0)  | 7.98    | 20/√(2π): the same area as the 20 nm box; < 1e-3 → 1e-3

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>

#include "iris/sampling/restriction/concept.hpp"

namespace iris::restriction {

/// \brief A smooth unimodal restriction (the paper's Gaussian), made exact at α = 1.
struct gaussian {
    static constexpr std::string_view name = "gaussian";
    static constexpr std::size_t max_intervals = 1;
    static constexpr float min_sigma_nm = 1e-3f;

    float centre_nm = 580.0f;
    float sigma_nm = 7.9788456f;

    struct bound {
        static constexpr bool indicator = false;
        double centre = 0.0;
        double inv_two_sigma2 = 0.0;  ///< 1 / 2σ(α)²
        double floor = 1.0;           ///< s(α)
        double inv_sigma_sqrt2 = 0.0; ///< 1 / (σ√2)
        double half_sqrt_pi_sigma_sqrt2 = 0.0;  ///< σ√(π/2): ∫g over a half line
        interval_set<1> domain;
        float operator()(float lambda_nm) const noexcept {
            if (floor >= 1.0) return 1.0f;
            const double x = static_cast<double>(lambda_nm) - centre;
            const double g = std::exp(-x * x * inv_two_sigma2);  // NaN λ → NaN → 0 below
            const double r = g + floor * (1.0 - g);
            return r >= 1.0 ? 1.0f : (r > 0.0 ? static_cast<float>(r) : 0.0f);
        }
        /// \brief What the mean of r needs to know about one cell edge: the edge and the
        /// Gaussian's tail beyond it, erfc(|x − c| / σ√2) (no cancellation in the tails).
        struct edge {
            double x = 0.0;
            double tail = 0.0;
        };
        edge edge_at(float x) const noexcept {
            const double xd = static_cast<double>(x);
            return {xd, floor >= 1.0 ? 0.0 : std::erfc(std::fabs(xd - centre) * inv_sigma_sqrt2)};
        }
        /// \brief Exact mean of r between two edges: s + (1 − s) ∫g / (b − a), with ∫g from
        /// the tails on each side of the centre.
        double average(const edge& a, const edge& b) const noexcept {
            if (!(b.x > a.x)) return 0.0;
            if (floor >= 1.0) return 1.0;
            double half_integral;  // ∫g / (σ√(π/2))
            if (a.x >= centre) half_integral = a.tail - b.tail;
            else if (b.x <= centre) half_integral = b.tail - a.tail;
            else half_integral = 2.0 - a.tail - b.tail;
            const double mean_g = std::max(0.0, half_integral) * half_sqrt_pi_sigma_sqrt2 / (b.x - a.x);
            return std::min(1.0, mean_g + floor * (1.0 - std::min(1.0, mean_g)));
        }
        /// \brief Exact mean of r over [a, b].
        double average(float a, float b) const noexcept { return average(edge_at(a), edge_at(b)); }
        constexpr const interval_set<1>& support() const noexcept { return domain; }
    };

    bound bind(float alpha, const spectral_domain& d) const noexcept {
        const double a = static_cast<double>(detail::clamp_alpha(alpha));
        double s0 = static_cast<double>(sigma_nm);
        if (!(s0 >= static_cast<double>(min_sigma_nm))) s0 = static_cast<double>(min_sigma_nm);
        const double width = static_cast<double>(d.max_nm) - static_cast<double>(d.min_nm);
        if (s0 > 1e3 * width) s0 = 1e3 * width;  // also Inf: wider than this is flat anyway
        const double sigma = s0 + a * width;
        interval_set<1> s;
        s.insert(d.min_nm, d.max_nm);
        const double sigma_sqrt2 = sigma * std::numbers::sqrt2;
        return {detail::sane_centre(centre_nm, d), 0.5 / (sigma * sigma), a, 1.0 / sigma_sqrt2,
                0.5 * std::sqrt(std::numbers::pi) * sigma_sqrt2, s.clipped(d)};
    }
};

static_assert(RestrictionKernel<gaussian> && EdgeAveragedRestriction<gaussian::bound>);

}  // namespace iris::restriction
