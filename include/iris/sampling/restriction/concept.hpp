#pragma once
/// \file
/// \brief The `RestrictionKernel` concept: r_α(λ) ∈ [0, 1] with extent α ∈ [0, 1]
/// (docs/method.md §1). Models: `restriction::unrestricted`, `restriction::box`,
/// `restriction::multi_box<N>`, `restriction::gaussian` (catalogue: restriction.hpp).
///
/// A kernel is a small value type holding its parameters (centres, widths in nm).
/// Required, for a `const K& k`, `float α` and a `spectral_domain d`:
/// - `K::name`              a `std::string_view` (`box`, `multibox3`, …);
/// - `K::max_intervals`     how many disjoint intervals its support can have;
/// - `k.bind(α, d)`         → a `BoundRestriction`: r_α on Λ = d with its parameters
///                            resolved once (α is clamped to [0, 1]; NaN counts as 1).
/// A `BoundRestriction` `b` has:
/// - `b(λ)`                 → float r_α(λ) in [0, 1], finite for every float λ;
/// - `b.support()`          → `interval_set<K::max_intervals>`: sorted, disjoint, closed
///                            intervals inside Λ outside which r_α = 0 (possibly empty);
/// - `b.average(lo, hi)`    → double: the mean of r_α over [lo, hi] (lo < hi), used to
///                            weigh a distribution's cells (exactly, for smooth kernels);
/// - `B::indicator`         true when r_α only takes the values 0 and 1 (boxes): then
///                            r_α = 1 on the whole support and a distribution needs no
///                            kernel evaluations to weigh its cells.
/// The laws every model obeys (tests/sampling/laws_test.cpp checks them):
///   1. r_1(λ) = 1 on Λ;  2. r_α(λ) non-decreasing in α;  3. ∫ p r_α > 0 for a p > 0 on Λ.

#include <algorithm>
#include <array>
#include <concepts>
#include <cstddef>
#include <limits>
#include <string_view>

#include "iris/sampling/domain.hpp"

namespace iris {

/// \brief A closed wavelength interval [lo, hi] in nm.
struct spectral_interval {
    float lo = 0.0f;
    float hi = 0.0f;
    friend constexpr bool operator==(const spectral_interval&, const spectral_interval&) = default;
};

/// \brief At most N closed intervals; `clipped(d)` sorts, merges and clips them to d.
template <std::size_t N>
class interval_set {
public:
    static constexpr std::size_t capacity = N;

    constexpr void insert(float lo, float hi) noexcept {
        if (m_size < N) m_items[m_size++] = {lo, hi};
    }
    constexpr std::size_t size() const noexcept { return m_size; }
    constexpr bool empty() const noexcept { return m_size == 0; }
    constexpr const spectral_interval& operator[](std::size_t i) const noexcept { return m_items[i]; }
    constexpr const spectral_interval* begin() const noexcept { return m_items.data(); }
    constexpr const spectral_interval* end() const noexcept { return m_items.data() + m_size; }

    /// \brief The union of the intervals intersected with d: sorted, disjoint (touching
    /// ones merged), each of positive width; NaN or empty intervals dropped.
    constexpr interval_set clipped(const spectral_domain& d) const noexcept {
        interval_set out;
        for (const auto& x : *this) {
            const float lo = std::max(x.lo, d.min_nm), hi = std::min(x.hi, d.max_nm);
            if (lo < hi) out.insert(lo, hi);  // false for NaN
        }
        // insertion sort by lo (N is small), then merge
        for (std::size_t i = 1; i < out.m_size; ++i)
            for (std::size_t j = i; j > 0 && out.m_items[j].lo < out.m_items[j - 1].lo; --j)
                std::swap(out.m_items[j], out.m_items[j - 1]);
        std::size_t k = 0;
        for (std::size_t i = 0; i < out.m_size; ++i) {
            if (k > 0 && out.m_items[i].lo <= out.m_items[k - 1].hi)
                out.m_items[k - 1].hi = std::max(out.m_items[k - 1].hi, out.m_items[i].hi);
            else
                out.m_items[k++] = out.m_items[i];
        }
        out.m_size = k;
        return out;
    }

