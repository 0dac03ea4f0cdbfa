#pragma once
/// \file
/// \brief Colorimetry: CIE 1931 2° CMFs, spectrum → XYZ, XYZ ↔ linear sRGB (D65 white),
/// the sRGB transfer function, chromaticity and white normalisation.
///
/// Integration convention: plain 1 nm sums over the CMF table (360–830 nm), the way the
/// CIE tabulates and pbrt-v4 integrates. `cie_y_integral` = Σ ȳ · 1 nm = 106.856917.

#include <array>
#include <cmath>
#include <cstddef>
#include <numeric>

#include "iris/spectrum/data/cie1931.hpp"
#include "iris/spectrum/sampled.hpp"
#include "iris/spectrum/spectrum.hpp"

namespace iris {

/// \brief CIE XYZ tristimulus values.
struct xyz {
    double x = 0, y = 0, z = 0;
    friend constexpr bool operator==(const xyz&, const xyz&) = default;
};
/// \brief Linear sRGB (Rec. 709 primaries, D65 white), not gamma-encoded.
struct rgb {
    double r = 0, g = 0, b = 0;
    friend constexpr bool operator==(const rgb&, const rgb&) = default;
};
/// \brief CIE 1931 xy chromaticity.
struct chromaticity_xy {
    double x = 0, y = 0;
};

namespace cie {

inline constexpr double cmf_lambda_min = data::cie1931::lambda_min;  ///< 360 nm
inline constexpr std::size_t cmf_samples = data::cie1931::y_bar.size();  ///< 471
inline constexpr double cmf_lambda_max = cmf_lambda_min + static_cast<double>(cmf_samples - 1);  ///< 830 nm

/// \brief ∫ ȳ(λ) dλ over the table at 1 nm (= 106.856917).
inline constexpr double y_integral =
    std::accumulate(data::cie1931::y_bar.begin(), data::cie1931::y_bar.end(), 0.0);

namespace detail {
inline constexpr double interpolate(const std::array<double, cmf_samples>& t, double lambda_nm) noexcept {
    if (!(lambda_nm >= cmf_lambda_min) || !(lambda_nm <= cmf_lambda_max)) return 0.0;  // also NaN → 0
    const double x = lambda_nm - cmf_lambda_min;
    std::size_t i = static_cast<std::size_t>(x);
    if (i >= cmf_samples - 1) i = cmf_samples - 2;
    const double f = x - static_cast<double>(i);
    return t[i] + f * (t[i + 1] - t[i]);
}
}  // namespace detail

/// \brief The CMFs at any λ (linear interpolation, 0 outside 360–830 nm).
constexpr double x_bar(double lambda_nm) noexcept { return detail::interpolate(data::cie1931::x_bar, lambda_nm); }
constexpr double y_bar(double lambda_nm) noexcept { return detail::interpolate(data::cie1931::y_bar, lambda_nm); }
constexpr double z_bar(double lambda_nm) noexcept { return detail::interpolate(data::cie1931::z_bar, lambda_nm); }

}  // namespace cie

/// \brief Unnormalised tristimulus values Σ S(λ)·(x̄,ȳ,z̄)(λ)·1 nm over 360–830 nm.
template <Spectrum S>
constexpr xyz spectrum_to_xyz(const S& s) {
    xyz r;
    for (std::size_t i = 0; i < cie::cmf_samples; ++i) {
        const double v = static_cast<double>(s(cie::cmf_lambda_min + static_cast<double>(i)));
        r.x += v * data::cie1931::x_bar[i];
        r.y += v * data::cie1931::y_bar[i];
        r.z += v * data::cie1931::z_bar[i];
    }
    return r;
}

/// \brief Photometric-style luminance of a spectrum relative to a flat one:
/// ∫S ȳ / ∫ȳ, so that `constant_spectrum{1}` has luminance 1.
template <Spectrum S>
constexpr double luminance(const S& s) {
    return spectrum_to_xyz(s).y / cie::y_integral;
}

/// \brief The factor that maps a spectrum's luminance (∫Sȳ/∫ȳ) to 1 (white normalisation).
/// Returns 0 for a spectrum with no luminance, so callers never divide by zero.
template <Spectrum S>
constexpr double white_normalisation(const S& s) {
    const double y = luminance(s);
    return y > 0.0 ? 1.0 / y : 0.0;
}

/// \brief XYZ scaled so that Y = 1 (the illuminant's white point).
constexpr xyz normalise_y(const xyz& c) noexcept {
    return c.y != 0.0 ? xyz{c.x / c.y, 1.0, c.z / c.y} : xyz{};
}

constexpr chromaticity_xy chromaticity(const xyz& c) noexcept {
    const double s = c.x + c.y + c.z;
    return s != 0.0 ? chromaticity_xy{c.x / s, c.y / s} : chromaticity_xy{};
}

/// \brief XYZ → linear sRGB. IEC 61966-2-1 primaries, D65 white; the matrix is the
/// inverse of `linear_srgb_to_xyz` to double precision.
constexpr rgb xyz_to_linear_srgb(const xyz& c) noexcept {
    return {3.2404542 * c.x - 1.5371385 * c.y - 0.4985314 * c.z,
            -0.9692660 * c.x + 1.8760108 * c.y + 0.0415560 * c.z,
            0.0556434 * c.x - 0.2040259 * c.y + 1.0572252 * c.z};
}

constexpr xyz linear_srgb_to_xyz(const rgb& c) noexcept {
    return {0.4124564 * c.r + 0.3575761 * c.g + 0.1804375 * c.b,
            0.2126729 * c.r + 0.7151522 * c.g + 0.0721750 * c.b,
            0.0193339 * c.r + 0.1191920 * c.g + 0.9503041 * c.b};
}

/// \brief sRGB opto-electronic transfer function (linear [0,1] → encoded [0,1]).
inline double srgb_encode(double v) noexcept {
    if (!(v > 0.0)) return 0.0;  // negative and NaN → 0
    if (v <= 0.0031308) return 12.92 * v;
    return v >= 1.0 ? 1.0 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

/// \brief Inverse of `srgb_encode`.
inline double srgb_decode(double v) noexcept {
    if (!(v > 0.0)) return 0.0;
    if (v <= 0.04045) return v / 12.92;
    return v >= 1.0 ? 1.0 : std::pow((v + 0.055) / 1.055, 2.4);
}

/// \brief v += w · (x̄, ȳ, z̄)(λ), in double: one wavelength's weighted radiance added to
/// a sample's XYZ (before the division by ∫ȳ). The path integrator's F_R and
/// `sampled_to_xyz` both add through it.
constexpr void add_cmf(xyz& v, double w, float lambda) noexcept {
    const double l = static_cast<double>(lambda);
    v.x += w * cie::x_bar(l);
    v.y += w * cie::y_bar(l);
    v.z += w * cie::z_bar(l);
}

/// \brief Monte Carlo XYZ of one sample: Σ_j s_j·cmf(λ_j) / (pdf_j · N) / ∫ȳ, with
/// zero-pdf wavelengths skipped: plain averaging over N wavelengths. (The path integrator
/// weighs its C wavelengths by the HWSS MIS weight instead, and adds them through `add_cmf`.)
template <std::size_t N>
constexpr xyz sampled_to_xyz(const sampled_spectrum<N>& s, const sampled_wavelengths<N>& wl) noexcept {
    xyz r;
    for (std::size_t i = 0; i < N; ++i) {
        if (wl.pdf(i) == 0.0f) continue;
        add_cmf(r, static_cast<double>(s[i]) / static_cast<double>(wl.pdf(i)), wl[i]);
    }
    const double k = 1.0 / (static_cast<double>(N) * cie::y_integral);
    return {r.x * k, r.y * k, r.z * k};
}

}  // namespace iris
