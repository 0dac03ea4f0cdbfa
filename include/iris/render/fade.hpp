#pragma once
/// \file
/// \brief The bias fade (accumulation::fade): a pixel's value as the blend of the mean of
/// its samples taken while α < 1 (biased: the restriction and the bias term) and the mean
/// of those taken at α = 1 (unbiased) whose estimated mean squared error is smallest.
///
/// **The blend.** Let M_b be the mean of the n_b early samples, M_u that of the n_u late
/// ones, μ the pixel's true value, β = E[M_b] − μ the early samples' bias (E[M_u] = μ), V_b
/// and V_u the two means' variances (independent samples). The blend w·M_b + (1 − w)·M_u
/// has MSE(w) = w²(β² + V_b) + (1 − w)² V_u, smallest at
///
///     w* = V_u / (β² + V_b + V_u).
///
/// With no bias and the same variance per sample on both sides (V = σ²/n) this is
/// n_b / (n_b + n_u): the running mean. The estimate: V_b, V_u from the second moments
/// (sample variance / n); β² + V_b + V_u is the expectation of (M_b − M_u)², so the
/// denominator is max((M_b − M_u)², V_b + V_u) — the squared difference, but never less
/// than the noise it must contain. A single pixel's (M_b − M_u)² is one noisy draw, so the
/// numerator and the denominator are sums over the three channels (X, Y, Z) and over a
/// (2·radius + 1)² neighbourhood: one weight for the neighbourhood, applied to the centre
/// pixel's two means (the weight assumes the bias-to-noise ratio varies slowly, not the
/// image).
///
/// **Consistency.** n_b stops growing at N_thold while V_u = σ_u²/n_u → 0, so with
/// V_b + β² > 0 somewhere in the neighbourhood w ≤ V_u / (V_b + V_u) = O(1/n_u) and the
/// blend tends to M_u → μ, at least as fast as the running mean's N_thold/N; where
/// V_b = V_u = 0 and M_b = M_u (a constant pixel) w is the running mean's n_b / (n_b + n_u)
/// (→ 0 too). Conditions: the late samples' variance is finite (the estimator M_u is), and
/// n_b ≥ 2 and n_u ≥ 2 (variances need two samples; until then the pixel shows the running
/// mean — so before N_thold the fade shows exactly what `paper` shows). The blend is not
/// unbiased for finite n (w depends on the data); its bias vanishes with w.
///
/// **Exactness.** The second moments are summed exactly like the film's means: each
/// sample's v² (a correctly rounded double) in fixed point with 48 fractional bits, in a
/// 192-bit sum (v² < 2^78 for the film's |v| < 2^39, so a sample is < 2^126 and 2^32 of
/// them fit). Squares below 2^-48 (|v| < 1.5·10^-7) count as 0: a variance of that size is
/// nothing against any pixel's. So the image depends on which samples a pixel took, not on
/// the order they were added in.

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace iris::fade {

__extension__ typedef unsigned __int128 exact_uint;  ///< GCC and Clang, like film's exact_int

/// \brief Fractional bits of a fixed-point square.
inline constexpr int square_fraction_bits = 48;

/// \brief v² in fixed point (square_fraction_bits), rounded toward zero; exact for the v² of
/// every |v| < 2^39. w = v² · 2^48 < 2^126: its high 64 bits h = trunc(w · 2^-64) and the rest
/// w − h · 2^64 (exact, in [0, 2^64)) are each one 64-bit conversion.
inline exact_uint to_fixed_square(double v) noexcept {
    const double w = v * v * 0x1p48;
    const auto h = static_cast<std::uint64_t>(w * 0x1p-64);
    const auto rest = static_cast<std::uint64_t>(w - static_cast<double>(h) * 0x1p64);
    return (static_cast<exact_uint>(h) << 64) + rest;
}

/// \brief A sum of fixed-point squares: 192 bits (a 128-bit low part and its carries).
struct square_sum {
    exact_uint low = 0;
    std::uint64_t high = 0;

    void add(exact_uint v) noexcept {
        low += v;
        high += low < v ? 1 : 0;  // carry
    }
    void add(const square_sum& o) noexcept {
        add(o.low);
        high += o.high;
    }
    /// \brief The sum as a double (rounded once per part).
    double value() const noexcept {
        return (static_cast<double>(high) * 0x1p128 + static_cast<double>(low)) * 0x1p-48;
    }
    friend bool operator==(const square_sum&, const square_sum&) = default;
};

/// \brief One side of a pixel (early or late samples) in one channel: count, mean, and the
/// variance of the mean (sample variance / n; 0 for n < 2).
struct side {
    double n = 0, mean = 0, var_mean = 0;
};

/// \brief The side's statistics from its sum, sum of squares and count.
inline side make_side(double n, double sum, double sum_sq) noexcept {
    side s;
    s.n = n;
    if (n <= 0) return s;
    s.mean = sum / n;
    if (n >= 2) s.var_mean = std::max(0.0, (sum_sq - n * s.mean * s.mean) / (n - 1)) / n;
    return s;
}

/// \brief The weight sums of a neighbourhood: Σ V_u (numerator), Σ (V_b + V_u) and
/// Σ (M_b − M_u)² over its pixels and channels.
struct weight_sums {
    double var_late = 0, var_both = 0, diff_sq = 0;
    void add(const side& early, const side& late) noexcept {
        var_late += late.var_mean;
        var_both += early.var_mean + late.var_mean;
        diff_sq += (early.mean - late.mean) * (early.mean - late.mean);
    }
};

/// \brief w*: the weight of the early mean, from a neighbourhood's sums; `running` (the
/// running mean's n_b / (n_b + n_u)) where the neighbourhood has neither noise nor bias.
inline double weight(const weight_sums& s, double running) noexcept {
    const double denominator = std::max(s.diff_sq, s.var_both);
    if (!(denominator > 0)) return running;
    return std::clamp(s.var_late / denominator, 0.0, 1.0);
}

}  // namespace iris::fade
