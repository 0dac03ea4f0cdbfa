#pragma once
/// \file
/// \brief Scrambled Sobol' points for the renderer's low-discrepancy samplers (std only).
///
/// **The sequence.** Sobol' points from Joe & Kuo's direction numbers (new-joe-kuo-6.21201,
/// its first 256 dimensions, data/sobol_joe_kuo_6_256.txt): dimension 0 is the van der
/// Corput sequence (the index's bits reversed), dimension d ≥ 1 XORs the generator columns
/// v_{d,k} of the set bits k of the index (`point`). Dimensions 0 and 1 together are a
/// (0, 2)-sequence: every aligned block of 2^m consecutive points puts exactly one point in
/// each elementary interval of area 2^-m. Other pairs of Sobol' dimensions are not, but
/// every dimension d has a partner that is: `paired`, (x_d, dimension1(reverse(x_d))). Its
/// generator matrices are (C_d, C₁·C_d) with C₁ = dimension 1's; because all Sobol'
/// generators are upper triangular, the top-left m × m blocks of (C_d, C₁C_d) are those of
/// (I, C₁)·C_d, and C_d's block is invertible, so every 2^m-block of the pair is a
/// (0, m, 2)-net exactly when (dimensions 0, 1) are — always. The renderer's 2-D slots use
/// such pairs (render/random.hpp), so a pixel's samples are stratified in every slot *and*
/// jointly across slots as far as the Sobol' dimensions are.
///
/// **Owen scrambling** (`owen_scramble`): each bit of a 32-bit fixed-point value is flipped
/// by a hash of the bits above it — a nested uniform scramble, computed from the
/// Laine–Karras hash on the bit-reversed value (Burley, "Practical Hash-based Owen
/// Scrambling", JCGT 9(4), 2020, with his constants). It keeps every net a net and makes each
/// point uniform on [0, 1).
///
/// **Index shuffling** (`shuffle_index`): the same nested scramble applied to the index bits
/// the other way round (each bit flipped by a hash of the bits *above* it), so that the
/// first 2^m shuffled indices are again an aligned block of 2^m indices, in another order:
/// a pixel's first 2^m samples stay a (0, m, 2)-net whatever the shuffle. XORed with the
/// shuffle of 0 (`shuffle_index ⊕ shuffle_index(0)`, still a nested scramble) it maps
/// [0, 2^m) onto itself, so `point` loops over no more bits than the sample count has.
/// One shuffle for all dimensions keeps the dimensions' joint structure; a shuffle per
/// dimension ("padding", Burley 2020 §4–5, pbrt-v4's PaddedSobol) decorrelates them, which
/// the renderer does only past the table (render/random.hpp).

#include <bit>
#include <cstdint>

#include "iris/sampling/data/sobol_joe_kuo.hpp"

