#pragma once
/// \file
/// \brief sRGB colour → smooth reflectance spectrum in [0, 1] (for scene authoring).
///
/// Method (three smooth basis functions, solved under D65):
///   b_blue(λ)  = 1 − σ((λ − 490 nm) / 5 nm)
///   b_red(λ)   = σ((λ − 590 nm) / 5 nm)
///   b_green(λ) = 1 − b_blue(λ) − b_red(λ)      (σ the logistic function)
/// The three are smooth (C∞), non-negative and sum to 1 at every λ (a partition of unity),
/// so S(λ) = c_r·b_red + c_g·b_green + c_b·b_blue lies in [0, 1] whenever c ∈ [0, 1]³, and
/// c = (1, 1, 1) is the flat spectrum 1. The coefficients are c = A·rgb with
/// A = M⁻¹·T: M holds the XYZ (under D65, white Y = 1, 1 nm sums like `spectrum_to_xyz`)
/// of the three basis functions as columns, T is the sRGB → XYZ matrix with each row
/// rescaled by ~1e-4 so that T·(1,1,1) is exactly the tabulated D65 white. Hence:
///   - white (1, 1, 1) → S ≡ 1 exactly; grey g → S ≡ g;
///   - the spectrum's colour under D65 reproduces the linear sRGB input to double
///     rounding (XYZ of the result, converted back with `xyz_to_linear_srgb`, is within
///     1e-3 of the input, the residue being the 1e-4 white rescaling);
///   - the edge positions (490, 590 nm) and width (5 nm) were chosen so that every entry
///     of A is ≥ 0 (the smallest is ≈ 0.0036): the basis colours are more saturated than
///     the sRGB primaries, so every colour of the sRGB cube maps to c ∈ [0, 1]³ and no
///     in-gamut colour is ever clipped. Widths above ≈ 6.5 nm lose that property.
/// Inputs outside [0, 1] are clamped first (a reflectance cannot exceed 1), and the result
/// is clamped to [0, 1] as a guard against rounding.
/// Cost: one 3×3 solve (computed once per process) and 471 logistic evaluations per
/// colour; meant for scene loading, not for the per-sample path.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "iris/spectrum/color.hpp"
#include "iris/spectrum/data/cie1931.hpp"
#include "iris/spectrum/data/cie_d65.hpp"
#include "iris/spectrum/tabulated.hpp"

namespace iris {

namespace rgb_upsampling {

inline constexpr double blue_green_nm = 490.0;  ///< centre of the blue → green edge
inline constexpr double green_red_nm = 590.0;   ///< centre of the green → red edge
inline constexpr double edge_width_nm = 5.0;    ///< logistic scale (10–90 % rise over ≈ 22 nm)

inline double logistic(double x) noexcept { return 1.0 / (1.0 + std::exp(-x)); }

inline double blue_basis(double lambda_nm) noexcept {
    return 1.0 - logistic((lambda_nm - blue_green_nm) / edge_width_nm);
}
inline double red_basis(double lambda_nm) noexcept { return logistic((lambda_nm - green_red_nm) / edge_width_nm); }
inline double green_basis(double lambda_nm) noexcept {
    // written as a difference of logistics so that it is never negative in floating point
    return logistic((lambda_nm - blue_green_nm) / edge_width_nm) - logistic((lambda_nm - green_red_nm) / edge_width_nm);
}

}  // namespace rgb_upsampling

/// \brief CIE XYZ of a reflectance lit by D65, scaled so that a perfect white has Y = 1
/// (1 nm sums over the CMF table, D65 at the same nodes).
template <Spectrum S>
xyz reflectance_xyz_d65(const S& reflectance) {
    const auto& d65 = data::cie_d65::values;
    xyz r, w;
    for (std::size_t i = 0; i < cie::cmf_samples; ++i) {
        const double lambda = cie::cmf_lambda_min + static_cast<double>(i);
        const auto k = static_cast<std::size_t>(std::lround((lambda - data::cie_d65::lambda_min) / data::cie_d65::lambda_step));
        const double e = k < d65.size() ? d65[k] : 0.0;
        const double v = e * static_cast<double>(reflectance(lambda));
        r.x += v * data::cie1931::x_bar[i];
        r.y += v * data::cie1931::y_bar[i];
        r.z += v * data::cie1931::z_bar[i];
        w.y += e * data::cie1931::y_bar[i];
    }
    return {r.x / w.y, r.y / w.y, r.z / w.y};
}

/// \brief A reflectance as weights of the three smooth basis functions (see the file
/// comment). Models `Spectrum`.
struct rgb_reflectance {
    double red = 0.0, green = 0.0, blue = 0.0;