    /// \brief Total length of the intervals (nm); meaningful after `clipped`.
    constexpr double length() const noexcept {
        double s = 0.0;
        for (const auto& x : *this) s += static_cast<double>(x.hi) - static_cast<double>(x.lo);
        return s;
    }

private:
    std::array<spectral_interval, N> m_items{};
    std::size_t m_size = 0;
};

template <class B>
concept BoundRestriction = std::copyable<B> && requires(const B& b, float lambda_nm) {
    { b(lambda_nm) } -> std::same_as<float>;
    { b.average(lambda_nm, lambda_nm) } -> std::same_as<double>;
    b.support();
    { B::indicator } -> std::convertible_to<bool>;
};

/// \brief Optional, for speed: a bound kernel whose cell means come from values at the
/// cell edges (`b.edge_at(x)` → `B::edge`, `b.average(e0, e1)` → double, equal to
/// `b.average(lo, hi)`), so a distribution evaluates the expensive part once per edge
/// instead of twice per cell (the Gaussian's erfc).
template <class B>
concept EdgeAveragedRestriction = BoundRestriction<B> && requires(const B& b, float x, const typename B::edge& e) {
    { b.edge_at(x) } -> std::same_as<typename B::edge>;
    { b.average(e, e) } -> std::same_as<double>;
};

template <class K>
concept RestrictionKernel = std::copyable<K> && requires(const K& k, float alpha, const spectral_domain& d) {
    { K::name } -> std::convertible_to<std::string_view>;
    { K::max_intervals } -> std::convertible_to<std::size_t>;
    { k.bind(alpha, d) } -> BoundRestriction;
    { k.bind(alpha, d).support() } -> std::convertible_to<interval_set<K::max_intervals>>;
};

namespace restriction::detail {
/// \brief α clamped to [0, 1]; NaN → 1 (the safe end: no restriction).
constexpr float clamp_alpha(float alpha) noexcept {
    if (!(alpha >= 0.0f)) return alpha < 0.0f ? 0.0f : 1.0f;
    return alpha > 1.0f ? 1.0f : alpha;
}
/// \brief The narrowest window used (nm): law 3 needs a window of positive width.
inline constexpr double min_window_nm = 1e-3;

/// \brief A window of centre c and initial width w0 whose edges move linearly, as α goes
/// from 0 to 1, from c ∓ w0/2 out to [share_lo, share_hi] (its part of Λ). An edge that
/// already lies beyond its share stays where it is, so the window never shrinks (law 2).
/// At α = 1 the window is the whole line: r_1 ≡ 1 exactly, whatever the rounding (law 1).
constexpr spectral_interval grow_window(double c, float w0, double share_lo, double share_hi, float alpha) noexcept {
    const float a = clamp_alpha(alpha);
    if (a >= 1.0f) return {-std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
    double w = static_cast<double>(w0);
    if (!(w >= min_window_nm)) w = min_window_nm;  // also NaN
    if (w > 4.0 * (share_hi - share_lo) + 1e6) w = 4.0 * (share_hi - share_lo) + 1e6;  // also Inf
    const double lo0 = c - 0.5 * w, hi0 = c + 0.5 * w, t = static_cast<double>(a);
    const double lo = lo0 > share_lo ? lo0 + t * (share_lo - lo0) : lo0;
    const double hi = hi0 < share_hi ? hi0 + t * (share_hi - hi0) : hi0;
    // (within float range even on a nonsense domain: an out-of-range cast is undefined)
    return {static_cast<float>(std::clamp(lo, -3.0e38, 3.0e38)), static_cast<float>(std::clamp(hi, -3.0e38, 3.0e38))};
}

/// \brief Mean over [lo, hi] of the indicator of the closed window w (overlap / length).
constexpr double window_average(const spectral_interval& w, float lo, float hi) noexcept {
    const double a = std::max(static_cast<double>(lo), static_cast<double>(w.lo));
    const double b = std::min(static_cast<double>(hi), static_cast<double>(w.hi));
    const double len = static_cast<double>(hi) - static_cast<double>(lo);
    return len > 0.0 && b > a ? std::min(1.0, (b - a) / len) : 0.0;
}
/// \brief The centre clamped into d (NaN → d's middle): a window or bump centred
/// outside Λ could hold no mass there, breaking law 3.
constexpr double sane_centre(float c, const spectral_domain& d) noexcept {
    const double x = static_cast<double>(c);
    if (!(x == x)) return 0.5 * (static_cast<double>(d.min_nm) + static_cast<double>(d.max_nm));
    return std::clamp(x, static_cast<double>(d.min_nm), static_cast<double>(d.max_nm));
}
}  // namespace restriction::detail

}  // namespace iris
