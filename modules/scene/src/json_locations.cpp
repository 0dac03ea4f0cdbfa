#include "json_locations.hpp"

#include <cstdint>
#include <unordered_set>

namespace iris::scene::detail {

std::string escape_pointer_token(std::string_view key) {
    std::string s;
    s.reserve(key.size());
    for (const char c : key) {
        if (c == '~') s += "~0";
        else if (c == '/') s += "~1";
        else s += c;
    }
    return s;
}

std::size_t json_locations::find(std::string pointer) const {
    for (;;) {
        if (const auto it = line_of.find(pointer); it != line_of.end()) return it->second;
        if (pointer.empty()) return 0;
        pointer.resize(pointer.rfind('/'));
    }
}

text_position position_of(std::string_view text, std::size_t offset) noexcept {
    text_position p;
    const std::size_t end = offset < text.size() ? offset : text.size();
    for (std::size_t i = 0; i < end; ++i) {
        if (text[i] == '\n') {
            ++p.line;
            p.column = 1;
        } else {
            ++p.column;
        }
    }
    return p;
}

namespace {

void append_utf8(std::string& s, std::uint32_t cp) {
    if (cp < 0x80) {
        s += static_cast<char>(cp);
    } else if (cp < 0x800) {
        s += static_cast<char>(0xC0 | (cp >> 6));
        s += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
        s += static_cast<char>(0xE0 | (cp >> 12));
        s += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        s += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
        s += static_cast<char>(0xF0 | (cp >> 18));
        s += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
        s += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        s += static_cast<char>(0x80 | (cp & 0x3F));
    }
}

/// Recursive descent over valid JSON; `ok` turns false (and everything unwinds) on
/// input it does not understand, which cannot happen after nlohmann accepted the text.
class scanner {
public:
    explicit scanner(std::string_view text) : m_text(text) {}

    json_locations run() {
        if (m_text.starts_with("\xEF\xBB\xBF")) m_pos = 3;  // a UTF-8 byte order mark, as nlohmann skips it
        skip_space();
        value("", 0);
        return std::move(m_out);
    }

private:
    static constexpr int max_depth = 512;  // nlohmann's own recursion limit is far lower in practice

    bool at_end() const noexcept { return m_pos >= m_text.size(); }
    char peek() const noexcept { return at_end() ? '\0' : m_text[m_pos]; }
    void advance() noexcept {
        if (at_end()) return;
        if (m_text[m_pos] == '\n') ++m_line;
        ++m_pos;
    }

    void skip_space() noexcept {
        while (m_ok && !at_end()) {
            const char c = peek();
            if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
                advance();
            } else if (c == '/' && m_pos + 1 < m_text.size() && m_text[m_pos + 1] == '/') {
                while (!at_end() && peek() != '\n') advance();
            } else if (c == '/' && m_pos + 1 < m_text.size() && m_text[m_pos + 1] == '*') {
                advance();
                advance();
                while (!at_end() && !(peek() == '*' && m_pos + 1 < m_text.size() && m_text[m_pos + 1] == '/')) advance();
                advance();
                advance();
            } else {
                return;
            }
        }
    }

    unsigned hex4() noexcept {
        unsigned v = 0;
        for (int i = 0; i < 4; ++i) {
            const char c = peek();
            unsigned d;
            if (c >= '0' && c <= '9') d = static_cast<unsigned>(c - '0');
            else if (c >= 'a' && c <= 'f') d = static_cast<unsigned>(c - 'a' + 10);
            else if (c >= 'A' && c <= 'F') d = static_cast<unsigned>(c - 'A' + 10);
            else {
                m_ok = false;
                return 0;
            }
            v = v * 16 + d;
            advance();
        }
        return v;
    }

    /// A string literal (at its opening quote), decoded the way nlohmann decodes keys.
    std::string string() {
        std::string s;
        advance();  // opening quote
        while (m_ok && !at_end()) {
            const char c = peek();
            if (c == '"') {
                advance();
                return s;
            }
            if (c != '\\') {
                s += c;
                advance();
                continue;
            }
            advance();
            const char e = peek();
            advance();
            switch (e) {
                case '"': s += '"'; break;
                case '\\': s += '\\'; break;
                case '/': s += '/'; break;
                case 'b': s += '\b'; break;
                case 'f': s += '\f'; break;
                case 'n': s += '\n'; break;
                case 'r': s += '\r'; break;
                case 't': s += '\t'; break;
                case 'u': {
                    std::uint32_t cp = hex4();
                    if (cp >= 0xD800 && cp <= 0xDBFF && peek() == '\\') {
                        advance();
                        advance();  // 'u'
                        const std::uint32_t lo = hex4();
                        cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
                    }
                    append_utf8(s, cp);
                    break;
                }
                default: m_ok = false;
            }
        }
        m_ok = false;
        return s;
    }

    void value(const std::string& pointer, int depth) {
        if (!m_ok || at_end() || depth > max_depth) {
            m_ok = false;
            return;
        }
        m_out.line_of.emplace(pointer, m_line);
        const char c = peek();
        if (c == '{') {
            advance();
            std::unordered_set<std::string> seen;
            skip_space();
            if (peek() == '}') {
                advance();
                return;
            }
            while (m_ok) {
                skip_space();
                if (peek() != '"') {
                    m_ok = false;
                    return;
                }
                const std::size_t key_line = m_line;
                const std::string key = string();
                const std::string child = pointer + "/" + escape_pointer_token(key);
                if (!seen.insert(key).second) m_out.duplicates.push_back({child, key_line});
                skip_space();
                if (peek() != ':') {
                    m_ok = false;
                    return;
                }
                advance();
                skip_space();
                // the member's line is its key's line (where a reader looks for it);
                // a duplicate keeps the first occurrence's line
                const bool first = !m_out.line_of.contains(child);
                value(child, depth + 1);
                if (first) m_out.line_of[child] = key_line;
                skip_space();
                if (peek() == ',') {
                    advance();
                } else if (peek() == '}') {
                    advance();
                    return;
                } else {
                    m_ok = false;
                }
            }
        } else if (c == '[') {
            advance();
            skip_space();
            if (peek() == ']') {
                advance();
                return;
            }
            for (std::size_t i = 0; m_ok; ++i) {
                skip_space();
                value(pointer + "/" + std::to_string(i), depth + 1);
                skip_space();
                if (peek() == ',') {
                    advance();
                } else if (peek() == ']') {
                    advance();
                    return;
                } else {
                    m_ok = false;
                }
            }
        } else if (c == '"') {
            string();
        } else {
            // number or literal: up to the next delimiter
            while (!at_end()) {
                const char d = peek();
                if (d == ',' || d == '}' || d == ']' || d == ' ' || d == '\t' || d == '\r' || d == '\n' || d == '/')
                    break;
                advance();
            }
        }
    }

    std::string_view m_text;
    std::size_t m_pos = 0;
    std::size_t m_line = 1;
    bool m_ok = true;
    json_locations m_out;
};

}  // namespace

json_locations locate_json_values(std::string_view text) { return scanner(text).run(); }

}  // namespace iris::scene::detail
