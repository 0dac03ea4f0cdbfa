#pragma once
/// \file
/// \brief Compile-time names (`multibox3`, `multibox3/linear/C4/propagate`): a small fixed
/// buffer filled by constexpr code, viewed as a `std::string_view` with static storage.

#include <cstddef>
#include <string_view>

namespace iris::detail {

/// \brief Up to 95 characters built at compile time.
struct name_buffer {
    static constexpr std::size_t capacity = 95;
    char data[capacity + 1]{};
    std::size_t size = 0;

    constexpr name_buffer& append(std::string_view s) noexcept {
        for (char c : s)
            if (size < capacity) data[size++] = c;
        return *this;
    }
    constexpr name_buffer& append_number(std::size_t n) noexcept {
        char digits[24]{};
        std::size_t k = 0;
        do {
            digits[k++] = static_cast<char>('0' + n % 10);
            n /= 10;
        } while (n != 0);
        while (k > 0 && size < capacity) data[size++] = digits[--k];
        return *this;
    }
    constexpr std::string_view view() const noexcept { return {data, size}; }
};

}  // namespace iris::detail
