#pragma once
/// \file
/// \brief The false-colour ramp of `iris-image error-map`: five control points in CIELAB
/// (D65 white), interpolated linearly in Lab, so lightness L* rises linearly from 15 to 91
/// with the error (equal error steps look like equal lightness steps, also in greyscale
/// print) while the hue turns violet → blue → teal → green → yellow, viridis-like. Every
/// point of every segment lies inside the sRGB gamut (checked in tests/metrics).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include <iris/spectrum/color.hpp>

namespace iris::app {

/// \brief A colour in CIELAB: L* (0–100), a*, b*.
struct lab {
    double l = 0, a = 0, b = 0;
};

/// \brief Control points at t = 0, 1/4, 1/2, 3/4, 1. L* steps by 19.
inline constexpr std::array<lab, 5> error_ramp_points{{
    {15.0, 40.0, -45.0},  // dark violet
    {34.0, 15.0, -45.0},  // blue
    {53.0, -30.0, -5.0},  // teal
    {72.0, -52.0, 42.0},  // green
    {91.0, -10.0, 85.0},  // yellow
}};

/// \brief CIELAB (D65 reference white, Y_n = 1) → linear sRGB, not clamped.
inline rgb lab_to_linear_srgb(const lab& c) {
    constexpr double delta = 6.0 / 29.0;
    auto finv = [](double t) { return t > delta ? t * t * t : 3.0 * delta * delta * (t - 4.0 / 29.0); };
    const double fy = (c.l + 16.0) / 116.0;
    const xyz v{0.95047 * finv(fy + c.a / 500.0), finv(fy), 1.08883 * finv(fy - c.b / 200.0)};
    return xyz_to_linear_srgb(v);
}

/// \brief The ramp at t ∈ [0, 1] (clamped; NaN → 0) in Lab.
inline lab error_ramp_lab(double t) {
    t = t > 0.0 ? std::min(t, 1.0) : 0.0;
    const double u = t * static_cast<double>(error_ramp_points.size() - 1);
    const auto i = std::min(static_cast<std::size_t>(u), error_ramp_points.size() - 2);
    const double f = u - static_cast<double>(i);
    const lab& p = error_ramp_points[i];
    const lab& q = error_ramp_points[i + 1];
    return {p.l + f * (q.l - p.l), p.a + f * (q.a - p.a), p.b + f * (q.b - p.b)};
}

/// \brief The ramp at t ∈ [0, 1] as linear sRGB, clamped to [0, 1] against rounding at
/// the gamut edge (the PNG writer encodes it).
inline rgb error_ramp(double t) {
    const rgb c = lab_to_linear_srgb(error_ramp_lab(t));
    return {std::clamp(c.r, 0.0, 1.0), std::clamp(c.g, 0.0, 1.0), std::clamp(c.b, 0.0, 1.0)};
}

}  // namespace iris::app