    double operator()(double lambda_nm) const noexcept {
        const double v = red * rgb_upsampling::red_basis(lambda_nm) + green * rgb_upsampling::green_basis(lambda_nm) +
                         blue * rgb_upsampling::blue_basis(lambda_nm);
        return std::clamp(v, 0.0, 1.0);
    }
};

namespace detail {

/// \brief A = M⁻¹·T (row-major), computed once.
inline const std::array<std::array<double, 3>, 3>& rgb_upsampling_matrix() {
    static const std::array<std::array<double, 3>, 3> a = [] {
        using rgb_upsampling::blue_basis;
        using rgb_upsampling::green_basis;
        using rgb_upsampling::red_basis;
        const xyz cr = reflectance_xyz_d65(red_basis), cg = reflectance_xyz_d65(green_basis),
                  cb = reflectance_xyz_d65(blue_basis);
        const xyz white = reflectance_xyz_d65([](double) { return 1.0; });
        // M: basis colours as columns
        const double m[3][3] = {{cr.x, cg.x, cb.x}, {cr.y, cg.y, cb.y}, {cr.z, cg.z, cb.z}};
        // T: sRGB → XYZ, rows rescaled so that T·1 is the tabulated white exactly
        double t[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                          {0.2126729, 0.7151522, 0.0721750},
                          {0.0193339, 0.1191920, 0.9503041}};
        const double target[3] = {white.x, white.y, white.z};
        for (int i = 0; i < 3; ++i) {
            const double s = t[i][0] + t[i][1] + t[i][2];
            for (int j = 0; j < 3; ++j) t[i][j] *= target[i] / s;
        }
        // M⁻¹ by the adjugate (M is well conditioned: three distinct broad-band colours)
        const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        double inv[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                // cofactor of m[j][i]
                const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
                inv[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
            }
        std::array<std::array<double, 3>, 3> out{};
        for (std::size_t i = 0; i < 3; ++i)
            for (std::size_t j = 0; j < 3; ++j)
                for (std::size_t k = 0; k < 3; ++k) out[i][j] += inv[i][k] * t[k][j];
        return out;
    }();
    return a;
}

}  // namespace detail

/// \brief The basis weights of a linear sRGB colour (clamped to [0, 1] first).
inline rgb_reflectance upsample_linear_srgb(const rgb& linear) {
    const auto& a = detail::rgb_upsampling_matrix();
    const auto c01 = [](double v) { return std::isnan(v) ? 0.0 : std::clamp(v, 0.0, 1.0); };
    const double in[3] = {c01(linear.r), c01(linear.g), c01(linear.b)};
    double c[3];
    for (std::size_t i = 0; i < 3; ++i) c[i] = std::clamp(a[i][0] * in[0] + a[i][1] * in[1] + a[i][2] * in[2], 0.0, 1.0);
    return {c[0], c[1], c[2]};
}

/// \brief A linear sRGB colour as a reflectance table: 1 nm steps over 360–830 nm (the CMF
/// range), `outside::clamp`, values in [0, 1].
inline tabulated_spectrum reflectance_from_linear_srgb(const rgb& linear) {
    const rgb_reflectance s = upsample_linear_srgb(linear);
    std::vector<double> lambda(cie::cmf_samples), value(cie::cmf_samples);
    for (std::size_t i = 0; i < cie::cmf_samples; ++i) {
        lambda[i] = cie::cmf_lambda_min + static_cast<double>(i);
        value[i] = s(lambda[i]);
    }
    return {std::move(lambda), std::move(value), outside::clamp};
}

/// \brief A gamma-encoded sRGB colour (components in [0, 1], as colour pickers give
/// them) as a reflectance table; decodes with `srgb_decode` first.
inline tabulated_spectrum reflectance_from_srgb(const rgb& encoded) {
    return reflectance_from_linear_srgb({srgb_decode(encoded.r), srgb_decode(encoded.g), srgb_decode(encoded.b)});
}

}  // namespace iris
