#pragma once
/// \file
/// \brief `restriction::box`: one window, r = 1 inside, 0 outside. Its edges move
/// linearly from c ∓ w0/2 at α = 0 to λmin and λmax at α = 1, so the window covers
/// w0 + α (|Λ| − w0) of Λ (when it starts inside Λ); at α = 1 it is the whole line, so
/// r_1 ≡ 1 holds exactly.
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
    static constexpr float min_width_nm = static_cast<float>(detail::min_window_nm);

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

    /// \brief The window [lo, hi] of a box of centre c and initial width w0 at α on d.
    static constexpr spectral_interval window_at(float centre, float w0, float alpha, const spectral_domain& d) noexcept {
        return detail::grow_window(detail::sane_centre(centre, d), w0, d.min_nm, d.max_nm, alpha);
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
