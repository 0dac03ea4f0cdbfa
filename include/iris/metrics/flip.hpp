#pragma once
/// \file
/// \brief ꟻLIP, the perceptual error of Andersson et al. ("FLIP: A Difference Evaluator for
/// Alternating Images", HPG 2020) and its HDR variant (Andersson et al., "Visualizing
/// Errors in Rendered High Dynamic Range Images", Eurographics 2021), as defined there
/// (docs/metrics.md). A per-pixel error in [0, 1] and its mean.
///
/// **LDR-ꟻLIP** of a test image against a reference, both linear sRGB clamped to [0, 1]:
/// - *colour*: each image to YCxCz (opponent space, D65-normalised XYZ), each channel
///   filtered by the contrast sensitivity of the eye at `ppd` pixels per degree (a sum of
///   Gaussians per channel, one kernel radius for all, clamp-to-edge borders), back to
///   linear sRGB clamped to [0, 1], to L*a*b* with the Hunt adjustment (a*, b* scaled by
///   L*/100); the HyAB distance |ΔL| + ‖Δ(a, b)‖ raised to q_c = 0.7 and mapped to
///   [0, 1]: errors below p_c = 0.4 of the largest (green against blue) onto [0, 0.95],
///   the rest onto (0.95, 1];
/// - *features*: edges and points of the (unfiltered) luminance by the first and second
///   derivatives of a Gaussian of σ = ½ · 0.082 · ppd pixels (positive and negative weights
///   each normalised to ±1), ΔE_f = (max(|‖e_t‖ − ‖e_r‖|, |‖p_t‖ − ‖p_r‖|) / √2)^0.5;
/// - error = ΔE_c^(1 − ΔE_f).
///
/// **HDR-ꟻLIP**: both images exposed by 2^c for exposures c evenly spaced from
/// c_start = log₂(x_max / Y_max) to c_stop = log₂(x_max / Y_median) (Y: the reference's
/// luminances; x_max: where the ACES tone curve reaches 0.85), ⌈c_stop − c_start⌉ of them
/// (at least 2); each exposure tone-mapped by the ACES fit and clamped to [0, 1], scored by
/// LDR-ꟻLIP; the error of a pixel is its largest over the exposures.
///
/// The default viewing condition is the papers': a 0.7 m wide monitor of 3 840 pixels seen
/// from 0.7 m, 67.02 pixels per degree. Computed in double precision; the reference
/// implementation computes in float (the values agree to about 1e-5, docs/metrics.md).
/// \throws std::invalid_argument for different or empty sizes, NaN/Inf, ppd ≤ 0, and (HDR)
/// a reference whose median luminance is not positive.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "iris/image.hpp"
#include "iris/metrics/common.hpp"

