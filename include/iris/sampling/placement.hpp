#pragma once
/// \file
/// \brief Window placement: where `multi_box<N>`'s windows sit. A compile-time policy of
/// `integrator_config` (its sixth parameter):
///
/// | policy | name | windows |
/// |---|---|---|
/// | `placement::fixed` | (none) | the kernel's own centres and widths: the paper's, placed by hand |
/// | `placement::emitters` | `auto` | chosen once per render from the scene's emitted spectrum (`place_windows`) |
///
/// **The criterion (`place_windows`).** Before the first sample the renderer knows what the
/// scene emits, E(λ), and what the image records of it: linear sRGB, whose matching
/// functions r̄, ḡ, b̄ are the CIE 1931 x̄, ȳ, z̄ through the sRGB matrix. Channel c receives
/// the emitted signal S_c(λ) = E(λ)·c̄⁺(λ), with c̄⁺ = max(c̄, 0) the function's positive lobe
/// (r̄⁺ peaks near 600 nm, ḡ⁺ near 540, b̄⁺ near 450). While α is small the wavelengths are
/// drawn inside the windows only; what lies outside reaches the image through the bias term
/// alone (for `restrict-only`, not at all). A channel whose signal falls mostly outside the
/// windows is the one whose early estimate is worst: colour noise. So the windows maximise
///
///     J = Σ_c log s_c,    s_c = ∫_windows S_c / ∫_Λ S_c   (the share of channel c inside),
///
/// over the channels that receive any signal: the geometric mean of the three shares. The
/// logarithm makes the channels equal partners: a placement that leaves one channel with
/// nothing scores −∞, however much it captures of the others, where the plain sum Σ s_c
/// would crowd the windows where the channels overlap. Display channels rather than x̄, ȳ,
/// z̄: x̄ and ȳ overlap over most of 500–650 nm, so one window near 575 nm serves both and the
/// placement leaves λ > 600 nm, where the display's red comes from, unsampled (measured on
/// D65: windows 445/457.5/572.5 nm). The criterion looks at α = 0: the windows' first extent
/// is what the first samples — the ones the method exists for — see; the windows then grow
/// over their shares (multi_box.hpp) whatever their placement. It does not use the base
/// pdf: inside the windows the estimator is unbiased for any p > 0, so p changes the
/// variance there, not which signal is inside.
///
/// **The search.** Λ is cut into 400 equal cells (1 nm on 380–780 nm). The windows keep the
/// paper's total extent, 60 cells (3 × 20 nm: 15 % of Λ), so a comparison with the hand
/// placement compares positions, not how much of the spectrum is sampled; each window is
/// 10–40 cells wide in steps of 5 (a narrow emission line needs a narrow window, a broad
/// channel a wide one). Every ordered, non-overlapping placement on a 5-cell lattice is
/// scored (about 1.6 million for N = 3, a few tens of milliseconds), then the best one is
/// refined while J grows: a window moved by 1–5 cells, or 5 cells of width handed from one
/// window to another. The result is a local optimum for those moves (tested), not
/// necessarily the global one on the 1-cell lattice. Deterministic: ties go to the
/// placement found first (leftmost).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <string_view>
#include <vector>

#include "iris/sampling/domain.hpp"
#include "iris/spectrum/color.hpp"

namespace iris::placement {

/// \brief The kernel's own centres and widths (for `multi_box<3>`: 464, 549, 611 nm, 20 nm).
struct fixed {
    static constexpr std::string_view name = "fixed";
    static constexpr bool automatic = false;
};

/// \brief `multi_box<N>` windows placed from the scene's emitted spectrum (`place_windows`).
struct emitters {
    static constexpr std::string_view name = "auto";
    static constexpr bool automatic = true;
};

/// \brief What a placement policy provides: a name and whether the renderer places the windows.
template <class P>
concept Placement = requires {
    { P::name } -> std::convertible_to<std::string_view>;
    { P::automatic } -> std::convertible_to<bool>;
};

/// \brief Cells of the search lattice over Λ, and the windows' total extent in cells.
inline constexpr int cells = 400;
inline constexpr int step_cells = 5;
inline constexpr int min_width_cells = 10;
inline constexpr int max_width_cells = 40;
inline constexpr int total_width_cells_per_window = 20;

/// \brief The emitted signal each channel receives, per lattice cell of Λ: the emitted
/// spectrum `emitted(λ)` (any callable; its scale does not matter) times r̄⁺, ḡ⁺, b̄⁺, at
/// the cells' centres.
template <class Emitted>
std::vector<std::array<double, 3>> channel_signals(const Emitted& emitted, const spectral_domain& d) {
    std::vector<std::array<double, 3>> s(cells);
    const double width = static_cast<double>(d.max_nm) - static_cast<double>(d.min_nm);
    for (int k = 0; k < cells; ++k) {
        const double lambda = static_cast<double>(d.min_nm) + width * (k + 0.5) / cells;
        const double e = static_cast<double>(emitted(lambda));
        const double v = std::isfinite(e) && e > 0.0 ? e : 0.0;
        const rgb m = xyz_to_linear_srgb({cie::x_bar(lambda), cie::y_bar(lambda), cie::z_bar(lambda)});
        s[static_cast<std::size_t>(k)] = {v * std::max(m.r, 0.0), v * std::max(m.g, 0.0), v * std::max(m.b, 0.0)};
    }
    return s;
}

/// \brief Windows on Λ and how well they do.
template <std::size_t N>
struct placed_windows {
    std::array<float, N> centres_nm{};
    std::array<float, N> widths_nm{};
    std::array<double, 3> captured{};     ///< s_c: share of r̄⁺'s, ḡ⁺'s and b̄⁺'s signal inside the windows (NaN: no signal)
    double score = -std::numeric_limits<double>::infinity();  ///< J (over the channels with signal)
    bool placed = false;  ///< false: no channel receives any signal, the windows are the kernel's defaults
};

namespace detail {

/// \brief Prefix sums of the channels' shares: prefix[k][c] = share of channel c in cells [0, k).
struct share_table {
    std::vector<std::array<double, 3>> prefix;
    std::array<bool, 3> active{};
    bool any = false;

