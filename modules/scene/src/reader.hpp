#pragma once
/// \file
/// \brief A checked view of one JSON value: typed getters that throw `iris::scene::error`
/// naming the file, the line and the JSON pointer of the value and what was expected.

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "iris/scene/error.hpp"
#include "json_locations.hpp"

namespace iris::scene::detail {

using json = nlohmann::ordered_json;

/// \brief The file being parsed: its name and where its values are.
struct source_context {
    std::string name;
    json_locations locations;

    [[noreturn]] void fail(const std::string& pointer, const std::string& message) const {
        throw error(name, locations.find(pointer), pointer, message);
    }
    /// \brief An error that is about `pointer` but reported at the line of `line_pointer`.
    [[noreturn]] void fail_at(const std::string& line_pointer, const std::string& pointer,
                              const std::string& message) const {
        throw error(name, locations.find(line_pointer), pointer, message);
    }
};

/// \brief `"a, b, c"`.
template <class Range>
std::string join(const Range& items) {
    std::string s;
    for (const auto& i : items) {
        if (!s.empty()) s += ", ";
        s += std::string(i);
    }
    return s;
}

/// \brief A short rendering of a value for messages (`got string "NaN"`).
inline std::string describe(const json& j) {
    std::string text = j.dump();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    const char* type = j.is_number() ? "number" : j.type_name();
    return std::string(type) + " " + text;
}

class reader {
public:
    reader(const json& value, std::string pointer, const source_context& ctx)
        : m_json(&value), m_pointer(std::move(pointer)), m_ctx(&ctx) {}

    const json& value() const noexcept { return *m_json; }
    const std::string& pointer() const noexcept { return m_pointer; }
    const source_context& context() const noexcept { return *m_ctx; }

    [[noreturn]] void fail(const std::string& message) const { m_ctx->fail(m_pointer, message); }

    bool is_object() const noexcept { return m_json->is_object(); }
    bool is_array() const noexcept { return m_json->is_array(); }
    bool is_string() const noexcept { return m_json->is_string(); }
    bool is_number() const noexcept { return m_json->is_number(); }

    /// \brief This value must be an object whose keys are all in `allowed`.
    void expect_object(std::initializer_list<std::string_view> allowed, std::string_view what = "an object") const {
        if (!m_json->is_object()) fail("expected " + std::string(what) + ", got " + describe(*m_json));
        for (const auto& [key, v] : m_json->items()) {
            bool ok = false;
            for (const auto a : allowed) ok = ok || a == key;
            if (!ok)
                m_ctx->fail_at(child_pointer(key), m_pointer,
                               "unknown key '" + key + "'; expected one of " + join(allowed));
        }
    }

    bool has(std::string_view key) const { return m_json->is_object() && m_json->contains(key); }

    reader at(std::string_view key) const {
        if (!has(key)) fail("missing key '" + std::string(key) + "'");
        return {m_json->at(std::string(key)), child_pointer(key), *m_ctx};
    }
    reader at(std::size_t index) const {
        return {m_json->at(index), m_pointer + "/" + std::to_string(index), *m_ctx};
    }
    std::size_t size() const noexcept { return m_json->size(); }

    std::string child_pointer(std::string_view key) const { return m_pointer + "/" + escape_pointer_token(key); }

    std::string string() const {
        if (!m_json->is_string()) fail("expected a string, got " + describe(*m_json));
        return m_json->get<std::string>();
    }

    bool boolean() const {
        if (!m_json->is_boolean()) fail("expected true or false, got " + describe(*m_json));
        return m_json->get<bool>();
    }

    /// \brief A finite number (JSON has no NaN; strings such as "NaN" and overflowing
    /// literals are what this rejects).
    double number() const {
        if (!m_json->is_number()) fail("expected a number, got " + describe(*m_json));
        const double v = m_json->get<double>();
        if (!std::isfinite(v)) fail("expected a finite number, got " + describe(*m_json));
        return v;
    }

    /// \brief A number in [lo, hi] (`open_lo`/`open_hi` exclude the ends); `what`
    /// describes it ("a field of view in degrees").
    double number_in(double lo, double hi, bool open_lo, bool open_hi, std::string_view what) const {
        const double v = number();
        const bool lo_ok = open_lo ? v > lo : v >= lo;
        const bool hi_ok = open_hi ? v < hi : v <= hi;
        if (!lo_ok || !hi_ok) fail("expected " + std::string(what) + " " + interval(lo, hi, open_lo, open_hi) + ", got " + shortest(v));
        return v;
    }

    /// \brief An integer in [lo, hi].
    long long integer_in(long long lo, long long hi, std::string_view what) const {
        if (!m_json->is_number_integer()) fail("expected " + std::string(what) + " (an integer), got " + describe(*m_json));
        const bool is_unsigned = m_json->is_number_unsigned();
        if (is_unsigned && m_json->get<unsigned long long>() > static_cast<unsigned long long>(hi))
            fail("expected " + std::string(what) + " in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + m_json->dump());
        const long long v = is_unsigned ? static_cast<long long>(m_json->get<unsigned long long>()) : m_json->get<long long>();
        if (v < lo || v > hi)
            fail("expected " + std::string(what) + " in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(v));
        return v;
    }

    /// \brief An array of exactly `n` elements (its elements are read by the caller).
    void expect_array(std::size_t n, std::string_view what) const {
        if (!m_json->is_array() || m_json->size() != n)
            fail("expected " + std::string(what) + " (an array of " + std::to_string(n) + " numbers), got " + describe(*m_json));
    }

    static std::string shortest(double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.9g", v);
        return buf;
    }
    static std::string interval(double lo, double hi, bool open_lo, bool open_hi) {
        const std::string l = lo == -std::numeric_limits<double>::infinity() ? "-inf" : shortest(lo);
        const std::string h = hi == std::numeric_limits<double>::infinity() ? "inf" : shortest(hi);
        return (open_lo ? "in (" : "in [") + l + ", " + h + (open_hi ? ")" : "]");
    }

private:
    const json* m_json;
    std::string m_pointer;
    const source_context* m_ctx;
};

}  // namespace iris::scene::detail