namespace iris {

/// \brief Pixels per degree of a monitor `width_m` wide with `pixels` across, seen from `distance_m`.
inline double flip_pixels_per_degree(double distance_m, double pixels, double width_m) {
    return distance_m * (pixels / width_m) * std::numbers::pi / 180.0;
}
/// \brief The papers' viewing condition: 0.7 m, 3 840 pixels across 0.7 m (67.02 ppd).
inline const double flip_default_ppd = flip_pixels_per_degree(0.7, 3840.0, 0.7);

namespace detail::flip {

/// \brief Linear sRGB → XYZ (D65), the exact rational matrix, and its inverse.
constexpr std::array<std::array<double, 3>, 3> rgb_to_xyz{{{10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
                                                           {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
                                                           {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}}};
constexpr std::array<std::array<double, 3>, 3> xyz_to_rgb{{{3.241003275, -1.537398934, -0.498615861},
                                                           {-0.969224334, 1.875930071, 0.041554224},
                                                           {0.055639423, -0.204011202, 1.057148933}}};
/// \brief The white of the sRGB primaries (rows of rgb_to_xyz summed).
constexpr std::array<double, 3> white{rgb_to_xyz[0][0] + rgb_to_xyz[0][1] + rgb_to_xyz[0][2],
                                      rgb_to_xyz[1][0] + rgb_to_xyz[1][1] + rgb_to_xyz[1][2],
                                      rgb_to_xyz[2][0] + rgb_to_xyz[2][1] + rgb_to_xyz[2][2]};

inline std::array<double, 3> mul(const std::array<std::array<double, 3>, 3>& m, const std::array<double, 3>& v) {
    return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

/// \brief Linear sRGB → YCxCz (the opponent space of the colour pipeline).
inline std::array<double, 3> ycxcz(const std::array<double, 3>& rgb) {
    const auto x = mul(rgb_to_xyz, rgb);
    const double X = x[0] / white[0], Y = x[1] / white[1], Z = x[2] / white[2];
    return {116.0 * Y - 16.0, 500.0 * (X - Y), 200.0 * (Y - Z)};
}

/// \brief YCxCz → linear sRGB clamped to [0, 1] → Hunt-adjusted L*a*b*.
inline std::array<double, 3> hunt_lab(const std::array<double, 3>& c) {
    const double Y = (c[0] + 16.0) / 116.0;
    std::array<double, 3> rgb = mul(xyz_to_rgb, {(Y + c[1] / 500.0) * white[0], Y * white[1], (Y - c[2] / 200.0) * white[2]});
    for (double& v : rgb) v = std::clamp(v, 0.0, 1.0);
    const auto x = mul(rgb_to_xyz, rgb);
    constexpr double d = 6.0 / 29.0;
    const auto f = [](double t) { return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0; };
    const double fx = f(x[0] / white[0]), fy = f(x[1] / white[1]), fz = f(x[2] / white[2]);
    const double L = 116.0 * fy - 16.0;
    return {L, 0.01 * L * 500.0 * (fx - fy), 0.01 * L * 200.0 * (fy - fz)};
}

inline double hyab(const std::array<double, 3>& p, const std::array<double, 3>& q) {
    return std::abs(p[0] - q[0]) + std::hypot(p[1] - q[1], p[2] - q[2]);
}

constexpr double qc = 0.7, pc = 0.4, pt = 0.95, qf = 0.5, feature_width = 0.082;

/// \brief The contrast sensitivity functions as sums of Gaussians a·√(π/b)·exp(−π²x²/b) in
/// degrees: achromatic, red–green, blue–yellow (two terms).
struct csf_term {
    double a, b;
};
constexpr csf_term csf_y{1.0, 0.0047}, csf_cx{1.0, 0.0053}, csf_cz1{34.1, 0.04}, csf_cz2{13.5, 0.025};

/// \brief One plane of doubles, row-major.
struct plane {
    int w = 0, h = 0;
    std::vector<double> v;
    plane(int width, int height) : w(width), h(height), v(static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {}
    double& at(int x, int y) { return v[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)]; }
    double at(int x, int y) const { return v[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)]; }
};

/// \brief `src` convolved with kx along x and ky along y (odd lengths, centred), borders clamped.
inline plane separable(const plane& src, const std::vector<double>& kx, const std::vector<double>& ky) {
    const int rx = static_cast<int>(kx.size() / 2), ry = static_cast<int>(ky.size() / 2);
    plane tmp(src.w, src.h), out(src.w, src.h);
    for (int y = 0; y < src.h; ++y)
        for (int x = 0; x < src.w; ++x) {
            double s = 0.0;
            for (int i = -rx; i <= rx; ++i) s += kx[static_cast<std::size_t>(i + rx)] * src.at(std::clamp(x + i, 0, src.w - 1), y);
            tmp.at(x, y) = s;
        }
    for (int y = 0; y < src.h; ++y)
        for (int x = 0; x < src.w; ++x) {
            double s = 0.0;
            for (int i = -ry; i <= ry; ++i) s += ky[static_cast<std::size_t>(i + ry)] * tmp.at(x, std::clamp(y + i, 0, src.h - 1));
            out.at(x, y) = s;
        }
    return out;
}

/// \brief The colour pipeline's kernels at `ppd`: the 1-D factors of each channel's 2-D
/// kernel, scaled so that the 2-D kernel sums to 1 (the blue–yellow one is a sum of two
/// separable terms).
struct csf_kernels {
    std::vector<double> y, cx, cz1, cz2;
};
inline csf_kernels make_csf_kernels(double ppd) {
    const double max_b = std::max({csf_y.b, csf_cx.b, csf_cz1.b, csf_cz2.b});
    const int r = static_cast<int>(std::ceil(3.0 * std::sqrt(max_b / (2.0 * std::numbers::pi * std::numbers::pi)) * ppd));
    const auto gauss = [&](const csf_term& t) {
        // 1-D factor of a·√(π/b)·exp(−π²(x² + y²)/b): √(a·√(π/b))·exp(−π²x²/b)
        std::vector<double> k(static_cast<std::size_t>(2 * r + 1));
        for (int i = -r; i <= r; ++i) {
            const double x = i / ppd;
            k[static_cast<std::size_t>(i + r)] =
                std::sqrt(t.a * std::sqrt(std::numbers::pi / t.b)) * std::exp(-std::numbers::pi * std::numbers::pi * x * x / t.b);
        }
        return k;
    };
    const auto sum = [](const std::vector<double>& k) {
        double s = 0.0;
        for (double v : k) s += v;
        return s;
    };
    csf_kernels c{gauss(csf_y), gauss(csf_cx), gauss(csf_cz1), gauss(csf_cz2)};
    // (Σk)² is the 2-D kernel's sum for one separable term, Σ over terms for two
    for (auto* k : {&c.y, &c.cx}) {
        const double s = sum(*k);
        for (double& v : *k) v /= s;
    }
    const double s = std::sqrt(sum(c.cz1) * sum(c.cz1) + sum(c.cz2) * sum(c.cz2));
    for (auto* k : {&c.cz1, &c.cz2})
        for (double& v : *k) v /= s;
    return c;
}

/// \brief The feature pipeline's kernels: a Gaussian (sums to 1) and its first and second
/// derivatives (positive and negative weights each summing to ±1).
struct feature_kernels {
    std::vector<double> g, dg, ddg;
};
inline feature_kernels make_feature_kernels(double ppd) {
    const double sd = 0.5 * feature_width * ppd;
    const int r = static_cast<int>(std::ceil(3.0 * sd));
    feature_kernels f;
    double gs = 0.0, dpos = 0.0, dneg = 0.0, ddpos = 0.0, ddneg = 0.0;
    for (int i = -r; i <= r; ++i) {
        const double x = i;
        const double g = std::exp(-(x * x) / (2.0 * sd * sd));
        const double dg = -x * g, ddg = (x * x / (sd * sd) - 1.0) * g;
        f.g.push_back(g), f.dg.push_back(dg), f.ddg.push_back(ddg);
        gs += g;
        (dg > 0 ? dpos : dneg) += std::abs(dg);
        (ddg > 0 ? ddpos : ddneg) += std::abs(ddg);
    }
    for (std::size_t i = 0; i < f.g.size(); ++i) {
        f.g[i] /= gs;
        f.dg[i] /= f.dg[i] > 0 ? dpos : dneg;
        f.ddg[i] /= f.ddg[i] > 0 ? ddpos : ddneg;
    }
    return f;
}

/// \brief What LDR-ꟻLIP needs of one image: its filtered Hunt L*a*b* and the magnitudes of
/// its edge and point responses.
struct prepared {
    std::vector<std::array<double, 3>> lab;
    std::vector<double> edge, point;
};

/// \brief `rgb(i)` is pixel i's linear sRGB (values outside [0, 1] are clamped).
template <class Rgb>
prepared prepare(int w, int h, Rgb&& rgb, const csf_kernels& csf, const feature_kernels& fk) {
    plane Y(w, h), Cx(w, h), Cz(w, h), gray(w, h);
    for (std::size_t i = 0; i < Y.v.size(); ++i) {
        std::array<double, 3> c = rgb(i);
        for (double& v : c) v = std::clamp(v, 0.0, 1.0);
        const auto o = ycxcz(c);
        Y.v[i] = o[0], Cx.v[i] = o[1], Cz.v[i] = o[2];
        gray.v[i] = (o[0] + 16.0) / 116.0;  // the luminance, normalised to the white's
    }
    const plane fy = separable(Y, csf.y, csf.y), fcx = separable(Cx, csf.cx, csf.cx);
    const plane fcz1 = separable(Cz, csf.cz1, csf.cz1), fcz2 = separable(Cz, csf.cz2, csf.cz2);
    prepared p;
    p.lab.reserve(Y.v.size());
    for (std::size_t i = 0; i < Y.v.size(); ++i) p.lab.push_back(hunt_lab({fy.v[i], fcx.v[i], fcz1.v[i] + fcz2.v[i]}));
    const plane ex = separable(gray, fk.dg, fk.g), ey = separable(gray, fk.g, fk.dg);
    const plane px = separable(gray, fk.ddg, fk.g), py = separable(gray, fk.g, fk.ddg);
    p.edge.reserve(Y.v.size());
    p.point.reserve(Y.v.size());
    for (std::size_t i = 0; i < Y.v.size(); ++i) {
        p.edge.push_back(std::hypot(ex.v[i], ey.v[i]));
        p.point.push_back(std::hypot(px.v[i], py.v[i]));
    }
    return p;
}

/// \brief The per-pixel LDR-ꟻLIP of two prepared images.
inline std::vector<float> ldr_map(const prepared& test, const prepared& ref) {
    const auto green = hunt_lab(ycxcz({0.0, 1.0, 0.0})), blue = hunt_lab(ycxcz({0.0, 0.0, 1.0}));
    const double cmax = std::pow(hyab(green, blue), qc);
    const double pccmax = pc * cmax;
    std::vector<float> out(ref.lab.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const double e = std::pow(hyab(test.lab[i], ref.lab[i]), qc);
        const double ec = e < pccmax ? pt / pccmax * e : pt + (e - pccmax) / (cmax - pccmax) * (1.0 - pt);
        const double ef = std::pow(std::max(std::abs(test.edge[i] - ref.edge[i]), std::abs(test.point[i] - ref.point[i])) /
                                       std::numbers::sqrt2,
                                   qf);
        out[i] = static_cast<float>(std::pow(ec, 1.0 - ef));
    }
    return out;
}

inline void require_ppd(double ppd) {
    if (!(ppd > 0.0 && std::isfinite(ppd)))
        throw std::invalid_argument("flip: pixels per degree must be a positive number, got " + std::to_string(ppd));
}

inline std::array<double, 3> rgb_of(const image& img, std::size_t i) {
    const auto& p = img.pixels()[i];
    return {p.r, p.g, p.b};
}

/// \brief The ACES fit (Narkowicz) with the papers' pre-exposure cancellation (0.6).
constexpr std::array<double, 6> aces{0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};
inline double tone(double x) {
    return std::clamp((x * x * aces[0] + x * aces[1] + aces[2]) / (x * x * aces[3] + x * aces[4] + aces[5]), 0.0, 1.0);
}

/// \brief What scoring a pair needs, after its checks: sizes and the kernels at `ppd`.
struct setup {
    setup(const image& img, const image& reference, double ppd)
        : w((require_comparable(img, reference, "flip"), require_ppd(ppd), img.width())),
          h(img.height()),
          csf(make_csf_kernels(ppd)),
          features(make_feature_kernels(ppd)) {}
    int w, h;
    csf_kernels csf;
    feature_kernels features;
};

}  // namespace detail::flip

/// \brief The per-pixel LDR-ꟻLIP of `img` against `reference` (row-major, values in [0, 1]).
inline std::vector<float> flip_map(const image& img, const image& reference, double ppd = flip_default_ppd) {
    using namespace detail::flip;
    const setup s(img, reference, ppd);
    return ldr_map(prepare(s.w, s.h, [&](std::size_t i) { return rgb_of(img, i); }, s.csf, s.features),
                   prepare(s.w, s.h, [&](std::size_t i) { return rgb_of(reference, i); }, s.csf, s.features));
}

/// \brief The exposures HDR-ꟻLIP scores a reference at.
struct flip_exposures {
    double start = 0, stop = 0;
    int count = 0;
};

/// \brief c_start, c_stop and their count from the reference's luminances (see the file's comment).
/// \throws std::invalid_argument if the reference's median luminance is not positive.
inline flip_exposures flip_exposure_range(const image& reference) {
    detail::require_finite(reference, "flip", "reference");
    using namespace detail::flip;
    // x_max: the larger root of tone(x) = 0.85, i.e. (a0 − t·a3)x² + (a1 − t·a4)x + (a2 − t·a5) = 0
    constexpr double t = 0.85;
    const double a = aces[0] - t * aces[3], b = aces[1] - t * aces[4], c = aces[2] - t * aces[5];
    const double disc = std::sqrt(b * b - 4.0 * a * c);
    const double x_max = std::max((-b + disc) / (2.0 * a), (-b - disc) / (2.0 * a));
    std::vector<double> lum(reference.pixel_count());
    for (std::size_t i = 0; i < lum.size(); ++i) {
        const auto p = rgb_of(reference, i);
        lum[i] = rgb_to_xyz[1][0] * p[0] + rgb_to_xyz[1][1] * p[1] + rgb_to_xyz[1][2] * p[2];
    }
    const double y_max = *std::max_element(lum.begin(), lum.end());
    auto mid = lum.begin() + static_cast<std::ptrdiff_t>(lum.size() / 2);
    std::nth_element(lum.begin(), mid, lum.end());
    const double y_median = *mid;
    if (!(y_median > 0.0))
        throw std::invalid_argument("flip: HDR-FLIP needs a reference whose median luminance is positive (its exposures "
                                    "run from its brightest pixel to its median); use LDR-FLIP for this image");
    flip_exposures e;
    e.start = std::log2(x_max / y_max);
    e.stop = std::log2(x_max / y_median);
    e.count = static_cast<int>(std::max(2.0, std::ceil(e.stop - e.start)));
    return e;
}

/// \brief The per-pixel HDR-ꟻLIP of `img` against `reference` (linear sRGB, any range):
/// the largest LDR-ꟻLIP over the exposures of `flip_exposure_range(reference)`.
inline std::vector<float> flip_hdr_map(const image& img, const image& reference, double ppd = flip_default_ppd) {
    using namespace detail::flip;
    const setup s(img, reference, ppd);
    const flip_exposures e = flip_exposure_range(reference);
    std::vector<float> out(reference.pixel_count(), 0.0f);
    for (int k = 0; k < e.count; ++k) {
        const double scale = std::exp2(e.start + k * (e.stop - e.start) / (e.count - 1));
        const auto exposed = [&](const image& src) {
            return [&src, scale](std::size_t i) {
                auto p = rgb_of(src, i);
                for (double& v : p) v = tone(v * scale);
                return p;
            };
        };
        const auto m = ldr_map(prepare(s.w, s.h, exposed(img), s.csf, s.features),
                               prepare(s.w, s.h, exposed(reference), s.csf, s.features));
        for (std::size_t i = 0; i < out.size(); ++i) out[i] = std::max(out[i], m[i]);
    }
    return out;
}

/// \brief The mean of a ꟻLIP map.
inline double flip_mean(const std::vector<float>& map) {
    double s = 0.0;
    for (float v : map) s += v;
    return map.empty() ? 0.0 : s / static_cast<double>(map.size());
}

/// \brief Mean LDR-ꟻLIP of `img` against `reference` (linear sRGB clamped to [0, 1]).
inline double flip(const image& img, const image& reference, double ppd = flip_default_ppd) {
    return flip_mean(flip_map(img, reference, ppd));
}

/// \brief Mean HDR-ꟻLIP of `img` against `reference` (linear sRGB).
inline double flip_hdr(const image& img, const image& reference, double ppd = flip_default_ppd) {
    return flip_mean(flip_hdr_map(img, reference, ppd));
}

}  // namespace iris