    explicit share_table(std::span<const std::array<double, 3>> signal) : prefix(signal.size() + 1) {
        std::array<double, 3> total{};
        for (const auto& s : signal)
            for (int c = 0; c < 3; ++c) total[static_cast<std::size_t>(c)] += s[static_cast<std::size_t>(c)];
        const double biggest = std::max({total[0], total[1], total[2]});
        for (std::size_t c = 0; c < 3; ++c) {
            active[c] = biggest > 0.0 && std::isfinite(biggest) && total[c] > 1e-9 * biggest;
            any = any || active[c];
        }
        for (std::size_t k = 0; k < signal.size(); ++k)
            for (std::size_t c = 0; c < 3; ++c)
                prefix[k + 1][c] = prefix[k][c] + (active[c] ? signal[k][c] / total[c] : 0.0);
    }
    double share(int lo, int hi, std::size_t c) const noexcept {
        return prefix[static_cast<std::size_t>(hi)][c] - prefix[static_cast<std::size_t>(lo)][c];
    }
    /// \brief Π s_c over the active channels: exp(J), what the search compares (no logarithms
    /// in the inner loop; the same order as J, with J = −∞ as 0).
    double product(const std::array<double, 3>& s) const noexcept {
        double p = 1.0;
        for (std::size_t c = 0; c < 3; ++c)
            if (active[c]) p *= std::max(s[c], 0.0);
        return p;
    }
    double score(const std::array<double, 3>& s) const noexcept {
        double j = 0.0;
        for (std::size_t c = 0; c < 3; ++c)
            if (active[c]) j += s[c] > 0.0 ? std::log(s[c]) : -std::numeric_limits<double>::infinity();
        return j;
    }
};

/// \brief A placement on the lattice: window k covers cells [lo[k], lo[k] + w[k]).
template <std::size_t N>
struct lattice_windows {
    std::array<int, N> lo{}, w{};
};

template <std::size_t N>
std::array<double, 3> captured(const share_table& t, const lattice_windows<N>& p) {
    std::array<double, 3> s{};
    for (std::size_t k = 0; k < N; ++k)
        for (std::size_t c = 0; c < 3; ++c) s[c] += t.share(p.lo[k], p.lo[k] + p.w[k], c);
    return s;
}

/// \brief Every ordered placement of windows k..N−1 from cell `from` on, with `width_left`
/// cells to share; keeps the best in `best` (by exp(J), strictly better only: the first
/// found wins ties).
template <std::size_t N>
void search(const share_table& t, std::size_t k, int from, int width_left, std::array<double, 3> acc,
            lattice_windows<N>& cur, lattice_windows<N>& best, double& best_score) {
    const int windows_left = static_cast<int>(N - k);
    if (windows_left == 0) {
        const double j = t.product(acc);
        if (j > best_score || best.w[0] == 0) {  // the first placement, even at J = −∞, then strictly better ones
            best_score = j;
            best = cur;
        }
        return;
    }
    for (int w = min_width_cells; w <= max_width_cells; w += step_cells) {
        const int rest = width_left - w;  // the later windows' cells
        if (rest < (windows_left - 1) * min_width_cells || rest > (windows_left - 1) * max_width_cells) continue;
        for (int lo = from; lo + w + rest <= cells; lo += step_cells) {
            std::array<double, 3> next = acc;
            for (std::size_t c = 0; c < 3; ++c) next[c] += t.share(lo, lo + w, c);
            cur.lo[k] = lo;
            cur.w[k] = w;
            search<N>(t, k + 1, lo + w, rest, next, cur, best, best_score);
        }
    }
}

}  // namespace detail

/// \brief How well given windows (centres and widths in nm) capture the channels' signal:
/// the windows as they are at α = 0, clipped to Λ (overlaps counted once).
template <std::size_t N>
placed_windows<N> evaluate_windows(std::span<const std::array<double, 3>> signal, const spectral_domain& d,
                                   const std::array<float, N>& centres_nm, const std::array<float, N>& widths_nm) {
    const detail::share_table t(signal);
    placed_windows<N> r;
    r.centres_nm = centres_nm;
    r.widths_nm = widths_nm;
    const double width = static_cast<double>(d.max_nm) - static_cast<double>(d.min_nm);
    const int n = static_cast<int>(signal.size());
    std::vector<bool> inside(signal.size(), false);
    for (std::size_t k = 0; k < N; ++k) {
        for (int i = 0; i < n; ++i) {
            const double lambda = static_cast<double>(d.min_nm) + width * (i + 0.5) / n;
            if (std::abs(lambda - static_cast<double>(centres_nm[k])) <= 0.5 * static_cast<double>(widths_nm[k]))
                inside[static_cast<std::size_t>(i)] = true;
        }
    }
    for (std::size_t c = 0; c < 3; ++c) {
        double s = 0.0;
        for (int i = 0; i < n; ++i)
            if (inside[static_cast<std::size_t>(i)]) s += t.share(i, i + 1, c);
        r.captured[c] = t.active[c] ? s : std::numeric_limits<double>::quiet_NaN();
    }
    std::array<double, 3> s{};
    for (std::size_t c = 0; c < 3; ++c) s[c] = t.active[c] ? r.captured[c] : 0.0;
    r.score = t.score(s);
    r.placed = t.any;
    return r;
}

/// \brief The windows that maximise J (see the file comment) for the channel signals of
/// `channel_signals` (`cells` entries). Without any signal (no emitter, or none inside Λ)
/// the kernel's defaults `default_centres`/`default_widths` are returned with `placed` false.
template <std::size_t N>
placed_windows<N> place_windows(std::span<const std::array<double, 3>> signal, const spectral_domain& d,
                                const std::array<float, N>& default_centres, const std::array<float, N>& default_widths) {
    static_assert(N >= 1 && N * total_width_cells_per_window <= static_cast<std::size_t>(cells),
                  "the windows' total extent must fit in Λ");
    const detail::share_table t(signal);
    if (!t.any || static_cast<int>(signal.size()) != cells) {
        auto r = evaluate_windows<N>(signal, d, default_centres, default_widths);
        r.placed = false;
        return r;
    }
    detail::lattice_windows<N> cur, best;
    double best_score = -std::numeric_limits<double>::infinity();
    detail::search<N>(t, 0, 0, static_cast<int>(N) * total_width_cells_per_window, {}, cur, best, best_score);
    best_score = t.score(detail::captured(t, best));  // exp(J) → J
    // refine while J grows: move one window by 1–5 cells, or hand 5 cells of width from one
    // window to another (each keeping its start or its end); windows stay ordered and disjoint
    const auto valid = [](const detail::lattice_windows<N>& p) {
        for (std::size_t k = 0; k < N; ++k) {
            if (p.w[k] < min_width_cells || p.w[k] > max_width_cells || p.lo[k] < 0 || p.lo[k] + p.w[k] > cells) return false;
            if (k > 0 && p.lo[k] < p.lo[k - 1] + p.w[k - 1]) return false;
        }
        return true;
    };
    const auto try_move = [&](const detail::lattice_windows<N>& p) {
        if (!valid(p)) return false;
        const double j = t.score(detail::captured(t, p));
        if (!(j > best_score)) return false;
        best_score = j;
        best = p;
        return true;
    };
    for (bool moved = true; moved;) {
        moved = false;
        for (std::size_t k = 0; k < N; ++k)
            for (int dl = -step_cells; dl <= step_cells; ++dl) {
                auto p = best;
                p.lo[k] += dl;
                moved |= dl != 0 && try_move(p);
            }
        for (std::size_t from = 0; from < N; ++from)
            for (std::size_t to = 0; to < N; ++to)
                for (int keep = 0; from != to && keep < 4; ++keep) {
                    auto p = best;
                    p.w[from] -= step_cells;
                    if (keep & 1) p.lo[from] += step_cells;  // the shrunk window keeps its end
                    p.w[to] += step_cells;
                    if (keep & 2) p.lo[to] -= step_cells;  // the grown one keeps its end
                    moved |= try_move(p);
                }
    }
    placed_windows<N> r;
    const double cell_nm = (static_cast<double>(d.max_nm) - static_cast<double>(d.min_nm)) / cells;
    const auto s = detail::captured(t, best);
    for (std::size_t k = 0; k < N; ++k) {
        r.centres_nm[k] = static_cast<float>(static_cast<double>(d.min_nm) + cell_nm * (best.lo[k] + 0.5 * best.w[k]));
        r.widths_nm[k] = static_cast<float>(cell_nm * best.w[k]);
    }
    for (std::size_t c = 0; c < 3; ++c) r.captured[c] = t.active[c] ? s[c] : std::numeric_limits<double>::quiet_NaN();
    r.score = best_score;
    r.placed = true;
    return r;
}

}  // namespace iris::placement
