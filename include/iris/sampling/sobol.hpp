#pragma once
/// \file
/// \brief Scrambled Sobol' points for the renderer's low-discrepancy samplers (std only).
///
/// **The sequence.** Only the first two Sobol' dimensions are used: dimension 0 is the van der
/// Corput sequence (the index's bits reversed) and dimension 1 the one whose generator is
/// the Pascal matrix mod 2 (Joe & Kuo's first row: s = 1, a = 0, m₁ = 1; Sobol' 1967). Together
/// they are a (0, 2)-sequence: every aligned block of 2^m consecutive points puts exactly one
/// point in each elementary interval of area 2^-m. Higher Sobol' dimensions are not a
/// (0, 2)-sequence in pairs, so every 2-D point a path asks for is this pair, *padded*: each
/// dimension of the path gets its own index shuffle and its own scrambling (Burley 2020,
/// §4–5; pbrt-v4's PaddedSobol and ZSobol samplers do the same). This is why no table of
/// direction numbers is needed: dimension 1's columns follow from v₁ = 2³¹, v_k = v_{k−1} ⊕ (v_{k−1} ≫ 1).
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
/// a pixel's first 2^m samples stay a (0, m, 2)-net whatever the shuffle, and two
/// dimensions with different shuffles are decorrelated.

#include <cstdint>

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
    std::uint32_t reversed[4][256] = {};  ///< the same, bit-reversed (reversal is linear too)
    constexpr dimension1_tables() {
        for (std::uint32_t b = 0; b < 4; ++b)
            for (std::uint32_t v = 0; v < 256; ++v) {
                t[b][v] = dimension1_by_columns(v << (8 * b));
                reversed[b][v] = reverse_bits(t[b][v]);
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

/// \brief `owen_scramble(dimension1(i), c)` without the reversal that cancels:
/// reverse(LK_c(reverse(dimension1(i)))), the inner reversal read from the reversed tables.
constexpr std::uint32_t scrambled_dimension1(std::uint32_t i, std::uint32_t c) noexcept {
    const auto& t = detail::dimension1_table.reversed;
    return reverse_bits(laine_karras(t[0][i & 0xffu] ^ t[1][(i >> 8) & 0xffu] ^ t[2][(i >> 16) & 0xffu] ^ t[3][i >> 24], c));
}

/// \brief `owen_scramble(dimension0(shuffle_index(i, a)), b)` with the bit reversals that
/// cancel left out, from r = reverse_bits(i): the shuffled index is reverse(LK_a(r)), its
/// dimension 0 is LK_a(r), and the scramble of that is reverse(LK_b(reverse(LK_a(r)))).
/// Also returns the shuffled index (for dimension 1).
struct scrambled_point0 {
    std::uint32_t value, index;
};
constexpr scrambled_point0 shuffled_dimension0(std::uint32_t reversed_index, std::uint32_t a, std::uint32_t b) noexcept {
    const std::uint32_t index = reverse_bits(laine_karras(reversed_index, a));
    return {reverse_bits(laine_karras(index, b)), index};
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
