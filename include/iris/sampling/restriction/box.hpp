#pragma once
/// \file
/// \brief `restriction::box`: one window [c − w(α)/2, c + w(α)/2], r = 1 inside, 0 outside.
/// w(α) = w0 + α (w_cover − w0), w_cover = 2 max(c − λmin, λmax − c): at α = 1 the box
/// covers Λ (and r_1 ≡ 1 holds exactly: the window is then the whole line).
///
/// Parameters (nm)   | default | note
/// ------------------|---------|-----------------------------------------------
/// `centre_nm`       | 580     | the paper's Fig. 5 peak; clamped into Λ
/// `width_nm` (w0)   | 20      | the paper's initial width; < 1e-3 nm counts as 1e-3 nm

#include <cmath>
#include <limits>
#include <string_view>

#include "iris/sampling/restriction/concept.hpp"

namespace iris::restriction {

/// \brief A single growing window (the paper's unimodal box).
struct box {
    static constexpr std::string_view name = "box";
    static constexpr std::size_t max_intervals = 1;
    /// \brief Narrowest window used (nm): law 3 needs a window of positive width.
    static constexpr float min_width_nm = 1e-3f;

    float centre_nm = 580.0f;
    float width_nm = 20.0f;

    struct bound {
        static constexpr bool indicator = true;
        float lo = 0.0f, hi = 0.0f;  ///< the closed window (±Inf at α = 1)
        interval_set<1> window;       ///< [lo, hi] ∩ Λ
        constexpr float operator()(float lambda_nm) const noexcept {
            return lambda_nm >= lo && lambda_nm <= hi ? 1.0f : 0.0f;
        }
        constexpr double average(float a, float b) const noexcept { return detail::window_average({lo, hi}, a, b); }
        constexpr const interval_set<1>& support() const noexcept { return window; }
    };

    /// \brief The window [lo, hi] of a box of centre c and initial width w0 at α on d
    /// (shared with `multi_box`, so r and the support always agree bit for bit).
    static constexpr spectral_interval window_at(float centre, float w0, float alpha, const spectral_domain& d) noexcept {
        const float a = detail::clamp_alpha(alpha);
        if (a >= 1.0f) return {-std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
        const double c = detail::sane_centre(centre, d);
        const double cover = detail::cover_width(c, d);
        double w = static_cast<double>(w0);
        if (!(w >= static_cast<double>(min_width_nm))) w = static_cast<double>(min_width_nm);  // also NaN
        if (w > cover) w = cover;
        const double half = 0.5 * (w + static_cast<double>(a) * (cover - w));
        return {static_cast<float>(c - half), static_cast<float>(c + half)};
    }

    constexpr bound bind(float alpha, const spectral_domain& d) const noexcept {
        const spectral_interval w = window_at(centre_nm, width_nm, alpha, d);
        interval_set<1> s;
        s.insert(w.lo, w.hi);
        return {w.lo, w.hi, s.clipped(d)};
    }
};

static_assert(RestrictionKernel<box>);

}  // namespace iris::restriction
