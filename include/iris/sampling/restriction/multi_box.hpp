#pragma once
/// \file
/// \brief `restriction::multi_box<N>`: N windows; r = 1 inside any of them. The paper's
/// multimodal kernel (three boxes near blue, green and red).
///
/// Growth: window k owns a share of Λ — the wavelengths nearer its centre than any other
/// centre (cut at the midpoints between neighbouring centres) — and its edges move
/// linearly from c_k ∓ w0_k/2 at α = 0 to the ends of its share at α = 1. The union of
/// the windows therefore grows linearly from Σ w0_k to |Λ| (when the windows start inside
/// their shares; an edge that starts beyond its share stays put), instead of the windows
/// swallowing the spectrum long before α = 1. At α = 1 the union is Λ: r_1 ≡ 1 exactly.
///
/// Parameters (nm)     | default (N = 3)        | default (other N)
/// --------------------|------------------------|------------------------------------------
/// `centres_nm[k]`     | 464, 549, 611          | 380 + 400 (k + ½) / N, evenly over 380–780
/// `widths_nm[k]` (w0) | 20 each                | 20 each
///
/// The N = 3 centres are the dominant wavelengths of the sRGB primaries (blue, green, red)
/// seen from D65: the windows sit where the display's three colours come from, which is
/// what the paper's placement by hand aimed at (its Fig. 6 used 465, 570, 580 nm).
/// Centres are clamped into Λ and may come in any order.

#include <algorithm>
#include <array>
#include <cstddef>
#include <string_view>

#include "iris/sampling/detail/name.hpp"
#include "iris/sampling/restriction/concept.hpp"

namespace iris::restriction {

/// \brief N growing windows; centres and widths are runtime values.
template <std::size_t N>
struct multi_box {
    static_assert(N >= 1, "multi_box<N> needs at least one window (N >= 1)");
    static_assert(N <= 16, "multi_box<N> supports at most 16 windows: more would sample most of the spectrum anyway");

    static constexpr std::string_view name = iris::detail::numbered_name_v<"multibox", N>.view();
    static constexpr std::size_t max_intervals = N;

    std::array<float, N> centres_nm = default_centres();
    std::array<float, N> widths_nm = default_widths();

    static constexpr std::array<float, N> default_centres() noexcept {
        std::array<float, N> c{};
        if constexpr (N == 3) {
            c = {464.0f, 549.0f, 611.0f};
        } else {
            for (std::size_t k = 0; k < N; ++k)
                c[k] = 380.0f + 400.0f * (static_cast<float>(k) + 0.5f) / static_cast<float>(N);
        }
        return c;
    }
    static constexpr std::array<float, N> default_widths() noexcept {
        std::array<float, N> w{};
        w.fill(20.0f);
        return w;
    }

    struct bound {
        static constexpr bool indicator = true;
        std::array<spectral_interval, N> windows{};  ///< closed, unclipped (±Inf at α = 1)
        interval_set<N> merged;                       ///< their union ∩ Λ
        constexpr float operator()(float lambda_nm) const noexcept {
            for (const auto& w : windows)
                if (lambda_nm >= w.lo && lambda_nm <= w.hi) return 1.0f;
            return 0.0f;
        }
        /// \brief Overlap of [a, b] with the union of the windows, over b − a.
        constexpr double average(float a, float b) const noexcept {
            double covered = 0.0;
            for (const auto& m : merged) covered += detail::window_average(m, a, b);
            return std::min(1.0, covered);
        }
        constexpr const interval_set<N>& support() const noexcept { return merged; }
    };

    constexpr bound bind(float alpha, const spectral_domain& d) const noexcept {
        // centres in increasing order (insertion sort: N is small), then each one's share
        std::array<std::size_t, N> order{};
        std::array<double, N> c{};
        for (std::size_t k = 0; k < N; ++k) {
            order[k] = k;
            c[k] = detail::sane_centre(centres_nm[k], d);
        }
        for (std::size_t i = 1; i < N; ++i)
            for (std::size_t j = i; j > 0 && c[order[j]] < c[order[j - 1]]; --j) std::swap(order[j], order[j - 1]);
        bound b;
        interval_set<N> s;
        for (std::size_t i = 0; i < N; ++i) {
            const std::size_t k = order[i];
            const double share_lo = i == 0 ? static_cast<double>(d.min_nm) : 0.5 * (c[order[i - 1]] + c[k]);
            const double share_hi = i + 1 == N ? static_cast<double>(d.max_nm) : 0.5 * (c[k] + c[order[i + 1]]);
            b.windows[k] = detail::grow_window(c[k], widths_nm[k], share_lo, share_hi, alpha);
            s.insert(b.windows[k].lo, b.windows[k].hi);
        }
        b.merged = s.clipped(d);
        return b;
    }
};

static_assert(RestrictionKernel<multi_box<3>>);

}  // namespace iris::restriction