namespace iris::sobol {

/// \brief The 32 bits of v in reverse order (a byte swap, then the bits of each byte).
constexpr std::uint32_t reverse_bits(std::uint32_t v) noexcept {
    v = __builtin_bswap32(v);
    v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    return ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
}

/// \brief Sobol' dimension 0 of point `i` as 32-bit fixed point (value = result · 2⁻³²).
constexpr std::uint32_t dimension0(std::uint32_t i) noexcept { return reverse_bits(i); }

/// \brief Sobol' dimension 1 of point `i` by its definition: the XOR of the generator
/// columns v_k of the set bits k of i (v₁ = 2³¹, v_k = v_{k−1} ⊕ (v_{k−1} ≫ 1)).
constexpr std::uint32_t dimension1_by_columns(std::uint32_t i) noexcept {
    std::uint32_t x = 0, v = 0x80000000u;
    for (; i != 0; i >>= 1, v ^= v >> 1)
        if (i & 1u) x ^= v;
    return x;
}

namespace detail {
/// \brief The generator is linear over GF(2): the XOR of the images of i's four bytes,
/// each from a 256-entry table (4 KiB, built at compile time). Shuffled indices have all
/// 32 bits in play, so the column loop would run 32 times per point.
struct dimension1_tables {
    std::uint32_t t[4][256] = {};
    constexpr dimension1_tables() {
        for (std::uint32_t b = 0; b < 4; ++b)
            for (std::uint32_t v = 0; v < 256; ++v) {
                t[b][v] = dimension1_by_columns(v << (8 * b));
            }
    }
};
inline constexpr dimension1_tables dimension1_table{};
}  // namespace detail

/// \brief Sobol' dimension 1 of point `i` as 32-bit fixed point.
constexpr std::uint32_t dimension1(std::uint32_t i) noexcept {
    const auto& t = detail::dimension1_table.t;
    return t[0][i & 0xffu] ^ t[1][(i >> 8) & 0xffu] ^ t[2][(i >> 16) & 0xffu] ^ t[3][i >> 24];
}

/// \brief How many Sobol' dimensions the table has (0 … dimensions − 1).
inline constexpr std::uint32_t dimensions = data::sobol_joe_kuo::rows.size() + 1;

namespace detail {
/// \brief The generator columns of every dimension, 32-bit fixed point (v[d][k] is the
/// image of index bit k), built at compile time by Joe & Kuo's recurrence:
/// v_k = m_k · 2^(32−k) for k ≤ s, then v_k = v_{k−s} ⊕ (v_{k−s} ≫ s) ⊕ ⨁_{j<s} a_j v_{k−j}.
struct generator_tables {
    std::uint32_t v[dimensions][32] = {};
    constexpr generator_tables() {
        for (std::uint32_t k = 0; k < 32; ++k) v[0][k] = 0x80000000u >> k;
        for (std::uint32_t d = 1; d < dimensions; ++d) {
            const auto& r = data::sobol_joe_kuo::rows[d - 1];
            const std::uint32_t s = r.s;
            for (std::uint32_t k = 0; k < 32; ++k) {  // k = index bit (Joe & Kuo's k + 1)
                if (k < s) {
                    v[d][k] = r.m[k] << (31 - k);
                    continue;
                }
                std::uint32_t x = v[d][k - s] ^ (v[d][k - s] >> s);
                for (std::uint32_t j = 1; j < s; ++j)
                    if ((r.a >> (s - 1 - j)) & 1u) x ^= v[d][k - j];
                v[d][k] = x;
            }
        }
    }
};
inline constexpr generator_tables generators{};
}  // namespace detail

/// \brief Sobol' dimension d (< `dimensions`) of point i, 32-bit fixed point: the XOR of
/// the columns of i's set bits (as many steps as i has bits).
constexpr std::uint32_t point(std::uint32_t i, std::uint32_t d) noexcept {
    const std::uint32_t* v = detail::generators.v[d];
    std::uint32_t x = 0;
    for (; i != 0; i &= i - 1) x ^= v[std::countr_zero(i)];
    return x;
}

/// \brief The partner of a dimension-d value x (= point(i, d)) that makes (x, paired(x)) a
/// (0, 2)-sequence in i: dimension 1 of the index whose dimension 0 is x.
constexpr std::uint32_t paired(std::uint32_t x) noexcept { return dimension1(reverse_bits(x)); }

/// \brief Laine–Karras hash: bit k of the result depends only on bits 0…k of x (and the
/// seed); a bijection for every seed.
constexpr std::uint32_t laine_karras(std::uint32_t x, std::uint32_t seed) noexcept {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/// \brief Owen scrambling of a fixed-point value in [0, 1): bit k (weight 2^(k−32)) is
/// flipped by a hash of the bits above it and the seed.
constexpr std::uint32_t owen_scramble(std::uint32_t v, std::uint32_t seed) noexcept {
    return reverse_bits(laine_karras(reverse_bits(v), seed));
}

/// \brief A shuffle of sample indices that maps every aligned block of 2^m indices onto an
/// aligned block of 2^m indices (bit k of i is flipped by a hash of the bits above it).
constexpr std::uint32_t shuffle_index(std::uint32_t i, std::uint32_t seed) noexcept {
    return owen_scramble(i, seed);  // the same nested scramble: bits above decide
}

/// \brief 64-bit variant of `shuffle_index` for Morton-ordered indices (ZSobol): a
/// bijection in which bit k of the result depends only on bits k…63 of i.
constexpr std::uint64_t shuffle_index64(std::uint64_t i, std::uint64_t seed) noexcept {
    const auto rev = [](std::uint64_t v) {
        return (static_cast<std::uint64_t>(reverse_bits(static_cast<std::uint32_t>(v))) << 32) |
               reverse_bits(static_cast<std::uint32_t>(v >> 32));
    };
    std::uint64_t x = rev(i);
    x += seed;  // bit k of each step depends on bits 0…k only
    x ^= x * 0x9e3779b97f4a7c16ull;  // even multipliers: x·c's bit k depends on bits < k
    x ^= x * 0xbf58476d1ce4e5bcull;
    x ^= x * 0x94d049bb133111eaull;
    x ^= x * 0xd6e8feb86659fd94ull;
    return rev(x);
}

/// \brief Interleave the low 16 bits of x and y: x in the even bits, y in the odd ones.
constexpr std::uint32_t morton2(std::uint32_t x, std::uint32_t y) noexcept {
    const auto spread = [](std::uint32_t v) {
        v &= 0xffffu;
        v = (v | (v << 8)) & 0x00ff00ffu;
        v = (v | (v << 4)) & 0x0f0f0f0fu;
        v = (v | (v << 2)) & 0x33333333u;
        v = (v | (v << 1)) & 0x55555555u;
        return v;
    };
    return spread(x) | (spread(y) << 1);
}

/// \brief A 32-bit fixed-point value in [0, 1) as a float in [0, 1) (24 bits, never 1).
constexpr float to_unit(std::uint32_t v) noexcept { return static_cast<float>(v >> 8) * 0x1.0p-24f; }

}  // namespace iris::sobol
