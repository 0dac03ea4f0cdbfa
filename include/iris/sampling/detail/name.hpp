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

/// \brief A string usable as a template argument (a preset's CLI name, a name prefix).
template <std::size_t N>
struct fixed_string {
    char data[N]{};
    constexpr fixed_string(const char (&s)[N]) noexcept {
        for (std::size_t i = 0; i < N; ++i) data[i] = s[i];
    }
    constexpr std::string_view view() const noexcept { return {data, N - 1}; }
};

/// \brief `Prefix` followed by the decimal `N`: `numbered_name<"multibox", 3>` is "multibox3".
template <fixed_string Prefix, std::size_t N>
constexpr name_buffer numbered_name() noexcept {
    name_buffer b;
    return b.append(Prefix.view()).append_number(N);
}
template <fixed_string Prefix, std::size_t N>
inline constexpr name_buffer numbered_name_v = numbered_name<Prefix, N>();

}  // namespace iris::detail
