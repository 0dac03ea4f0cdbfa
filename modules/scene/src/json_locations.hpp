#pragma once
/// \file
/// \brief Where each value of a JSON text starts (1-based line), by JSON pointer.
///
/// nlohmann::json 3.11 reports byte offsets for syntax errors only; semantic errors
/// (a negative size, an unknown glass) are found later on the parsed tree, which has
/// no positions. This second pass over the *already validated* text recovers them: one
/// linear scan that records the line of every value (for object members: the line of
/// the key) and every duplicated key. It accepts what nlohmann accepts with comments
/// enabled (`//`, `/* */`); on anything else it stops quietly with what it has.

#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace iris::scene::detail {

/// \brief RFC 6901 escaping of one reference token (`~` → `~0`, `/` → `~1`).
std::string escape_pointer_token(std::string_view key);

struct json_locations {
    std::unordered_map<std::string, std::size_t> line_of;  ///< pointer → line
    struct duplicate {
        std::string pointer;  ///< the repeated member
        std::size_t line;     ///< of its second occurrence
    };
    std::vector<duplicate> duplicates;

    /// \brief The line of `pointer`, or of its nearest ancestor that was recorded; 0 if none.
    std::size_t find(std::string pointer) const;
};

json_locations locate_json_values(std::string_view text);

/// \brief 1-based line and column of byte offset `offset` (clamped to the text).
struct text_position {
    std::size_t line = 1, column = 1;
};
text_position position_of(std::string_view text, std::size_t offset) noexcept;

}  // namespace iris::scene::detail
