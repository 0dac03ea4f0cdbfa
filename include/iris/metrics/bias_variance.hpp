#pragma once
/// \file
/// \brief How much of a renderer's error is bias: the MSE of k ≥ 2 independent runs (other
/// seeds) against a reference, split into the runs' variance and what is left, the squared
/// bias. Definitions: docs/metrics.md.
///
/// Per pixel and channel, with the runs X_1 … X_k, their mean X̄ and the reference R:
/// s² = Σ_j (X_j − X̄)² / (k − 1) estimates the variance of one run without bias, and
///
///     (1/k) Σ_j (X_j − R)² = (X̄ − R)² + (k − 1)/k · s²,
///
/// so d = (X̄ − R)² − s²/k estimates E[(E[X] − R)²] — the squared bias of a run against R —
/// without bias. `mse`, `variance` and `bias_sq` are the means of the three over every
/// pixel and channel (mse = variance + bias_sq exactly). bias_sq includes the reference's
/// own error (a noisy reference adds its variance): an unbiased renderer's bias_sq measures
/// it, so a biased renderer's own squared bias is the difference between the two.
/// `bias_sq_se` is the standard error of bias_sq from the spread of d over the pixels
/// (treating pixels as independent; bias_sq can come out negative by noise).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>

#include "iris/image.hpp"
#include "iris/metrics/common.hpp"

namespace iris {

/// \brief The split of `bias_variance`.
struct bias_variance_split {
    double mse = 0;         ///< mean over runs of mse(run, reference)
    double variance = 0;    ///< mean over pixels and channels of s² (one run's variance)
    double bias_sq = 0;     ///< mse − variance: squared bias plus the reference's error
    double bias_sq_se = 0;  ///< its standard error over the pixels
    std::size_t runs = 0;
};

/// \brief The split of `runs` (independent renders of one image) against `reference`.
/// \throws std::invalid_argument for fewer than 2 runs, sizes that differ, NaN/Inf.
inline bias_variance_split bias_variance(std::span<const image> runs, const image& reference) {
    if (runs.size() < 2)
        throw std::invalid_argument("bias_variance: needs at least 2 runs, got " + std::to_string(runs.size()));
    for (const image& r : runs) detail::require_comparable(r, reference, "bias_variance");
    const double k = static_cast<double>(runs.size());
    const std::size_t n = reference.pixel_count();
    double sum_mse = 0, sum_var = 0, sum_d = 0, sum_d2 = 0;
    for (std::size_t i = 0; i < n; ++i)
        for (auto c : detail::rgb_channels) {
            const double ref = static_cast<double>(reference.pixels()[i].*c);
            double mean = 0;
            for (const image& r : runs) mean += static_cast<double>(r.pixels()[i].*c);
            mean /= k;
            double ss = 0, se = 0;
            for (const image& r : runs) {
                const double v = static_cast<double>(r.pixels()[i].*c);
                ss += (v - mean) * (v - mean);
                se += (v - ref) * (v - ref);
            }
            const double s2 = ss / (k - 1);
            const double d = (mean - ref) * (mean - ref) - s2 / k;
            sum_mse += se / k;
            sum_var += s2;
            sum_d += d;
            sum_d2 += d * d;
        }
    const double m = 3.0 * static_cast<double>(n);
    bias_variance_split out;
    out.runs = runs.size();
    out.mse = sum_mse / m;
    out.variance = sum_var / m;
    out.bias_sq = sum_d / m;
    out.bias_sq_se = m > 1 ? std::sqrt(std::max(0.0, (sum_d2 - sum_d * sum_d / m) / (m - 1)) / m) : 0.0;
    return out;
}

}  // namespace iris
