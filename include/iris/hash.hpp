#pragma once
/// \file
/// \brief `fnv1a`: the 64-bit FNV-1a hash, iris's one stable content hash (std::hash may
/// differ between builds): the scene fingerprint, the checkpoint checksum and
/// iris-ablate's cache keys use it.

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace iris {

class fnv1a {
public:
    /// \brief Hash n more bytes.
    constexpr void add(const void* data, std::size_t n) noexcept {
        const auto* b = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < n; ++i) m_h = (m_h ^ b[i]) * 0x100000001b3ull;
    }
    void add(std::string_view s) noexcept { add(s.data(), s.size()); }
    constexpr std::uint64_t value() const noexcept { return m_h; }

private:
    std::uint64_t m_h = 0xcbf29ce484222325ull;
};

/// \brief FNV-1a of n bytes.
inline std::uint64_t fnv1a_of(const void* data, std::size_t n) noexcept {
    fnv1a h;
    h.add(data, n);
    return h.value();
}

}  // namespace iris
