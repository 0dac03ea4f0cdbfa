#pragma once
/// \file
/// \brief `iris::scene::error`: what is wrong with a scene, and where.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace iris::scene {

/// \brief Bad scene input. `what()` reads `FILE:LINE: POINTER: MESSAGE`, e.g.
/// `falling.json:12: materials/glass/ior: unknown glass 'BK-7'; expected one of N-BK7, …`
/// (the line is left out when unknown, the pointer when the error is about the whole file).
class error : public std::runtime_error {
public:
    /// \param file    the scene's name as the user gave it (path or `builtin:NAME`)
    /// \param line    1-based line of the offending value, 0 if unknown
    /// \param pointer JSON pointer of the offending value (RFC 6901, e.g. `/camera/fov`), or ""
    error(std::string file, std::size_t line, std::string pointer, std::string message)
        : std::runtime_error(format(file, line, pointer, message)),
          m_file(std::move(file)),
          m_line(line),
          m_pointer(std::move(pointer)),
          m_message(std::move(message)) {}

    /// \brief A column within the line (1-based), for formats read token by token (pbrt-v4):
    /// `what()` reads `FILE:LINE:COLUMN: MESSAGE`.
    struct column {
        std::size_t value = 0;
    };
    error(std::string file, std::size_t line, column col, std::string message)
        : std::runtime_error(format(file + ":" + std::to_string(line) + ":" + std::to_string(col.value), 0, "", message)),
          m_file(std::move(file)),
          m_line(line),
          m_column(col.value),
          m_message(std::move(message)) {}

    const std::string& file() const noexcept { return m_file; }
    /// \brief The column (1-based), 0 if unknown.
    std::size_t column_number() const noexcept { return m_column; }
    std::size_t line() const noexcept { return m_line; }
    const std::string& pointer() const noexcept { return m_pointer; }
    /// \brief The message alone, without file, line and pointer.
    const std::string& message() const noexcept { return m_message; }

private:
    static std::string format(const std::string& file, std::size_t line, const std::string& pointer,
                              const std::string& message) {
        // appended piece by piece (GCC 12 misreports -Wrestrict on chained temporaries)
        std::string s;
        s.append(file.empty() ? std::string_view("<scene>") : std::string_view(file));
        if (line > 0) {
            s.push_back(':');
            s.append(std::to_string(line));
        }
        s.append(": ");
        // shown without the leading '/', which reads better in a message
        if (!pointer.empty()) {
            s.append(std::string_view(pointer).substr(pointer.front() == '/' ? 1 : 0));
            s.append(": ");
        }
        s.append(message);
        return s;
    }

    std::string m_file;
    std::size_t m_line;
    std::size_t m_column = 0;
    std::string m_pointer;
    std::string m_message;
};

}  // namespace iris::scene
