#pragma once
/// \file
/// \brief SSIM (Wang, Bovik, Sheikh, Simoncelli 2004) with every choice pinned down, so a
/// number from iris means one thing (docs/metrics.md):
///
/// - input: linear sRGB clamped to [0, 1], then sRGB-encoded (`srgb_encode`); each of R, G,
///   B is scored separately;
/// - window: Gaussian, σ = 1.5, truncated at 3.5σ (radius 5, 11 × 11), normalised to sum 1
///   over that support;
/// - K1 = 0.01, K2 = 0.03, data range L = 1, so C1 = (K1 L)², C2 = (K2 L)²;
/// - local statistics are weighted *population* moments (weights sum to 1, no n/(n−1));
/// - the SSIM map is averaged over the window positions that fit inside the image
///   ("valid" mode: no padding), then over the three channels.
///
/// This is scikit-image's `structural_similarity(gaussian_weights=True, sigma=1.5,
/// use_sample_covariance=False, data_range=1)` on the encoded channels.
/// \throws std::invalid_argument for different sizes, images smaller than 11 × 11 and NaN/Inf.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "iris/image.hpp"
#include "iris/metrics/common.hpp"
#include "iris/spectrum/color.hpp"

namespace iris {

inline constexpr double ssim_sigma = 1.5;        ///< Gaussian window σ (pixels)
inline constexpr double ssim_truncate = 3.5;     ///< window radius in units of σ
inline constexpr int ssim_radius = 5;            ///< ⌊3.5 · 1.5 + 0.5⌋, as scikit-image rounds it
inline constexpr int ssim_window = 2 * ssim_radius + 1;  ///< 11
inline constexpr double ssim_k1 = 0.01;
inline constexpr double ssim_k2 = 0.03;
inline constexpr double ssim_data_range = 1.0;  ///< encoded values lie in [0, 1]
inline constexpr double ssim_c1 = (ssim_k1 * ssim_data_range) * (ssim_k1 * ssim_data_range);
inline constexpr double ssim_c2 = (ssim_k2 * ssim_data_range) * (ssim_k2 * ssim_data_range);
static_assert(ssim_radius == static_cast<int>(ssim_truncate * ssim_sigma + 0.5));

/// \brief The 1-D window g_k ∝ exp(−(k − 5)² / (2σ²)), k = 0…10, normalised to sum 1. The
/// 2-D window is the outer product g_i g_j, which then also sums to 1.
inline std::array<double, ssim_window> ssim_weights() {
    std::array<double, ssim_window> g{};
    double sum = 0.0;
    for (int k = 0; k < ssim_window; ++k) {
        const double d = static_cast<double>(k - ssim_radius);
        g[static_cast<std::size_t>(k)] = std::exp(-d * d / (2.0 * ssim_sigma * ssim_sigma));
        sum += g[static_cast<std::size_t>(k)];
    }
    for (double& v : g) v /= sum;
    return g;
}

/// \brief The SSIM formula for one window from its weighted moments.
inline double ssim_from_moments(double mean_a, double mean_b, double var_a, double var_b, double cov_ab) {
    // 2·μaμb is formed as mab + mab so that for a == b numerator and denominator are the
    // same floating-point expression and identical images score exactly 1.
    const double mab = mean_a * mean_b;
    return ((mab + mab + ssim_c1) * (cov_ab + cov_ab + ssim_c2)) /
           ((mean_a * mean_a + mean_b * mean_b + ssim_c1) * (var_a + var_b + ssim_c2));
}

namespace detail {

/// \brief Mean SSIM of two encoded planes (row-major, w × h, w and h ≥ 11). Separable
/// valid-mode filtering: each input row is filtered horizontally once into a ring of the
/// last 11 rows, and each output row is the vertical weighted sum over that ring, so the
/// cost is 2 · 11 multiply-adds per moment per pixel and the memory 11 rows.
inline double ssim_plane(const std::vector<double>& a, const std::vector<double>& b, int w, int h) {
    const auto g = ssim_weights();
    const auto n = static_cast<std::size_t>(ssim_window);
    const auto uw = static_cast<std::size_t>(w);
    const std::size_t ow = uw - n + 1;  // output columns
    enum { ma, mb, maa, mbb, mab, moments };
    // ring[row % 11][moment][x]: horizontally filtered moments of the last 11 rows
    std::vector<double> ring(n * moments * ow);
    auto slot = [&](std::size_t row, int m) { return ring.data() + ((row % n) * moments + static_cast<std::size_t>(m)) * ow; };

    std::vector<double> products(3 * uw);  // a², b², ab of the current row
    std::vector<double> acc(moments * ow);  // vertically filtered moments of one output row
    double sum = 0.0;
    for (std::size_t y = 0; y < static_cast<std::size_t>(h); ++y) {
        const double* in[moments] = {a.data() + y * uw, b.data() + y * uw, products.data(),
                                     products.data() + uw, products.data() + 2 * uw};
        for (std::size_t x = 0; x < uw; ++x) {
            products[x] = in[ma][x] * in[ma][x];
            products[uw + x] = in[mb][x] * in[mb][x];
            products[2 * uw + x] = in[ma][x] * in[mb][x];
        }
        for (int m = 0; m < moments; ++m) {
            double* out = slot(y, m);
            for (std::size_t x = 0; x < ow; ++x) {
                double s = 0.0;
                for (std::size_t k = 0; k < n; ++k) s += g[k] * in[m][x + k];
                out[x] = s;
            }
        }
        if (y + 1 < n) continue;
        const std::size_t top = y + 1 - n;  // first input row of this output row's windows
        std::fill(acc.begin(), acc.end(), 0.0);
        for (int m = 0; m < moments; ++m) {
            double* out = acc.data() + static_cast<std::size_t>(m) * ow;
            for (std::size_t k = 0; k < n; ++k) {
                const double* row = slot(top + k, m);
                for (std::size_t x = 0; x < ow; ++x) out[x] += g[k] * row[x];
            }
        }
        const double* s[moments];
        for (int m = 0; m < moments; ++m) s[m] = acc.data() + static_cast<std::size_t>(m) * ow;
        for (std::size_t x = 0; x < ow; ++x) {
            // Population moments: E[x²] − E[x]² with weights summing to 1.
            sum += ssim_from_moments(s[ma][x], s[mb][x], s[maa][x] - s[ma][x] * s[ma][x],
                                     s[mbb][x] - s[mb][x] * s[mb][x], s[mab][x] - s[ma][x] * s[mb][x]);
        }
    }
    return sum / static_cast<double>(ow * (static_cast<std::size_t>(h) - n + 1));
}

/// \brief One channel of an image, clamped to [0, 1] and sRGB-encoded, as doubles.
inline std::vector<double> encoded_channel(const image& img, float rgb_pixel::*c) {
    std::vector<double> out(img.pixel_count());
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = srgb_encode(std::clamp(static_cast<double>(img.pixels()[i].*c), 0.0, 1.0));
    return out;
}

}  // namespace detail

/// \brief SSIM of each channel (R, G, B), each the mean over all valid 11 × 11 windows.
/// Symmetric in a and b; 1 exactly for identical images (after clamping).
/// \throws std::invalid_argument for different sizes, either side < 11 pixels, NaN/Inf.
inline std::array<double, 3> ssim_channels(const image& a, const image& b) {
    detail::require_same_size(a, b, "ssim");
    if (a.width() < ssim_window || a.height() < ssim_window)
        throw std::invalid_argument("ssim: SSIM needs at least 11x11 pixels (one whole window), got " +
                                    detail::size_string(a));
    detail::require_finite(a, "ssim", "first");
    detail::require_finite(b, "ssim", "second");
    std::array<double, 3> out{};
    for (std::size_t c = 0; c < 3; ++c)
        out[c] = detail::ssim_plane(detail::encoded_channel(a, detail::rgb_channels[c]),
                                    detail::encoded_channel(b, detail::rgb_channels[c]), a.width(), a.height());
    return out;
}

/// \brief SSIM as defined in this file's header: the mean of `ssim_channels` over R, G, B.
inline double ssim(const image& a, const image& b) {
    const auto s = ssim_channels(a, b);
    return (s[0] + s[1] + s[2]) / 3.0;
}

}  // namespace iris
