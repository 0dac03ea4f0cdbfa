#pragma once
/// \file
/// \brief Counter-based random numbers: a pure function of (seed, pixel, sample,
/// dimension), so no pixel depends on tiling, thread count or evaluation order.

#include <cstdint>

#include <glm/vec2.hpp>

namespace iris {

namespace detail {
/// \brief SplitMix64 finaliser: a bijective 64-bit mix with full avalanche.
constexpr std::uint64_t mix64(std::uint64_t z) noexcept {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}
}  // namespace detail

/// \brief The random stream of one (pixel, sample) pair. `next()` walks the dimensions.
class sample_stream {
public:
    constexpr sample_stream(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample) noexcept
        : m_key(detail::mix64(detail::mix64(detail::mix64(seed) ^ pixel) ^ (sample * 0xd1b54a32d192ed03ull))) {}

    /// \brief A uniform float in [0, 1) (24 random bits, so never exactly 1).
    constexpr float next() noexcept {
        const std::uint64_t bits = detail::mix64(m_key + m_dimension++);
        return static_cast<float>(bits >> 40) * 0x1.0p-24f;
    }
    constexpr glm::vec2 next2() noexcept {
        const float a = next();
        return {a, next()};
    }
    constexpr std::uint32_t dimension() const noexcept { return m_dimension; }

private:
    std::uint64_t m_key;
    std::uint32_t m_dimension = 0;
};

}  // namespace iris
