#pragma once
/// \file
/// \brief `counter_rng`: deterministic random numbers that are a pure function of
/// (seed, pixel, sample, dimension), for tests, tools and renderers alike. No state is
/// shared, so neither thread count nor evaluation order changes any number.
///
/// The mixer is the SplitMix64 finaliser (Steele, Lea and Flood 2014): bijective on 64
/// bits with full avalanche, which is all a counter-based generator needs.

#include <cstdint>

namespace iris {

namespace detail {
/// \brief SplitMix64 finaliser (with the golden-ratio increment folded in).
constexpr std::uint64_t counter_hash(std::uint64_t z) noexcept {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}
}  // namespace detail

/// \brief A counter-based random stream keyed by (seed, pixel, sample). `at(d)` is the
/// number of dimension d, a pure function; `next()` walks the dimensions 0, 1, 2, …
class counter_rng {
public:
    constexpr explicit counter_rng(std::uint64_t seed, std::uint64_t pixel = 0, std::uint64_t sample = 0) noexcept
        : m_key(detail::counter_hash(detail::counter_hash(detail::counter_hash(seed) ^ pixel) ^
                                     (sample * 0xd1b54a32d192ed03ull))) {}

    /// \brief 64 random bits of dimension `d`.
    constexpr std::uint64_t bits(std::uint64_t d) const noexcept { return detail::counter_hash(m_key + d); }
    /// \brief A float in [0, 1) from 24 random bits (never exactly 1).
    constexpr float at(std::uint64_t d) const noexcept { return static_cast<float>(bits(d) >> 40) * 0x1.0p-24f; }
    /// \brief A double in [0, 1) from 53 random bits.
    constexpr double at_double(std::uint64_t d) const noexcept {
        return static_cast<double>(bits(d) >> 11) * 0x1.0p-53;
    }

    constexpr float next() noexcept { return at(m_dimension++); }
    constexpr double next_double() noexcept { return at_double(m_dimension++); }
    constexpr std::uint64_t next_bits() noexcept { return bits(m_dimension++); }
    constexpr std::uint64_t dimension() const noexcept { return m_dimension; }

private:
    std::uint64_t m_key;
    std::uint64_t m_dimension = 0;
};

}  // namespace iris
