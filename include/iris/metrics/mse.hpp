#pragma once
/// \file
/// \brief Pixel-wise error metrics on linear RGB images: MSE, relative MSE, max |a − b|.
///
/// All are means (or the maximum) over every pixel and all three channels, computed in
/// double from the float pixels, with no clamping or encoding: they measure the linear
/// radiance a renderer estimates. Definitions: docs/metrics.md.
/// \throws std::invalid_argument for images of different or zero size and for NaN/Inf values.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "iris/image.hpp"
#include "iris/metrics/common.hpp"

namespace iris {

/// \brief Default ε of `relmse`: keeps near-black reference pixels from dominating (the
/// value used by Rousselle et al. and most denoising papers for images with radiance ~1).
inline constexpr double relmse_default_epsilon = 1e-2;

/// \brief Mean squared error: (1 / 3N) Σ_pixels Σ_{c∈RGB} (a_c − b_c)². Symmetric.
inline double mse(const image& a, const image& b) {
    detail::require_comparable(a, b, "mse");
    double sum = 0.0;
    for (std::size_t i = 0; i < a.pixel_count(); ++i)
        for (auto c : detail::rgb_channels) {
            const double d = static_cast<double>(a.pixels()[i].*c) - static_cast<double>(b.pixels()[i].*c);
            sum += d * d;
        }
    return sum / (3.0 * static_cast<double>(a.pixel_count()));
}

/// \brief Relative MSE against a reference: (1 / 3N) Σ_pixels Σ_c (a_c − r_c)² / (r_c² + ε).
/// Not symmetric: the second argument is the reference. \throws std::invalid_argument
/// also for ε that is not a positive finite number.
inline double relmse(const image& a, const image& reference, double epsilon = relmse_default_epsilon) {
    if (!(epsilon > 0.0) || !std::isfinite(epsilon))
        throw std::invalid_argument("relmse: epsilon must be a positive finite number, got " + std::to_string(epsilon));
    detail::require_comparable(a, reference, "relmse");
    double sum = 0.0;
    for (std::size_t i = 0; i < a.pixel_count(); ++i)
        for (auto c : detail::rgb_channels) {
            const double r = static_cast<double>(reference.pixels()[i].*c);
            const double d = static_cast<double>(a.pixels()[i].*c) - r;
            sum += d * d / (r * r + epsilon);
        }
    return sum / (3.0 * static_cast<double>(a.pixel_count()));
}

/// \brief Largest absolute channel difference max_{pixels, c} |a_c − b_c|. Symmetric.
inline double max_abs(const image& a, const image& b) {
    detail::require_comparable(a, b, "max_abs");
    double m = 0.0;
    for (std::size_t i = 0; i < a.pixel_count(); ++i)
        for (auto c : detail::rgb_channels)
            m = std::max(m, std::abs(static_cast<double>(a.pixels()[i].*c) - static_cast<double>(b.pixels()[i].*c)));
    return m;
}

}  // namespace iris
