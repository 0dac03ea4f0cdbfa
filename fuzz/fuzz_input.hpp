#pragma once
/// \file
/// \brief The byte decoder every fuzz target shares: turns libFuzzer's bytes into typed
/// values, deterministically, without ever reading past the end (missing bytes are 0).

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

namespace iris::fuzz {

class input {
public:
    input(const std::uint8_t* data, std::size_t size) noexcept : m_data(data), m_size(size) {}

    std::size_t remaining() const noexcept { return m_size - m_pos; }

    /// \brief The next sizeof(T) bytes as a T (zero-padded at the end of the input).
    template <class T>
        requires std::is_trivially_copyable_v<T>
    T raw() noexcept {
        unsigned char bytes[sizeof(T)] = {};
        const std::size_t n = remaining() < sizeof(T) ? remaining() : sizeof(T);
        if (n > 0) std::memcpy(bytes, m_data + m_pos, n);
        m_pos += n;
        T v;
        std::memcpy(&v, bytes, sizeof(T));
        return v;
    }

    /// \brief Any double, including NaN, ±Inf, denormals: the point is to hit them.
    double any_double() noexcept { return raw<double>(); }

    /// \brief A double in [lo, hi] from 32 bits (uniform-ish), for values that must be sane.
    double in_range(double lo, double hi) noexcept {
        const auto u = raw<std::uint32_t>();
        return lo + (hi - lo) * (static_cast<double>(u) / static_cast<double>(std::numeric_limits<std::uint32_t>::max()));
    }

    /// \brief An integer in [lo, hi].
    std::size_t count(std::size_t lo, std::size_t hi) noexcept {
        return lo + static_cast<std::size_t>(raw<std::uint16_t>()) % (hi - lo + 1);
    }

    bool flag() noexcept { return (raw<std::uint8_t>() & 1u) != 0; }

private:
    const std::uint8_t* m_data;
    std::size_t m_size;
    std::size_t m_pos = 0;
};

/// \brief Stop the fuzzer (and fail the replay) with a message: a property was violated.
[[noreturn]] void fail(const char* what);

}  // namespace iris::fuzz

#include <cstdio>
#include <cstdlib>

inline void iris::fuzz::fail(const char* what) {
    std::fprintf(stderr, "fuzz property violated: %s\n", what);
    std::abort();
}
