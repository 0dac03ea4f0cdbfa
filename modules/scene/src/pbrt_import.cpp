// pbrt-v4 text → scene_document (docs/pbrt-import.md): the tokenizer, the graphics state and
// the directives, parameters and types iris can render; everything else is an error at its
// FILE:LINE:COLUMN, or, where an approximation is reasonable, a note the tools print as a
// warning (an error with `strict`). CGAL-free, like the JSON half: the fuzzer links it.
//
// Conventions (docs/pbrt-import.md, "Conventions"): a light's spectrum S and `scale` become
// iris's radiance scale·S/Y(S), Y the luminance (pbrt-v4 normalises by the photometric
// integral and its film does not divide by ∫ȳ; iris's does), an "rgb" light scale·E_rgb (the
// RGB illuminant spectrum, D65 white); an "rgb" reflectance is upsampled by Jakob–Hanika
// (as pbrt-v4 does). pbrt-v4's world is mirrored into iris's right-handed one when its camera
// frame is left-handed (pbrt-v4's plain LookAt), so that the image is the same.
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include "iris/gzip.hpp"
#include "iris/scene/document.hpp"
#include "iris/spectrum/blackbody.hpp"
#include "iris/spectrum/color.hpp"
#include "iris/spectrum/named.hpp"
#include "iris/spectrum/rgb_sigmoid.hpp"
#include "spectra.hpp"

namespace iris::scene {
namespace {

constexpr int max_include_depth = 32;
constexpr std::size_t max_included_files = 10000;
constexpr std::size_t max_included_bytes = std::size_t{4} << 30;
constexpr std::size_t max_triangles = std::size_t{1} << 28;  ///< what a scene may hold (about 270 M)
constexpr double max_coordinate = 1e7;
constexpr int max_texture_depth = 64;  ///< textures of textures, at most this deep

// ---- tokens ---------------------------------------------------------------------------

struct location {
    std::string file;
    std::size_t line = 0, column = 0;
};

[[noreturn]] void fail(const location& at, const std::string& message) {
    throw error(at.file, at.line, error::column{at.column}, message);
}

struct token {
    enum class kind { word, string, number, open, close } type = kind::word;
    std::string text;
    double number = 0.0;
    location at;
};

/// One file's text, read token by token.
class tokenizer {
public:
    tokenizer(std::string text, std::string file, std::filesystem::path dir)
        : m_text(std::move(text)), m_file(std::move(file)), m_dir(std::move(dir)) {}

    const std::filesystem::path& dir() const noexcept { return m_dir; }
    const std::string& file() const noexcept { return m_file; }

    std::optional<token> next() {
        skip_space();
        if (m_pos >= m_text.size()) return std::nullopt;
        token t;
        t.at = here();
        const char c = m_text[m_pos];
        if (c == '[' || c == ']') {
            t.type = c == '[' ? token::kind::open : token::kind::close;
            t.text = std::string(1, c);
            advance();
            return t;
        }
        if (c == '"') {
            t.type = token::kind::string;
            advance();
            for (;;) {
                if (m_pos >= m_text.size()) fail(t.at, "unterminated string (a '\"' is missing)");
                const char d = m_text[m_pos];
                if (d == '\n') fail(t.at, "unterminated string (a string cannot span lines)");
                advance();
                if (d == '"') break;
                if (d == '\\') {
                    if (m_pos >= m_text.size()) fail(t.at, "unterminated string (a '\"' is missing)");
                    const char e = m_text[m_pos];
                    advance();
                    switch (e) {
                        case 'n': t.text += '\n'; break;
                        case 't': t.text += '\t'; break;
                        case '\\': t.text += '\\'; break;
                        case '"': t.text += '"'; break;
                        default: fail(here(), std::string("unknown escape '\\") + e + "' in a string");
                    }
                } else {
                    t.text += d;
                }
            }
            return t;
        }
        while (m_pos < m_text.size() && !is_space(m_text[m_pos]) && m_text[m_pos] != '"' && m_text[m_pos] != '[' &&
               m_text[m_pos] != ']' && m_text[m_pos] != '#') {
            t.text += m_text[m_pos];
            advance();
        }
        const char f = t.text.front();
        if (std::isdigit(static_cast<unsigned char>(f)) || f == '-' || f == '+' || f == '.') {
            t.type = token::kind::number;
            const char* b = t.text.data() + (f == '+' ? 1 : 0);
            const char* e = t.text.data() + t.text.size();
            const auto r = std::from_chars(b, e, t.number);
            if (r.ec != std::errc() || r.ptr != e) fail(t.at, "'" + t.text + "' is not a number");
            if (!std::isfinite(t.number)) fail(t.at, "'" + t.text + "' is not a finite number");
        }
        return t;
    }

private:
    static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
    location here() const { return {m_file, m_line, m_column}; }
    void advance() {
        if (m_text[m_pos] == '\n') {
            ++m_line;
            m_column = 1;
        } else {
            ++m_column;
        }
        ++m_pos;
    }
    void skip_space() {
        while (m_pos < m_text.size()) {
            if (is_space(m_text[m_pos])) advance();
            else if (m_text[m_pos] == '#')
                while (m_pos < m_text.size() && m_text[m_pos] != '\n') advance();
            else break;
        }
    }

    std::string m_text, m_file;
    std::filesystem::path m_dir;
    std::size_t m_pos = 0, m_line = 1, m_column = 1;
};

std::string read_file(const std::filesystem::path& p, const location& at, const std::string& what, bool allowed) {
    if (!allowed) fail(at, what + " '" + p.string() + "' not read: reading files is disabled");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec)) fail(at, what + " '" + p.string() + "' does not exist or is not a file");
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    if (!in && !in.eof()) fail(at, "cannot read " + what + " '" + p.string() + "'");
    return s.str();
}

// ---- parameters -----------------------------------------------------------------------

/// One `"type name" value(s)` of a directive.
struct parameter {
    std::string type, name;
    std::vector<double> numbers;
    std::vector<std::string> strings;
    std::vector<bool> bools;
    location at;
    bool used = false;
};

/// A directive's parameters: every getter marks what it reads; `finish` refuses the rest.
class parameters {
public:
    std::vector<parameter> list;
    std::string directive;  ///< e.g. `Shape "sphere"`, for messages

    parameter* find(std::string_view name) {
        for (auto& p : list)
            if (p.name == name) {
                p.used = true;
                return &p;
            }
        return nullptr;
    }
    const parameter& expect(parameter& p, std::initializer_list<std::string_view> types, std::size_t count) const {
        if (std::find(types.begin(), types.end(), p.type) == types.end()) {
            std::string expected;
            for (auto t : types) expected += (expected.empty() ? "\"" : ", \"") + std::string(t) + " " + p.name + "\"";
            fail(p.at, "parameter \"" + p.type + " " + p.name + "\" of " + directive + " has the wrong type; expected " + expected);
        }
        const std::size_t n = p.type == "string" || p.type == "texture" ? p.strings.size()
                              : p.type == "bool"                       ? p.bools.size()
                                                                       : p.numbers.size();
        if (count > 0 && n != count)
            fail(p.at, "parameter \"" + p.type + " " + p.name + "\" of " + directive + " takes " + std::to_string(count) +
                           " value" + (count > 1 ? "s" : "") + ", got " + std::to_string(n));
        return p;
    }
    double number(std::string_view name, double fallback, std::string_view type = "float") {
        parameter* p = find(name);
        if (!p) return fallback;
        return expect(*p, {type}, 1).numbers[0];
    }
    int integer(std::string_view name, int fallback) {
        parameter* p = find(name);
        if (!p) return fallback;
        const double v = expect(*p, {"integer"}, 1).numbers[0];
        if (v != std::floor(v) || std::fabs(v) > 1e9) fail(p->at, "\"integer " + p->name + "\" must be an integer");
        return static_cast<int>(v);
    }
    std::string string(std::string_view name, const std::string& fallback) {
        parameter* p = find(name);
        if (!p) return fallback;
        return expect(*p, {"string"}, 1).strings[0];
    }
    bool boolean(std::string_view name, bool fallback) {
        parameter* p = find(name);
        if (!p) return fallback;
        return expect(*p, {"bool"}, 1).bools[0];
    }
    glm::dvec3 point(std::string_view name, glm::dvec3 fallback) {
        parameter* p = find(name);
        if (!p) return fallback;
        const auto& v = expect(*p, {"point3", "point", "vector3", "vector", "normal", "normal3"}, 3).numbers;
        return {v[0], v[1], v[2]};
    }
    /// Refuse every parameter nothing read.
    void finish() const {
        for (const auto& p : list)
            if (!p.used)
                fail(p.at, "parameter \"" + p.type + " " + p.name + "\" of " + directive +
                               " is not supported by iris's pbrt-v4 importer (docs/pbrt-import.md)");
    }
};

// ---- spectra --------------------------------------------------------------------------

enum class spectrum_use { albedo, unbounded, illuminant };

/// A spectrum as a table over 360–830 nm at 1 nm (the CMF table's grid).
template <class F>
tabulated_spectrum tabulate(F&& f, outside mode = outside::zero) {
    std::vector<double> l, v;
    for (std::size_t i = 0; i < cie::cmf_samples; ++i) {
        l.push_back(cie::cmf_lambda_min + static_cast<double>(i));
        v.push_back(f(l.back()));
    }
    return {std::move(l), std::move(v), mode};
}

/// pbrt-v4's glass, metal and illuminant names, as iris's own data (docs/pbrt-import.md).
struct named_pbrt {
    std::string_view pbrt, iris;
};
constexpr std::array<named_pbrt, 7> pbrt_glasses{{{"glass-BK7", "N-BK7"},
                                                  {"glass-BAF10", "N-BAF10"},
                                                  {"glass-FK51A", "N-FK51A"},
                                                  {"glass-LASF9", "N-LASF9"},
                                                  {"glass-F5", "SF5"},
                                                  {"glass-F10", "SF10"},
                                                  {"glass-F11", "SF11"}}};
constexpr std::array<named_pbrt, 2> pbrt_illuminants{{{"stdillum-D65", "D65"}, {"stdillum-A", "A"}}};

struct spectrum_value {
    std::string name;  ///< what the tools report ("rgb", "blackbody:3000", a named spectrum, "tabulated")
    tabulated_spectrum table;
    bool rgb_illuminant = false;  ///< an "rgb" light: its luminance is not divided out (pbrt-v4's rule)
    std::optional<sellmeier_ior> glass;  ///< a named glass: iris's Sellmeier model of it
    std::optional<double> constant;      ///< a "float" value
};

// ---- the parser -----------------------------------------------------------------------

struct graphics_state {
    glm::dmat4 ctm{1.0};  ///< at the shutter's opening (the StartTime transform)
    /// pbrt-v4's ActiveTransform: which of the start and end transforms the transform
    /// directives change; iris renders the start's pose only (no motion blur).
    enum class active_transform { all, start, end } active = active_transform::all;
    bool reverse_orientation = false;
    std::optional<std::uint32_t> material;          ///< the current material (nullopt: pbrt's default)
    std::optional<std::uint32_t> area_light;        ///< the current AreaLightSource's emitter
    /// An AreaLightSource with "power": pbrt-v4 normalises each shape's radiance by its own
    /// area, so each shape gets its own emitter (made when the shape is read).
    struct powered_light {
        std::string name;
        tabulated_spectrum radiance;  ///< luminance-normalised, times scale
        bool two_sided = false;
        double power = 0.0;
    };
    std::shared_ptr<const powered_light> area_power;
    /// pbrt-v4's MediumInterface: the named media on each side of the shapes that follow
    /// ("" = none); the outside one is also the camera's (docs/pbrt-import.md, "Media").
    std::string inside_medium, outside_medium;
};

/// The media a shape was read under, resolved once the file is read (`resolve_media`).
struct shape_media {
    std::string inside, outside;
    location at;
};

class importer {
public:
    importer(const std::string& source, const pbrt_import_options& o) : m_options(o) { m_doc.source = source; }

    scene_document run(std::string text, const std::string& source, const std::filesystem::path& dir) {
        m_base = dir;
        m_last = {source, 1, 1};
        m_files.emplace_back(std::move(text), source, dir);
        // pbrt-v4's defaults without a Sampler or Integrator directive
        m_doc.desc.default_spp = 16;
        m_doc.desc.default_max_depth = 5;
        std::filesystem::path stem = std::filesystem::path(source).stem();
        m_doc.desc.name = stem.empty() ? "pbrt" : stem.string();
        while (auto t = next()) {
            finish_imports();
            directive(*t);
        }
        finish_imports();
        if (!m_stack.empty())
            fail(m_stack.back().at, m_stack.back().kind == opened::object ? "ObjectBegin without its ObjectEnd"
                                                                          : "AttributeBegin without its AttributeEnd");
        if (m_object) fail(m_object_at, "ObjectBegin \"" + *m_object + "\" without its ObjectEnd");
        if (!m_world) fail(m_end, "no WorldBegin: the file describes no scene");
        if (m_doc.shapes.empty()) fail(m_end, "the scene has no shapes");
        bool light = !m_doc.desc.lights.empty() || m_doc.desc.environment.has_value();
        for (const auto& s : m_doc.shapes) light |= s.emitter.has_value();
        if (!light) fail(m_end, "the scene has no light (no AreaLightSource on a shape, no LightSource)");
        imaging_ratio();
        resolve_media();
        m_doc.desc.notes = std::move(m_notes);
        return std::move(m_doc);
    }

private:
    // -- tokens across included files
    std::optional<token> next() {
        if (m_peeked) return std::exchange(m_peeked, std::nullopt);
        while (!m_files.empty()) {
            if (auto t = m_files.back().next()) {
                m_last = t->at;
                return t;
            }
            m_end = m_last;
            m_files.pop_back();
            // the end of an imported file: undone before the next directive (`finish_imports`),
            // not here — the last directive of the file may be reading past its end
            if (!m_imports.empty() && m_imports.back().files == m_files.size() && !m_imports.back().ended) {
                m_imports.back().ended = true;
                m_imports.back().at = m_end;
            }
        }
        return std::nullopt;
    }

    /// An imported file's state changes stay inside it (pbrt-v4's Import).
    void finish_imports() {
        while (!m_imports.empty() && m_imports.back().ended) {
            if (m_stack.size() != m_imports.back().stack || m_stack.back().kind != opened::import)
                fail(m_imports.back().at, "the imported file ends inside an AttributeBegin or ObjectBegin it opened");
            m_state = m_stack.back().state;
            m_stack.pop_back();
            m_imports.pop_back();
        }
    }
    std::optional<token> peek() {
        if (!m_peeked) m_peeked = next();
        return m_peeked;
    }
    token expect(token::kind k, const location& after, const std::string& what) {
        auto t = next();
        if (!t) fail(after, "the file ends where " + what + " was expected");
        if (t->type != k) fail(t->at, "expected " + what + ", found '" + t->text + "'");
        return *t;
    }
    std::string quoted(const location& after, const std::string& what) {
        return expect(token::kind::string, after, what + " (a quoted string)").text;
    }
    double number(const location& after, const std::string& what) {
        return expect(token::kind::number, after, what + " (a number)").number;
    }
    std::vector<double> numbers(std::size_t n, const location& at, const std::string& what) {
        std::vector<double> v;
        auto t = peek();
        const bool bracket = t && t->type == token::kind::open;
        if (bracket) next();
        for (std::size_t i = 0; i < n; ++i) v.push_back(number(at, what));
        if (bracket) expect(token::kind::close, at, "']' after " + std::to_string(n) + " numbers of " + what);
        return v;
    }

    /// The parameter list after a directive's positional arguments.
    parameters read_parameters(const std::string& directive) {
        parameters ps;
        ps.directive = directive;
        for (;;) {
            auto t = peek();
            if (!t || t->type != token::kind::string) break;
            next();
            parameter p;
            p.at = t->at;
            std::istringstream decl(t->text);
            std::string extra;
            if (!(decl >> p.type >> p.name) || (decl >> extra))
                fail(t->at, "expected a parameter declaration \"TYPE NAME\", found \"" + t->text + "\"");
            static const std::set<std::string> types{"integer", "float",  "point2", "vector2", "point3", "vector3",
                                                     "normal",  "normal3", "point", "vector",  "bool",   "string",
                                                     "texture", "rgb",    "spectrum", "blackbody", "color"};
            if (!types.count(p.type)) fail(t->at, "unknown parameter type '" + p.type + "' in \"" + t->text + "\"");
            for (const auto& q : ps.list)
                if (q.name == p.name) fail(t->at, "parameter '" + p.name + "' of " + directive + " is given twice");
            auto value = [&](const token& v) {
                if (p.type == "string" || p.type == "texture" || (p.type == "spectrum" && v.type == token::kind::string)) {
                    if (v.type != token::kind::string) fail(v.at, "\"" + t->text + "\" takes quoted strings, found '" + v.text + "'");
                    p.strings.push_back(v.text);
                } else if (p.type == "bool") {
                    const std::string& s = v.text;
                    if (s != "true" && s != "false") fail(v.at, "\"" + t->text + "\" takes true or false, found '" + s + "'");
                    p.bools.push_back(s == "true");
                } else {
                    if (v.type != token::kind::number) fail(v.at, "\"" + t->text + "\" takes numbers, found '" + v.text + "'");
                    p.numbers.push_back(v.number);
                }
            };
            auto v = next();
            if (!v) fail(t->at, "the file ends where the value of \"" + t->text + "\" was expected");
            if (v->type == token::kind::open) {
                for (;;) {
                    auto w = next();
                    if (!w) fail(v->at, "the file ends inside the list of \"" + t->text + "\" (a ']' is missing)");
                    if (w->type == token::kind::close) break;
                    if (w->type == token::kind::open) fail(w->at, "a '[' inside the list of \"" + t->text + "\"");
                    value(*w);
                }
            } else {
                value(*v);
            }
            if (p.numbers.empty() && p.strings.empty() && p.bools.empty())
                fail(v->at, "\"" + t->text + "\" has no value");
            ps.list.push_back(std::move(p));
        }
        return ps;
    }

    /// What the importer approximated (an error with `strict`) or, with `approximation` false,
    /// ignored without an effect on the image (an output file name, a sampler type): printed
    /// by every tool either way.
    void note(const location& at, const std::string& message, bool approximation = true) {
        if (m_options.strict && approximation) fail(at, message + " (an error under --strict)");
        m_notes.push_back(at.file + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) + ": " + message);
    }

    // -- transforms
    void apply(const glm::dmat4& m) { m_state.ctm = m_state.ctm * m; }

    glm::dmat4 world(const glm::dmat4& m) const { return m_mirror * m; }

    void require_world(const token& t, bool world) {
        if (world && !m_world) fail(t.at, t.text + " is allowed only after WorldBegin");
        if (!world && m_world) fail(t.at, t.text + " is allowed only before WorldBegin");
    }

    // -- directives
    void directive(const token& t) {
        try {
            run_directive(t);
        } catch (const std::invalid_argument& e) {  // a spectrum table refused a value (overflow)
            fail(t.at, std::string("a value out of range (it overflows or is not a number): ") + e.what());
        }
    }

    /// Whether a transform directive changes iris's (the shutter-open) transform: not under
    /// `ActiveTransform EndTime`. A transform that differs between start and end is motion
    /// blur, which iris approximates by the start's pose (a note, an error under --strict).
    bool moves(const token& t) {
        if (m_state.active == graphics_state::active_transform::all) return true;
        note(t.at, t.text + " under ActiveTransform " +
                       (m_state.active == graphics_state::active_transform::start ? "StartTime" : "EndTime") +
                       ": motion blur approximated by the pose at the shutter's opening (iris renders no motion blur)");
        return m_state.active == graphics_state::active_transform::start;
    }

    void run_directive(const token& t) {
        if (t.type != token::kind::word) fail(t.at, "expected a directive, found '" + t.text + "'");
        const std::string& d = t.text;
        static const std::set<std::string> transforms{"Translate", "Scale", "Rotate", "LookAt", "Transform",
                                                      "ConcatTransform", "Identity", "CoordSysTransform"};
        if (transforms.count(d) && m_state.active != graphics_state::active_transform::all) {
            const graphics_state::active_transform a = m_state.active;
            const glm::dmat4 before = m_state.ctm;
            m_state.active = graphics_state::active_transform::all;  // read it as any other transform
            run_directive(t);
            m_state.active = a;
            if (!moves(t)) m_state.ctm = before;
            return;
        }
        if (d == "Translate") {
            const auto v = numbers(3, t.at, "Translate's x y z");
            apply(glm::translate(glm::dmat4(1.0), glm::dvec3(v[0], v[1], v[2])));
        } else if (d == "Scale") {
            const auto v = numbers(3, t.at, "Scale's x y z");
            apply(glm::scale(glm::dmat4(1.0), glm::dvec3(v[0], v[1], v[2])));
        } else if (d == "Rotate") {
            const auto v = numbers(4, t.at, "Rotate's angle x y z");
            const glm::dvec3 axis(v[1], v[2], v[3]);
            if (!(glm::length(axis) > 0.0)) fail(t.at, "Rotate's axis is zero");
            apply(glm::rotate(glm::dmat4(1.0), glm::radians(v[0]), glm::normalize(axis)));
        } else if (d == "LookAt") {
            const auto v = numbers(9, t.at, "LookAt's eye, look and up");
            apply(look_at(t.at, {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}));
        } else if (d == "Transform" || d == "ConcatTransform") {
            const auto v = numbers(16, t.at, d + "'s 16 numbers");
            glm::dmat4 m;
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) m[c][r] = v[static_cast<std::size_t>(4 * c + r)];  // pbrt-v4: column by column
            if (d == "Transform") m_state.ctm = m;
            else apply(m);
        } else if (d == "Identity") {
            m_state.ctm = glm::dmat4(1.0);
        } else if (d == "CoordinateSystem") {
            m_coordinate_systems[quoted(t.at, "the coordinate system's name")] = m_state.ctm;
        } else if (d == "CoordSysTransform") {
            const std::string n = quoted(t.at, "the coordinate system's name");
            const auto it = m_coordinate_systems.find(n);
            if (it == m_coordinate_systems.end()) fail(t.at, "unknown coordinate system '" + n + "'");
            m_state.ctm = it->second;
        } else if (d == "ReverseOrientation") {
            m_state.reverse_orientation = !m_state.reverse_orientation;
        } else if (d == "AttributeBegin" || d == "TransformBegin") {
            // pbrt-v4 reads the deprecated TransformBegin/End as AttributeBegin/End
            m_stack.push_back({m_state, t.at, opened::attribute});
        } else if (d == "AttributeEnd" || d == "TransformEnd") {
            if (m_stack.empty() || m_stack.back().kind != opened::attribute)
                fail(t.at, d + " without a matching AttributeBegin" +
                               (m_stack.empty() ? std::string() : std::string(" (mismatched nesting)")));
            m_state = m_stack.back().state;
            m_stack.pop_back();
        } else if (d == "ActiveTransform") {
            const auto w = expect(token::kind::word, t.at, "All, StartTime or EndTime");
            if (w.text == "All") m_state.active = graphics_state::active_transform::all;
            else if (w.text == "StartTime") m_state.active = graphics_state::active_transform::start;
            else if (w.text == "EndTime") m_state.active = graphics_state::active_transform::end;
            else fail(w.at, "expected All, StartTime or EndTime after ActiveTransform, found '" + w.text + "'");
        } else if (d == "TransformTimes") {
            numbers(2, t.at, "TransformTimes's start and end");
            note(t.at, "TransformTimes ignored (iris renders no motion blur)", false);
        } else if (d == "Option") {
            const std::string n = quoted(t.at, "the option's declaration");
            auto v = next();
            if (!v) fail(t.at, "the file ends where the value of Option \"" + n + "\" was expected");
            if (v->type == token::kind::open)
                for (;;) {
                    auto w = next();
                    if (!w) fail(v->at, "the file ends inside the list of Option \"" + n + "\" (a ']' is missing)");
                    if (w->type == token::kind::close) break;
                }
            note(t.at, "Option \"" + n + "\" ignored", false);
        } else if (d == "ColorSpace") {
            const std::string n = quoted(t.at, "the colour space's name");
            if (n != "srgb") fail(t.at, "ColorSpace \"" + n + "\": only \"srgb\" is supported");
        } else if (d == "Camera") {
            require_world(t, false);
            camera(t);
        } else if (d == "Film") {
            require_world(t, false);
            film(t);
        } else if (d == "Sampler") {
            require_world(t, false);
            const std::string type = quoted(t.at, "the sampler's type");
            auto ps = read_parameters("Sampler \"" + type + "\"");
            // pbrt-v4's sample counts: "stratified" takes x × y jittered samples, "independent"
            // defaults to 4, the others to 16
            if (type == "stratified") m_doc.desc.default_spp = ps.integer("xsamples", 4) * ps.integer("ysamples", 4);
            else m_doc.desc.default_spp = ps.integer("pixelsamples", type == "independent" ? 4 : 16);
            if (m_doc.desc.default_spp < 1) fail(t.at, "the sampler's sample count must be at least 1");
            note_unread(ps, "Sampler", " (iris-render --sampler chooses iris's sampler)", false);
            if (type != "zsobol")
                note(t.at, "Sampler \"" + type + "\": iris uses its own sampler (--sampler); its sample count is the default spp", false);
        } else if (d == "Integrator") {
            require_world(t, false);
            const std::string type = quoted(t.at, "the integrator's type");
            auto ps = read_parameters("Integrator \"" + type + "\"");
            m_doc.desc.default_max_depth = ps.integer("maxdepth", 5);
            if (m_doc.desc.default_max_depth < 0) fail(t.at, "\"integer maxdepth\" must be at least 0");
            if (m_doc.desc.default_max_depth == 0) {
                note(t.at, "\"integer maxdepth\" 0 (emitters seen directly only): iris's shortest path has one scattering event");
                m_doc.desc.default_max_depth = 1;
            }
            note_unread(ps, "Integrator", "", true);
            note(t.at, "Integrator \"" + type + "\": iris renders with its own estimator (iris-render --estimator); maxdepth is the default max depth",
                 false);
        } else if (d == "PixelFilter") {
            require_world(t, false);
            const std::string type = quoted(t.at, "the filter's type");
            m_filter_given = true;
            auto ps = read_parameters("PixelFilter \"" + type + "\"");
            const double rx = ps.number("xradius", type == "box" ? 0.5 : 1.5), ry = ps.number("yradius", type == "box" ? 0.5 : 1.5);
            for (auto& p : ps.list) p.used = true;
            if (type != "box" || rx != 0.5 || ry != 0.5)
                note(t.at, "PixelFilter \"" + type + "\" approximated by iris's pixel box (each sample counts in its own pixel)");
        } else if (d == "Accelerator") {
            const std::string type = quoted(t.at, "the accelerator's type");
            auto ps = read_parameters("Accelerator");
            for (auto& p : ps.list) p.used = true;
            note(t.at, "Accelerator \"" + type + "\" ignored (iris uses Embree)", false);
        } else if (d == "WorldBegin") {
            require_world(t, false);
            world_begin(t);
        } else if (d == "WorldEnd") {
            note(t.at, "WorldEnd is not a pbrt-v4 directive (pbrt-v3's): ignored", false);
        } else if (d == "Include" || d == "Import") {
            if (d == "Import") require_world(t, true);
            include(t, d == "Import");
        } else if (d == "MakeNamedMaterial") {
            require_world(t, true);
            const std::string n = quoted(t.at, "the material's name");
            if (m_named_materials.count(n)) fail(t.at, "material '" + n + "' is defined twice");
            auto ps = read_parameters("MakeNamedMaterial \"" + n + "\"");
            parameter* type = ps.find("type");
            if (!type) fail(t.at, "MakeNamedMaterial \"" + n + "\" has no \"string type\"");
            const std::string ty = ps.expect(*type, {"string"}, 1).strings[0];
            m_named_materials[n] = material(ty, ps, n, t.at);
        } else if (d == "Material") {
            require_world(t, true);
            const std::string ty = quoted(t.at, "the material's type");
            auto ps = read_parameters("Material \"" + ty + "\"");
            m_state.material = material(ty, ps, "material." + std::to_string(m_doc.desc.materials.size()), t.at);
        } else if (d == "NamedMaterial") {
            require_world(t, true);
            const std::string n = quoted(t.at, "the material's name");
            const auto it = m_named_materials.find(n);
            if (it == m_named_materials.end()) fail(t.at, "unknown material '" + n + "' (no MakeNamedMaterial before it)");
            m_state.material = it->second;
        } else if (d == "Texture") {
            require_world(t, true);
            texture_directive(t);
        } else if (d == "LightSource") {
            require_world(t, true);
            light_source(t);
        } else if (d == "AreaLightSource") {
            require_world(t, true);
            area_light(t);
        } else if (d == "Shape") {
            require_world(t, true);
            shape(t);
        } else if (d == "ObjectBegin") {
            require_world(t, true);
            if (m_object) fail(t.at, "ObjectBegin inside ObjectBegin \"" + *m_object + "\"");
            const std::string n = quoted(t.at, "the object's name");
            if (m_objects.count(n)) fail(t.at, "object '" + n + "' is defined twice");
            m_object = n;
            m_object_at = t.at;
            m_objects[n];
            m_stack.push_back({m_state, t.at, opened::object});
        } else if (d == "ObjectEnd") {
            if (!m_object || m_stack.empty() || m_stack.back().kind != opened::object)
                fail(t.at, "ObjectEnd without a matching ObjectBegin");
            m_object.reset();
            m_state = m_stack.back().state;
            m_stack.pop_back();
        } else if (d == "ObjectInstance") {
            require_world(t, true);
            const std::string n = quoted(t.at, "the object's name");
            const auto it = m_objects.find(n);
            if (it == m_objects.end()) fail(t.at, "unknown object '" + n + "' (no ObjectBegin before it)");
            if (m_object) fail(t.at, "ObjectInstance inside ObjectBegin");
            const auto& media = m_object_media[n];
            for (std::size_t i = 0; i < it->second.size(); ++i) {  // its orientation is the definition's
                shape_spec s = it->second[i];
                s.transform = glm::mat4(world(m_state.ctm) * glm::dmat4(s.transform));
                s.name = n + "/" + s.name;
                add_shape(std::move(s), media[i], t.at);
            }
        } else if (d == "MakeNamedMedium") {
            named_medium(t);
        } else if (d == "MediumInterface") {
            // one name: both sides (pbrt-v4's rule); the names resolve once the file is read
            m_state.inside_medium = quoted(t.at, "the inside medium's name");
            m_state.outside_medium = m_state.inside_medium;
            if (auto p = peek(); p && p->type == token::kind::string)
                m_state.outside_medium = next()->text;
        } else if (d == "Attribute") {
            fail(t.at, "Attribute: default parameters per target are not supported (docs/pbrt-import.md)");
        } else {
            fail(t.at, "unknown directive '" + d + "'");
        }
    }

    glm::dmat4 look_at(const location& at, glm::dvec3 eye, glm::dvec3 look, glm::dvec3 up) {
        const glm::dvec3 dir = look - eye;
        if (!(glm::length(dir) > 0.0)) fail(at, "LookAt: the eye and the look-at point are the same");
        const glm::dvec3 d = glm::normalize(dir);
        if (!(glm::length(glm::cross(glm::normalize(up), d)) > 1e-9)) fail(at, "LookAt: the up vector is parallel to the view direction");
        // pbrt-v4's LookAt: camera x = up × dir (a left-handed camera frame), y, z = dir
        const glm::dvec3 right = glm::normalize(glm::cross(glm::normalize(up), d));
        const glm::dvec3 new_up = glm::cross(d, right);
        glm::dmat4 world_from_camera(1.0);
        world_from_camera[0] = glm::dvec4(right, 0.0);
        world_from_camera[1] = glm::dvec4(new_up, 0.0);
        world_from_camera[2] = glm::dvec4(d, 0.0);
        world_from_camera[3] = glm::dvec4(eye, 1.0);
        return glm::inverse(world_from_camera);
    }

    void camera(const token& t) {
        const std::string type = quoted(t.at, "the camera's type");
        auto ps = read_parameters("Camera \"" + type + "\"");
        if (type != "perspective") fail(t.at, "Camera \"" + type + "\": only \"perspective\" is supported");
        m_camera_from_world = m_state.ctm;
        m_camera_medium = m_state.outside_medium;  // pbrt-v4: the camera is in the current outside medium
        m_coordinate_systems["camera"] = glm::inverse(m_state.ctm);
        m_fov = ps.number("fov", 90.0);
        if (!(m_fov > 0.0 && m_fov < 180.0)) fail(t.at, "\"float fov\" must be in (0, 180) degrees");
        if (ps.number("lensradius", 0.0) > 0.0) {
            ps.find("focaldistance");
            note(t.at, "Camera \"lensradius\": iris's camera is a pinhole (no depth of field)");
        }
        ps.find("focaldistance");
        // pbrt-v4's exposure is the shutter's open time (times the film's ISO / 100)
        const double open = ps.number("shutteropen", 0.0), close = ps.number("shutterclose", 1.0);
        if (!(close - open > 0.0 && close - open <= 1e6)) fail(t.at, "the shutter must be open for (0, 1e6] s (shutterclose > shutteropen)");
        m_exposure_time = close - open;  // part of pbrt-v4's imaging ratio (`imaging_ratio`)
        ps.finish();
        m_camera_at = t.at;
    }

    void film(const token& t) {
        const std::string type = quoted(t.at, "the film's type");
        auto ps = read_parameters("Film \"" + type + "\"");
        if (type != "rgb" && type != "gbuffer" && type != "spectral") fail(t.at, "Film \"" + type + "\": unknown film type");
        m_doc.desc.camera.width = ps.integer("xresolution", 1280);
        m_doc.desc.camera.height = ps.integer("yresolution", 720);
        if (m_doc.desc.camera.width < 1 || m_doc.desc.camera.height < 1 || m_doc.desc.camera.width > 16384 ||
            m_doc.desc.camera.height > 16384)
            fail(t.at, "the film's resolution must be 1-16384 pixels a side");
        if (parameter* p = ps.find("cropwindow")) {
            const auto& c = ps.expect(*p, {"float"}, 4).numbers;
            if (c[0] != 0.0 || c[1] != 1.0 || c[2] != 0.0 || c[3] != 1.0)
                fail(p->at, "a crop window is not supported (render the whole image and crop it: iris-image crop)");
        }
        if (parameter* p = ps.find("pixelbounds")) fail(p->at, "pixel bounds are not supported (iris-image crop)");
        if (parameter* p = ps.find("filename")) note(p->at, "Film \"filename\" ignored (iris-render -o names the output)", false);
        // pbrt-v4's imaging ratio: exposure time × ISO / 100, applied to every light (`imaging_ratio`)
        m_iso = ps.number("iso", 100.0);
        if (!(m_iso > 0.0 && m_iso <= 1e6)) fail(t.at, "\"float iso\" must lie in (0, 1e6]");
        m_iso_at = t.at;
        if (const std::string sensor = ps.string("sensor", "cie1931"); sensor != "cie1931")
            note(t.at, "Film \"sensor\" \"" + sensor + "\" approximated by the CIE 1931 observer (iris's film is XYZ; pbrt-v4 "
                       "also white-balances a camera sensor to 6500 K)");
        if (const double wb = ps.number("whitebalance", 0.0); wb != 0.0)
            note(t.at, "Film \"whitebalance\" " + reader_number(wb) + " ignored (iris does not white-balance)");
        for (auto& p : ps.list)
            if (!p.used) {
                p.used = true;
                note(p.at, "Film parameter \"" + p.name + "\" ignored (iris writes linear sRGB, exposure 1, to iris-render -o)");
            }
    }

    void world_begin(const token& t) {
        m_world = true;
        m_coordinate_systems["world"] = glm::dmat4(1.0);
        // the camera: pbrt-v4's camera-from-world at `Camera` (identity if there was none)
        if (!(std::fabs(glm::determinant(m_camera_from_world)) > 0.0))
            fail(m_camera_at, "the camera's transform is singular (a zero scale?)");
        if (!m_filter_given)
            note(t.at, "no PixelFilter: pbrt-v4's default Gaussian filter approximated by iris's pixel box");
        const glm::dmat4 w = glm::inverse(m_camera_from_world);
        const glm::dvec3 eye(w[3]), right = glm::normalize(glm::dvec3(w * glm::dvec4(1, 0, 0, 0))),
            up = glm::normalize(glm::dvec3(w * glm::dvec4(0, 1, 0, 0))), dir = glm::normalize(glm::dvec3(w * glm::dvec4(0, 0, 1, 0)));
        // iris's image right is dir × up: mirror the world when pbrt-v4's frame is the other way
        if (glm::dot(glm::cross(dir, up), right) < 0.0) m_mirror = glm::scale(glm::dmat4(1.0), glm::dvec3(-1.0, 1.0, 1.0));
        const glm::dvec3 e = m_mirror * glm::dvec4(eye, 1.0), d = m_mirror * glm::dvec4(dir, 0.0), u = m_mirror * glm::dvec4(up, 0.0);
        for (int i = 0; i < 3; ++i)
            if (!std::isfinite(e[i]) || !std::isfinite(d[i]) || !std::isfinite(u[i]) || std::fabs(e[i]) > max_coordinate)
                fail(m_camera_at, "the camera's position or orientation is not finite, or beyond ±1e7");
        if (!(glm::length(glm::cross(d, u)) > 1e-6)) fail(m_camera_at, "the camera's up and view directions are parallel");
        auto& c = m_doc.desc.camera;
        c.position = glm::vec3(e);
        c.look_at = glm::vec3(e + d * std::max(1.0, glm::length(e)));  // far enough that float keeps the aim
        c.up = glm::vec3(u);
        // pbrt-v4's fov spans the shorter side, iris's the height
        double fov = m_fov;
        if (c.width < c.height) fov = std::atan(std::tan(fov * std::numbers::pi / 360.0) * c.height / c.width) * 360.0 / std::numbers::pi;
        c.fov_y_degrees = static_cast<float>(fov);
        // pbrt-v4's WorldBegin resets the transform only: the media of a MediumInterface given
        // before it (the camera's, typically) stay current for the world's shapes
        graphics_state world_state;
        world_state.inside_medium = m_state.inside_medium;
        world_state.outside_medium = m_state.outside_medium;
        m_state = world_state;
        m_stack.clear();
        (void)t;
    }

    void include(const token& t, bool import) {
        const std::string n = quoted(t.at, "the file to include");
        if (static_cast<int>(m_files.size()) > max_include_depth) fail(t.at, "includes nested more than 32 deep");
        const std::filesystem::path p = resolve(n);
        for (const auto& f : m_files)
            if (f.file() == p.string()) fail(t.at, "'" + n + "' includes itself (through " + m_files.back().file() + ")");
        std::string text = read_file(p, t.at, "included file", m_options.read_files);
        if (p.extension() == ".gz") {  // pbrt-v4 reads gzip-compressed scene files (`part.pbrt.gz`)
            std::string why;
            auto plain = gunzip_bytes(text, max_included_bytes, why);
            if (!plain) fail(t.at, "included file '" + n + "': " + why);
            text = std::move(*plain);
        }
        m_included_bytes += text.size();
        if (++m_included > max_included_files || m_included_bytes > max_included_bytes)
            fail(t.at, "more than 10 000 included files or 4 GiB of included text: refused");
        if (import) {
            m_imports.push_back({m_files.size(), m_stack.size() + 1, false, t.at});
            m_stack.push_back({m_state, t.at, opened::import});
        }
        m_files.emplace_back(std::move(text), p.string(), p.parent_path());
    }

    /// A file a scene names: relative to the main file's directory, as pbrt-v4 resolves it.
    std::filesystem::path resolve(const std::string& name) const {
        const std::filesystem::path p(name);
        return p.is_relative() ? m_base / p : p;
    }

    // -- spectra of parameters
    std::optional<spectrum_value> spectrum(parameters& ps, std::string_view name, spectrum_use use) {
        parameter* p = ps.find(name);
        if (!p) return std::nullopt;
        spectrum_value v;
        if (p->type == "texture") {
            texture_result r = named_texture(ps.expect(*p, {"texture"}, 1).strings[0], "spectrum", p->at, use);
            if (r.image)
                fail(p->at, "\"texture " + p->name + "\": an image texture is supported only as a diffuse or coateddiffuse "
                            "\"reflectance\" (docs/pbrt-import.md)");
            return std::move(*r.constant);
        }
        if (p->type == "float") {
            const double x = ps.expect(*p, {"float"}, 1).numbers[0];
            v.constant = x;
            v.name = "constant";
            v.table = tabulate([&](double) { return x; }, outside::clamp);
            return v;
        }
        if (p->type == "rgb" || p->type == "color") {
            const auto& c = ps.expect(*p, {"rgb", "color"}, 3).numbers;
            if (c[0] < 0.0 || c[1] < 0.0 || c[2] < 0.0) fail(p->at, "\"rgb " + p->name + "\" has a negative component");
            const rgb col{c[0], c[1], c[2]};
            v.name = "rgb";
            if (use == spectrum_use::albedo) {
                if (c[0] > 1.0 || c[1] > 1.0 || c[2] > 1.0) fail(p->at, "\"rgb " + p->name + "\" is a reflectance: components must be at most 1");
                const auto s = rgb_to_sigmoid(col);
                v.table = tabulate([&](double l) { return s(l); }, outside::clamp);
            } else if (use == spectrum_use::illuminant) {
                const auto e = rgb_illuminant::from_linear_srgb(col);
                v.table = tabulate([&](double l) { return e(l); });
                v.rgb_illuminant = true;
            } else {  // pbrt-v4's RGBUnboundedSpectrum: m·S(λ), m = 2·max, S the sigmoid of rgb/m
                const double m = 2.0 * std::max({c[0], c[1], c[2]});
                const auto sg = rgb_to_sigmoid(m > 0.0 ? rgb{c[0] / m, c[1] / m, c[2] / m} : rgb{0.0, 0.0, 0.0});
                v.table = tabulate([&](double l) { return m > 0.0 ? m * sg(l) : 0.0; }, outside::clamp);
            }
            return v;
        }
        if (p->type == "blackbody") {
            const double k = ps.expect(*p, {"blackbody"}, 1).numbers[0];
            if (!(k >= 1.0 && k <= 1e6)) fail(p->at, "\"blackbody " + p->name + "\" must be a temperature in 1-1e6 K");
            const blackbody_spectrum b(k);
            v.name = "blackbody:" + reader_number(k);
            v.table = tabulate([&](double l) { return b(l); });
            return v;
        }
        if (p->type != "spectrum") ps.expect(*p, {"spectrum", "rgb", "blackbody", "float"}, 0);
        if (!p->strings.empty()) {
            if (p->strings.size() != 1) fail(p->at, "\"spectrum " + p->name + "\" takes one name");
            const std::string& n = p->strings[0];
            for (const auto& g : pbrt_glasses)
                if (g.pbrt == n) {
                    const auto glass = find_glass(g.iris);
                    v.glass = glass->sellmeier;
                    v.name = std::string(g.iris);
                    v.table = tabulate([&](double l) { return glass->sellmeier.n(l); }, outside::clamp);
                    return v;
                }
            for (const auto& i : pbrt_illuminants)
                if (i.pbrt == n) {
                    v.name = std::string(i.iris);
                    v.table = find_illuminant(i.iris)->spectrum();
                    return v;
                }
            if (n.rfind("metal-", 0) == 0) {
                const auto dash = n.rfind('-');
                const std::string metal = n.substr(6, dash - 6), part = n.substr(dash + 1);
                if (const auto m = find_metal(metal); m && (part == "eta" || part == "k")) {
                    v.name = n;
                    v.table = part == "eta" ? m->eta_spectrum() : m->k_spectrum();
                    return v;
                }
            }
            if (n.size() > 4 && n.substr(n.size() - 4) == ".spd") return spd_file(*p, n);
            fail(p->at, "unknown named spectrum '" + n + "' (iris knows glass-BK7, glass-BAF10, glass-FK51A, glass-LASF9, "
                        "glass-F5, glass-F10, glass-F11, metal-{Ag,Al,Au,Cu,CuZn}-{eta,k}, stdillum-D65, stdillum-A, "
                        "and .spd files)");
        }
        return inline_spectrum(p->numbers, p->at, "\"spectrum " + p->name + "\"", v);
    }

    static std::string reader_number(double x) {
        std::ostringstream s;
        s << x;
        return s.str();
    }

    spectrum_value inline_spectrum(const std::vector<double>& xs, const location& at, const std::string& what, spectrum_value v) {
        if (xs.size() < 4 || xs.size() % 2 != 0) fail(at, what + " needs (wavelength, value) pairs, at least two");
        std::vector<double> l, y;
        for (std::size_t i = 0; i < xs.size(); i += 2) {
            if (!l.empty() && !(xs[i] > l.back())) fail(at, what + ": the wavelengths must increase");
            if (!(xs[i] > 0.0 && xs[i] < 1e5)) fail(at, what + ": a wavelength must be in (0, 1e5) nm");
            l.push_back(xs[i]);
            y.push_back(xs[i + 1]);
        }
        v.name = "tabulated";
        v.table = tabulated_spectrum(std::move(l), std::move(y));  // 0 outside the list, as pbrt-v4's
        return v;
    }

    spectrum_value spd_file(const parameter& p, const std::string& n) {
        const std::filesystem::path path = resolve(n);
        const std::string text = read_file(path, p.at, "spectrum file", m_options.read_files);
        std::vector<double> xs;
        std::istringstream in(text);
        std::string line;
        while (std::getline(in, line)) {
            if (const auto h = line.find('#'); h != std::string::npos) line.resize(h);
            std::istringstream ls(line);
            std::string w;
            while (ls >> w) {
                double x = 0.0;
                const auto r = std::from_chars(w.data(), w.data() + w.size(), x);
                if (r.ec != std::errc() || r.ptr != w.data() + w.size() || !std::isfinite(x))
                    fail(p.at, "spectrum file '" + n + "': '" + w + "' is not a number");
                xs.push_back(x);
            }
        }
        spectrum_value v = inline_spectrum(xs, p.at, "spectrum file '" + n + "'", {});
        v.name = path.filename().string();
        return v;
    }

    /// iris's radiance of a pbrt-v4 light: scale·S/Y(S), or scale·E_rgb for an "rgb" one.
    tabulated_spectrum light_radiance(const spectrum_value& s, double scale, const location& at) {
        for (double v : s.table.values())
            if (v < 0.0) fail(at, "the light's spectrum is negative somewhere (" + reader_number(v) + ")");
        double k = scale;
        if (!s.rgb_illuminant) {
            const double y = luminance(s.table);
            if (!(y > 0.0)) fail(at, "the light's spectrum has no luminance (its Y over 360-830 nm is 0)");
            k = scale / y;
        }
        tabulated_spectrum out = s.table.scaled(k);
        for (double v : out.values())
            if (!(std::fabs(v) < 1e30)) fail(at, "the light's radiance overflows (its scale is too large)");
        return out;
    }

    /// A point of a light in iris's world: finite and within ±1e7.
    glm::vec3 light_point(const glm::dmat4& m, const glm::dvec3& p, const location& at) {
        const glm::dvec3 w = m * glm::dvec4(p, 1.0);
        for (int i = 0; i < 3; ++i)
            if (!std::isfinite(w[i]) || std::fabs(w[i]) > max_coordinate) fail(at, "a light's position is beyond ±1e7");
        return glm::vec3(w);
    }
    /// A light's direction in iris's world: unit, from a finite non-zero vector.
    glm::vec3 light_direction(const glm::dvec3& d, const location& at, const std::string& what) {
        const double l = glm::length(d);
        if (!(l > 0.0) || !std::isfinite(l)) fail(at, what + " has no direction (from and to are the same point, or too far apart)");
        return glm::vec3(d / l);
    }

    double light_scale(parameters& ps, const location& at) {
        const double scale = ps.number("scale", 1.0);
        if (!(scale >= 0.0)) fail(at, "\"float scale\" must be at least 0");
        return scale;
    }

    /// pbrt-v4's "power" (a light's luminous power) or "illuminance" (`name`): the value, or
    /// nothing when absent or not positive (pbrt-v4 ignores it then: a note says so).
    std::optional<double> photometric(parameters& ps, const char* name, const location& at) {
        parameter* p = ps.find(name);
        if (!p) return std::nullopt;
        const double v = ps.expect(*p, {"float"}, 1).numbers[0];
        if (!(v > 0.0)) {
            note(p->at, std::string("\"float ") + name + "\" " + reader_number(v) + " ignored (pbrt-v4 reads only a positive one)", false);
            return std::nullopt;
        }
        if (!(v <= 1e15)) fail(p->at, std::string("\"float ") + name + "\" must be at most 1e15");
        (void)at;
        return v;
    }

    std::uint32_t add_emitter(const std::string& name, tabulated_spectrum radiance, bool two_sided) {
        m_doc.desc.emitters.push_back({name, std::move(radiance), two_sided});
        emitter_spec e;
        e.name = "emitter." + std::to_string(m_doc.emitters.size());
        m_doc.emitters.push_back(e);
        return static_cast<std::uint32_t>(m_doc.desc.emitters.size() - 1);
    }

    /// A note for each parameter of `ps` nothing read: "KIND parameter "NAME" ignored" + why.
    void note_unread(parameters& ps, const std::string& kind, const std::string& why, bool approximation) {
        for (auto& p : ps.list)
            if (!p.used) {
                p.used = true;
                note(p.at, kind + " parameter \"" + p.name + "\" ignored" + why, approximation);
            }
    }

    /// pbrt-v4's film multiplies what it records by exposure time × ISO / 100 (its
    /// PixelSensor's imaging ratio, 1 by default); iris's film records radiance, so every
    /// light is scaled by it instead — the same image, linearly.
    void imaging_ratio() {
        const double k = m_exposure_time * m_iso / 100.0;
        if (k == 1.0) return;
        for (auto& e : m_doc.desc.emitters) e.radiance = e.radiance.scaled(k);
        if (m_doc.desc.environment) m_doc.desc.environment->radiance = m_doc.desc.environment->radiance.scaled(k);
        if (m_doc.environment_image) m_doc.environment_image->scale *= k;
        note(m_iso_at.file.empty() ? m_camera_at : m_iso_at, "pbrt-v4's imaging ratio " + reader_number(k) + " (shutter time " + reader_number(m_exposure_time) +
                           " s × ISO " + reader_number(m_iso) + " / 100) applied to every light",
             false);
    }

    // -- textures (docs/pbrt-import.md, "Textures")

    /// A named texture as written: its class and parameters, evaluated where it is used (a
    /// spectrum texture's "rgb" is a reflectance or an index depending on the parameter).
    struct texture_def {
        std::string type;  ///< imagemap, constant, scale, mix
        parameters ps;
        location at;
    };
    /// What a texture evaluates to: a constant (spectrum or float), or an image.
    struct texture_result {
        std::optional<spectrum_value> constant;  ///< a spectrum texture's constant value
        std::optional<double> value;             ///< a float texture's constant value
        std::optional<texture_spec> image;       ///< an image (spectrum textures only)
    };

    void texture_directive(const token& t) {
        const std::string n = quoted(t.at, "the texture's name");
        const std::string kind = quoted(t.at, "the texture's kind (\"spectrum\" or \"float\")");
        if (kind != "spectrum" && kind != "float")
            fail(t.at, "Texture \"" + n + "\": the kind must be \"spectrum\" or \"float\", found \"" + kind + "\"");
        const std::string type = quoted(t.at, "the texture's class");
        texture_def def{type, read_parameters("Texture \"" + n + "\" \"" + kind + "\" \"" + type + "\""), t.at};
        static const std::map<std::string, std::vector<std::string_view>> allowed{
            {"imagemap", {"filename", "wrap", "filter", "maxanisotropy", "encoding", "scale", "invert", "mapping", "uscale",
                          "vscale", "udelta", "vdelta"}},
            {"constant", {"value"}},
            {"scale", {"tex", "scale"}},
            {"mix", {"tex1", "tex2", "amount"}}};
        const auto it = allowed.find(type);
        if (it == allowed.end())
            fail(t.at, "Texture \"" + n + "\": the class \"" + type + "\" is not supported (iris: imagemap, constant, scale, mix; "
                       "docs/pbrt-import.md)");
        for (const auto& p : def.ps.list) {
            if (std::find(it->second.begin(), it->second.end(), p.name) == it->second.end())
                fail(p.at, "parameter \"" + p.type + " " + p.name + "\" of " + def.ps.directive +
                               " is not supported by iris's pbrt-v4 importer (docs/pbrt-import.md)");
            if (p.type == "texture") {  // what it names must exist now: no cycles, and the error where it is written
                if (p.strings.size() != 1) fail(p.at, "\"texture " + p.name + "\" takes one name");
                const std::string sub = p.name == "amount" || (p.name == "scale" && type == "scale") || kind == "float" ? "float" : "spectrum";
                if (!m_textures.count({sub, p.strings[0]}))
                    fail(p.at, "unknown " + sub + " texture '" + p.strings[0] + "' (no Texture \"" + p.strings[0] + "\" \"" + sub + "\" before it)");
            }
        }
        if (type == "imagemap" && kind == "float")
            fail(t.at, "Texture \"" + n + "\": float image textures (roughness, bump or alpha maps) are not supported; "
                       "iris reads image textures as diffuse reflectances only");
        if (m_textures.count({kind, n})) fail(t.at, "Texture \"" + n + "\" \"" + kind + "\" is defined twice");
        m_textures.emplace(std::make_pair(kind, n), std::move(def));
        // evaluated once here, as pbrt-v4 creates every texture: a bad one is an error even unused
        // (a spectrum texture as a reflectance, the only use iris has for one)
        (void)named_texture(n, kind, t.at, spectrum_use::albedo);
    }

    /// The texture `name` of `kind` evaluated for `use`.
    texture_result named_texture(const std::string& name, const std::string& kind, const location& at, spectrum_use use) {
        const auto it = m_textures.find({kind, name});
        if (it == m_textures.end())
            fail(at, "unknown " + kind + " texture '" + name + "' (no Texture \"" + name + "\" \"" + kind + "\" before it)");
        // a bound on the recursion (and on re-evaluating long chains): no cycles are possible
        // (a texture names only earlier ones), but a chain may be arbitrarily long
        struct depth_guard {
            int& d;
            explicit depth_guard(int& x) : d(x) { ++d; }
            ~depth_guard() { --d; }
        } guard(m_texture_depth);
        if (m_texture_depth > max_texture_depth)
            fail(at, "textures nested more than " + std::to_string(max_texture_depth) + " deep (a texture of a texture of …)");
        texture_def def = it->second;  // a copy: its parameters are marked as this evaluation reads them
        texture_result r;
        auto& ps = def.ps;
        if (def.type == "constant") {
            r = operand(ps, "value", kind, use, 1.0);
        } else if (def.type == "scale") {
            texture_result tex = operand(ps, "tex", kind, use, 1.0);
            const texture_result k = operand(ps, "scale", "float", use, 1.0);
            if (!k.value) fail(def.at, "a scale texture's \"scale\" must be a constant");
            const double s = *k.value;
            if (tex.image) {
                if (!(s > 0.0 && s <= 1e6)) fail(def.at, "an image texture's scale must lie in (0, 1e6]");
                tex.image->scale *= s;
            } else if (tex.value) {
                *tex.value *= s;
            } else {
                tex.constant->table = tex.constant->table.scaled(s);
                tex.constant->name = "scaled";
                tex.constant->glass.reset();
                if (tex.constant->constant) *tex.constant->constant *= s;
            }
            r = std::move(tex);
        } else if (def.type == "mix") {
            texture_result a = operand(ps, "tex1", kind, use, 0.0), b = operand(ps, "tex2", kind, use, 1.0);
            const texture_result k = operand(ps, "amount", "float", use, 0.5);
            if (!k.value) fail(def.at, "a mix texture's \"amount\" must be a constant (iris mixes constants only)");
            const double w = *k.value;
            if (w == 0.0 && !a.image) r = std::move(a);
            else if (w == 1.0 && !b.image) r = std::move(b);
            else if (a.image || b.image) fail(def.at, "a mix texture of an image texture is not supported (iris mixes constants only)");
            else if (a.value) r.value = (1.0 - w) * *a.value + w * *b.value;
            else {
                spectrum_value v;
                v.name = "mix";
                const tabulated_spectrum ta = a.constant->table, tb = b.constant->table;
                v.table = tabulate([&](double l) { return (1.0 - w) * ta(l) + w * tb(l); }, outside::clamp);
                r.constant = std::move(v);
            }
        } else {  // imagemap, spectrum (float image maps are refused where they are defined)
            r.image = image_texture_spec(ps, def.at);
        }
        ps.finish();
        return r;
    }

    /// One operand of a texture: a named texture, or a value of the parameter's own type.
    texture_result operand(parameters& ps, const std::string& name, const std::string& kind, spectrum_use use, double fallback) {
        texture_result r;
        parameter* p = ps.find(name);
        if (p && p->type == "texture") return named_texture(p->strings[0], kind, p->at, use);
        if (kind == "float") {
            r.value = p ? ps.expect(*p, {"float"}, 1).numbers[0] : fallback;
            return r;
        }
        if (auto s = spectrum(ps, name, use)) {
            r.constant = std::move(*s);
        } else {
            spectrum_value v;
            v.name = "constant";
            v.constant = fallback;
            v.table = tabulate([&](double) { return fallback; }, outside::clamp);
            r.constant = std::move(v);
        }
        return r;
    }

    texture_spec image_texture_spec(parameters& ps, const location& at) {
        texture_spec spec;
        const std::string f = ps.string("filename", "");
        if (f.empty()) fail(at, "an imagemap texture has no \"string filename\"");
        spec.file = resolve(f);
        std::string ext = spec.file.extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".exr" && ext != ".bmp" && ext != ".tga")
            fail(at, "imagemap '" + f + "': iris reads .png, .jpg, .bmp, .tga and .exr images");
        if (m_options.read_files) {
            std::error_code ec;
            if (!std::filesystem::is_regular_file(spec.file, ec)) fail(at, "imagemap '" + f + "' does not exist or is not a file");
        } else {
            fail(at, "imagemap '" + f + "' not read: reading files is disabled");
        }
        const std::string wrap = ps.string("wrap", "repeat");
        if (wrap == "repeat") spec.wrap = texture_wrap::repeat;
        else if (wrap == "clamp") spec.wrap = texture_wrap::clamp;
        else fail(at, "imagemap wrap \"" + wrap + "\" is not supported (iris: repeat, clamp)");
        const std::string filter = ps.string("filter", "bilinear");
        if (filter != "bilinear") {
            if (filter != "point" && filter != "trilinear" && filter != "ewa") fail(at, "unknown imagemap filter \"" + filter + "\"");
            note(at, "imagemap filter \"" + filter + "\" approximated by a bilinear lookup (iris does not filter textures)");
        }
        ps.number("maxanisotropy", 8.0);  // only the "ewa" filter reads it
        // pbrt-v4's default encoding: sRGB for PNG, linear for everything else
        const std::string encoding = ps.string("encoding", ext == ".png" ? "sRGB" : "linear");
        if (encoding == "sRGB") spec.srgb = true;
        else if (encoding == "linear") spec.srgb = false;
        else fail(at, "imagemap encoding \"" + encoding + "\" is not supported (iris: sRGB, linear)");
        spec.scale = ps.number("scale", 1.0);
        if (!(spec.scale > 0.0 && spec.scale <= 1e6)) fail(at, "an imagemap's \"float scale\" must lie in (0, 1e6]");
        if (ps.boolean("invert", false)) fail(at, "an inverted imagemap (\"bool invert\" true) is not supported");
        const std::string mapping = ps.string("mapping", "uv");
        if (mapping != "uv") fail(at, "texture mapping \"" + mapping + "\" is not supported (iris: uv)");
        const double su = ps.number("uscale", 1.0), sv = ps.number("vscale", 1.0);
        const double du = ps.number("udelta", 0.0), dv = ps.number("vdelta", 0.0);
        for (double x : {su, sv, du, dv})
            if (!(std::fabs(x) <= 1e6)) fail(at, "a texture's uscale, vscale, udelta and vdelta must lie in [-1e6, 1e6]");
        if (su == 0.0 || sv == 0.0) fail(at, "a texture's uscale and vscale must not be 0");
        spec.uv_scale = {static_cast<float>(su), static_cast<float>(sv)};
        spec.uv_offset = {static_cast<float>(du), static_cast<float>(dv)};
        spec.pointer = "";
        spec.line = at.line;
        spec.file_name = at.file;
        return spec;
    }

    /// The document's index of an image texture (one entry per distinct image and setting).
    std::uint32_t add_texture(const texture_spec& spec) {
        for (std::size_t i = 0; i < m_doc.textures.size(); ++i) {
            const auto& o = m_doc.textures[i];
            if (o.file == spec.file && o.wrap == spec.wrap && o.scale == spec.scale && o.srgb == spec.srgb &&
                o.uv_scale == spec.uv_scale && o.uv_offset == spec.uv_offset)
                return static_cast<std::uint32_t>(i);
        }
        m_doc.textures.push_back(spec);
        return static_cast<std::uint32_t>(m_doc.textures.size() - 1);
    }

    /// A float parameter that may also name a constant float texture.
    double float_parameter(parameters& ps, const std::string& name, double fallback) {
        parameter* p = ps.find(name);
        if (p && p->type == "texture") {
            const texture_result r = named_texture(ps.expect(*p, {"texture"}, 1).strings[0], "float", p->at, spectrum_use::unbounded);
            return *r.value;
        }
        return ps.number(name, fallback);
    }

    void check_reflectance(const tabulated_spectrum& s, const location& at, const std::string& param) {
        for (double x : s.values())
            if (x < 0.0 || x > 1.0) fail(at, "\"" + param + "\" must lie in [0, 1] at every wavelength");
    }

    /// `LightSource "infinite" "string filename"`: pbrt-v4's equal-area image, its texels
    /// linear sRGB with (1, 1, 1) D65 at luminance 1 times `scale`, turned by the light's
    /// transform (mirror included) — iris's environment image (docs/pbrt-import.md).
    void environment_image(const token& t, const std::string& f, double scale, const glm::dmat4& m,
                           std::optional<double> illuminance) {
        environment_image_spec spec;
        spec.file = resolve(f);
        std::string ext = spec.file.extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (ext != ".exr") fail(t.at, "infinite light image '" + f + "': iris reads OpenEXR environment images only");
        if (!m_options.read_files) fail(t.at, "infinite light image '" + f + "' not read: reading files is disabled");
        std::error_code ec;
        if (!std::filesystem::is_regular_file(spec.file, ec)) fail(t.at, "infinite light image '" + f + "' does not exist or is not a file");
        if (!(scale > 0.0 && scale <= 1e12)) fail(t.at, "an infinite light's \"float scale\" must lie in (0, 1e12]");
        spec.mapping = environment_mapping::equal_area;
        spec.scale = scale;
        spec.illuminance = illuminance;
        // the light's frame in iris's world: orthogonal up to a uniform scale (pbrt-v4 normalises
        // the direction after its inverse transform, so a uniform scale does not matter)
        glm::dmat3 a(m);
        const glm::dmat3 e = glm::transpose(a) * a;
        const double c = (e[0][0] + e[1][1] + e[2][2]) / 3.0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (!(std::fabs(e[i][j] - (i == j ? c : 0.0)) <= 1e-6 * c))
                    fail(t.at, "an infinite light under a non-uniform scale or shear is not supported (iris turns environments only)");
        a /= std::sqrt(c);
        // pbrt-v4's light frame (x, y, z) as the equal-area map's iris convention (x, z, −y)
        // (iris/render/lights/directions.hpp): to_map = P · a⁻¹, a⁻¹ = aᵀ
        glm::dmat3 p(0.0);  // glm: [column][row]
        p[0][0] = 1.0;      // row 0: x
        p[2][1] = 1.0;      // row 1: z
        p[1][2] = -1.0;     // row 2: −y
        spec.to_map = glm::mat3(p * glm::transpose(a));
        spec.pointer = "";
        spec.line = t.at.line;
        spec.file_name = t.at.file;
        m_doc.environment_image = spec;
        const auto d65 = find_illuminant("D65");
        environment_desc env;
        env.spd_name = "D65";
        env.radiance = d65->spectrum().scaled(white_normalisation(d65->spectrum()));
        env.basis = detail::environment_basis(d65->spectrum());
        m_doc.desc.environment = std::move(env);
    }

    // -- materials
    float roughness(parameters& ps, bool remap_default, const location& at, const std::string& prefix = "") {
        const double r = float_parameter(ps, prefix + "roughness", 0.0);
        const double u = float_parameter(ps, prefix + "uroughness", r), v = float_parameter(ps, prefix + "vroughness", r);
        const bool remap = ps.boolean("remaproughness", remap_default);
        if (u < 0.0 || v < 0.0) fail(at, "a roughness must be at least 0");
        if (u != v) note(at, "anisotropic roughness (" + reader_number(u) + ", " + reader_number(v) + ") approximated by its mean: iris's GGX is isotropic");
        const double x = 0.5 * (u + v);
        const double alpha = remap ? std::sqrt(x) : x;  // pbrt-v4's RoughnessToAlpha: √roughness
        if (!(alpha <= 1.0)) fail(at, "a GGX α above 1 (" + reader_number(alpha) + ") is not supported");
        return static_cast<float>(alpha);
    }

    std::uint32_t material(const std::string& type, parameters& ps, const std::string& name, const location& at) {
        auto reflectance = [&](const char* param, double fallback) {
            auto s = spectrum(ps, param, spectrum_use::albedo);
            if (!s) return tabulate([&](double) { return fallback; }, outside::clamp);
            check_reflectance(s->table, at, param);
            return s->table;
        };
        // pbrt-v4's layered materials: the coat's index, roughness and layer (docs/pbrt-import.md)
        auto coat = [&](material::coated c, const std::string& prefix) {
            c.roughness = roughness(ps, true, at, prefix);
            const std::string eta_name = prefix + "eta";
            if (auto e = spectrum(ps, eta_name.c_str(), spectrum_use::unbounded)) {
                double v = e->constant ? *e->constant : e->table(550.0);
                if (!e->constant)
                    note(at, "material '" + name + "': the coat's spectral \"" + eta_name + "\" approximated by its value at 550 nm, " +
                                 reader_number(v) + " (iris's coats have a constant index)");
                if (v == 0.0) v = 1.0;  // as pbrt-v4
                if (!(v >= 1.0 && v <= 4.0)) fail(at, "material '" + name + "': the coat's \"" + eta_name + "\" must lie in [1, 4], it is " + reader_number(v));
                c.eta = static_cast<float>(v);
            }
            const double thickness = float_parameter(ps, "thickness", 0.01);
            if (!(thickness >= 0.0 && thickness <= 1e3)) fail(at, "\"float thickness\" must lie in [0, 1000]");
            c.thickness = static_cast<float>(thickness);
            c.max_depth = ps.integer("maxdepth", 10);
            if (c.max_depth < 1 || c.max_depth > 100) fail(at, "\"integer maxdepth\" must lie in [1, 100] (iris's limit)");
            c.samples = ps.integer("nsamples", 1);
            if (c.samples < 1 || c.samples > 256) fail(at, "\"integer nsamples\" must lie in [1, 256]");
            if (auto a = spectrum(ps, "albedo", spectrum_use::albedo))
                for (double x : a->table.values())
                    if (x != 0.0) fail(at, "material '" + name + "': a scattering medium in the coat (\"albedo\" > 0) is not supported");
            const double g = float_parameter(ps, "g", 0.0);
            if (!(g >= -1.0 && g <= 1.0)) fail(at, "\"float g\" must lie in [-1, 1]");
            return c;
        };
        // a diffuse reflectance: a spectrum, or a texture (an image's index in the document)
        auto diffuse = [&]() {
            if (parameter* p = ps.find("reflectance"); p && p->type == "texture") {
                texture_result r = named_texture(ps.expect(*p, {"texture"}, 1).strings[0], "spectrum", p->at, spectrum_use::albedo);
                if (r.image) {
                    // the constant stands for the texture where one number is needed (the tools' summaries)
                    material::diffuse d{tabulate([](double) { return 0.5; }, outside::clamp)};
                    d.texture = add_texture(*r.image);
                    return d;
                }
                check_reflectance(r.constant->table, at, "reflectance");
                return material::diffuse{r.constant->table};
            }
            return material::diffuse{reflectance("reflectance", 0.5)};
        };
        material_desc m;
        if (type == "diffuse") {
            m = diffuse();
        } else if (type == "coateddiffuse") {
            m = coat(material::coated{diffuse()}, "");
        } else if (type == "dielectric" || type == "thindielectric") {
            if (type == "thindielectric") fail(at, "thindielectric is not supported yet (docs/pbrt-import.md)");
            material::dielectric d;
            if (auto e = spectrum(ps, "eta", spectrum_use::unbounded)) {
                if (e->constant) d.ior = constant_ior{*e->constant};
                else if (e->glass) d.ior = *e->glass;
                else d.ior = tabulated_ior{tabulated_spectrum(std::vector<double>(e->table.wavelengths().begin(), e->table.wavelengths().end()),
                                                              std::vector<double>(e->table.values().begin(), e->table.values().end()),
                                                              outside::clamp)};
            }
            for (double l = 360.0; l <= 830.0; l += 1.0) {
                const double n = refractive_index(d.ior, l);
                if (!(n >= 1.0 && n <= 10.0))
                    fail(at, "material '" + name + "': eta must lie in [1, 10] at 360-830 nm, it is " + reader_number(n) + " at " + reader_number(l) + " nm");
            }
            d.roughness = roughness(ps, true, at);
            m = d;
        } else if (type == "conductor" || type == "coatedconductor") {
            material::conductor c;
            const char* eta_name = type == "conductor" ? "eta" : "conductor.eta";
            const char* k_name = type == "conductor" ? "k" : "conductor.k";
            if (ps.find("reflectance") || ps.find("conductor.reflectance"))
                fail(at, "material '" + name + "': a conductor given by \"reflectance\" is not supported (give eta and k)");
            auto eta = spectrum(ps, eta_name, spectrum_use::unbounded);
            auto k = spectrum(ps, k_name, spectrum_use::unbounded);
            material::conductor_ior ior;
            ior.name = eta ? eta->name : "Cu";
            ior.eta = eta ? eta->table : find_metal("Cu")->eta_spectrum();  // pbrt-v4's default: copper
            ior.k = k ? k->table : find_metal("Cu")->k_spectrum();
            for (double l = 360.0; l <= 830.0; l += 1.0)
                if (!(ior.eta(l) > 0.0) || ior.k(l) < 0.0)
                    fail(at, "material '" + name + "': eta must be > 0 and k ≥ 0 at 360-830 nm");
            // its reflectance at normal incidence stands for it where one spectrum is needed (the tools)
            c.reflectance = tabulate(
                [&](double l) {
                    const double e = ior.eta(l), k2 = ior.k(l) * ior.k(l);
                    return ((e - 1.0) * (e - 1.0) + k2) / ((e + 1.0) * (e + 1.0) + k2);
                },
                outside::clamp);
            c.ior = std::move(ior);
            if (type == "coatedconductor") {
                c.roughness = roughness(ps, true, at, "conductor.");
                m = coat(material::coated{std::move(c)}, "interface.");
            } else {
                c.roughness = roughness(ps, true, at);
                m = c;
            }
        } else if (type == "interface" || type == "none" || type.empty()) {
            fail(at, "material \"" + type + "\" (a surface that only bounds a medium) is not supported yet: iris's media fill the "
                     "scene or a dielectric (docs/pbrt-import.md, \"Media\")");
        } else {
            fail(at, "material type '" + type + "' is not supported (iris: diffuse, dielectric, conductor, coateddiffuse, "
                     "coatedconductor)");
        }
        if (parameter* p = ps.find("displacement")) fail(p->at, "displacement is not supported");
        if (parameter* p = ps.find("normalmap")) fail(p->at, "normal maps are not supported");
        ps.find("type");
        ps.finish();
        m_doc.desc.materials.push_back(std::move(m));
        m_doc.desc.material_names.push_back(name);
        return static_cast<std::uint32_t>(m_doc.desc.materials.size() - 1);
    }

    std::uint32_t current_material() {
        if (m_state.material) return *m_state.material;
        if (!m_default_material) {
            m_doc.desc.materials.push_back(material::diffuse{tabulate([](double) { return 0.5; }, outside::clamp)});
            m_doc.desc.material_names.push_back("default-diffuse");
            m_default_material = static_cast<std::uint32_t>(m_doc.desc.materials.size() - 1);
        }
        return *m_default_material;
    }

    // -- lights
    void area_light(const token& t) {
        const std::string type = quoted(t.at, "the area light's type");
        auto ps = read_parameters("AreaLightSource \"" + type + "\"");
        if (type != "diffuse") fail(t.at, "AreaLightSource \"" + type + "\": only \"diffuse\" is supported");
        if (ps.find("filename")) fail(t.at, "an image on an area light is not supported");
        const double scale = light_scale(ps, t.at);
        const auto power = photometric(ps, "power", t.at);
        const bool two_sided = ps.boolean("twosided", false);
        auto l = spectrum(ps, "L", spectrum_use::illuminant);
        if (!l) {
            l = spectrum_value{};
            l->name = "D65";
            l->table = find_illuminant("D65")->spectrum();
        }
        ps.finish();
        if (power) {  // each shape its own emitter, normalised by its own area (`powered_emitter`)
            m_state.area_light.reset();
            m_state.area_power = std::make_shared<const graphics_state::powered_light>(
                graphics_state::powered_light{l->name, light_radiance(*l, scale, t.at), two_sided, *power});
            return;
        }
        m_state.area_power.reset();
        m_state.area_light = add_emitter(l->name, light_radiance(*l, scale, t.at), two_sided);
    }

    void light_source(const token& t) {
        const std::string type = quoted(t.at, "the light's type");
        auto ps = read_parameters("LightSource \"" + type + "\"");
        const double scale = light_scale(ps, t.at);
        const glm::dmat4 m = world(m_state.ctm);
        auto spd = [&](const char* name) {
            auto s = spectrum(ps, name, spectrum_use::illuminant);
            if (!s) {
                s = spectrum_value{};
                s->name = "D65";
                s->table = find_illuminant("D65")->spectrum();
            }
            return *s;
        };
        if (type == "point") {
            const auto s = spd("I");
            const auto power = photometric(ps, "power", t.at);  // pbrt-v4: I·φ/(4π)
            const glm::dvec3 from = ps.point("from", {0, 0, 0});
            ps.finish();
            const glm::vec3 at = light_point(m, from, t.at);
            const double k = power ? *power / (4.0 * std::numbers::pi) : 1.0;
            const auto e = add_emitter(s.name, light_radiance(s, scale * k, t.at), false);
            m_doc.desc.lights.push_back(light::point{at, e});
        } else if (type == "spot") {
            const auto s = spd("I");
            const glm::dvec3 from = ps.point("from", {0, 0, 0}), to = ps.point("to", {0, 0, 1});
            const double cone = ps.number("coneangle", 30.0), delta = ps.number("conedeltaangle", 5.0);
            const auto power = photometric(ps, "power", t.at);
            ps.finish();
            if (!(cone > 0.0 && cone <= 180.0) || !(delta >= 0.0 && delta < cone))
                fail(t.at, "a spot light needs 0 < coneangle <= 180 and 0 <= conedeltaangle < coneangle");
            const glm::vec3 p = light_point(m, from, t.at), q = light_point(m, to, t.at);
            double k = 1.0;
            if (power) {  // pbrt-v4's k_e: the cone's solid angle, its falloff band counted half
                const double c_end = std::cos(glm::radians(cone)), c_start = std::cos(glm::radians(cone - delta));
                k = *power / (2.0 * std::numbers::pi * ((1.0 - c_start) + (c_start - c_end) / 2.0));
            }
            const auto e = add_emitter(s.name, light_radiance(s, scale * k, t.at), false);
            light::spot l;
            l.position = p;
            l.direction = light_direction(glm::dvec3(q) - glm::dvec3(p), t.at, "a spot light");
            l.cos_total_width = static_cast<float>(std::cos(glm::radians(cone)));
            l.cos_falloff_start = static_cast<float>(std::cos(glm::radians(cone - delta)));
            if (!(l.cos_falloff_start < 1.0f) || !(l.cos_total_width > -1.0f))
                fail(t.at, "a spot light's cone is too narrow or too wide (0.01 < coneangle - conedeltaangle, coneangle < 180)");
            l.emitter = e;
            m_doc.desc.lights.push_back(l);
        } else if (type == "distant") {
            const auto s = spd("L");
            const auto illuminance = photometric(ps, "illuminance", t.at);  // pbrt-v4: L·E_v
            const glm::dvec3 from = ps.point("from", {0, 0, 0}), to = ps.point("to", {0, 0, 1});
            ps.finish();
            const glm::vec3 dir = light_direction(glm::dvec3(m * glm::dvec4(to - from, 0.0)), t.at, "a distant light");  // from → to
            const auto e = add_emitter(s.name, light_radiance(s, scale * illuminance.value_or(1.0), t.at), false);
            m_doc.desc.lights.push_back(light::distant{dir, e});
        } else if (type == "infinite") {
            if (ps.find("portal")) fail(t.at, "portals are not supported");
            if (m_doc.desc.environment) fail(t.at, "a second infinite light (iris has one environment)");
            const auto illuminance = photometric(ps, "illuminance", t.at);
            if (const std::string f = ps.string("filename", ""); !f.empty()) {
                if (ps.find("L")) fail(t.at, "an infinite light takes \"L\" or \"filename\", not both (as pbrt-v4)");
                ps.finish();
                environment_image(t, f, scale, m, illuminance);
                return;
            }
            const auto s = spd("L");
            ps.finish();
            // pbrt-v4: the illuminance of a uniform sky on an upward-facing patch is π·L
            const double k = illuminance ? *illuminance / std::numbers::pi : 1.0;
            m_doc.desc.environment = environment_desc{s.name, light_radiance(s, scale * k, t.at), std::nullopt, {}};
        } else {
            fail(t.at, "LightSource \"" + type + "\" is not supported (iris: point, spot, distant, infinite)");
        }
    }

    // -- shapes
    void shape(const token& t) {
        const std::string type = quoted(t.at, "the shape's type");
        auto ps = read_parameters("Shape \"" + type + "\"");
        shape_spec s;
        s.line = t.at.line;
        s.pointer = "";
        if (ps.find("alpha")) fail(t.at, "alpha (cut-out) shapes are not supported");
        if (type == "trianglemesh" || type == "bilinearmesh" || type == "loopsubdiv") {
            auto mesh = std::make_shared<iris::triangle_mesh>();
            parameter* p = ps.find("P");
            if (!p) fail(t.at, "Shape \"" + type + "\" has no \"point3 P\"");
            const auto& pv = ps.expect(*p, {"point3", "point"}, 0).numbers;
            if (pv.size() % 3 != 0 || pv.empty()) fail(p->at, "\"point3 P\" needs x y z triples");
            for (std::size_t i = 0; i < pv.size(); i += 3) {
                for (std::size_t k = 0; k < 3; ++k)
                    if (std::fabs(pv[i + k]) > max_coordinate) fail(p->at, "a coordinate beyond ±1e7");
                mesh->positions.emplace_back(pv[i], pv[i + 1], pv[i + 2]);
            }
            const std::size_t n = mesh->positions.size(), per = type == "bilinearmesh" ? 4 : 3;
            std::vector<double> idx;
            if (parameter* q = ps.find("indices")) idx = ps.expect(*q, {"integer"}, 0).numbers;
            else if (n == per)
                for (std::size_t i = 0; i < per; ++i) idx.push_back(static_cast<double>(i));
            else fail(t.at, "Shape \"" + type + "\" has no \"integer indices\" (needed unless it has exactly " + std::to_string(per) + " points)");
            if (idx.empty() || idx.size() % per != 0) fail(t.at, "\"integer indices\" needs groups of " + std::to_string(per));
            for (double i : idx)
                if (i < 0 || i >= static_cast<double>(n) || i != std::floor(i))
                    fail(t.at, "an index (" + reader_number(i) + ") is not one of the " + std::to_string(n) + " points");
            auto u = [&](std::size_t i) { return static_cast<std::uint32_t>(idx[i]); };
            if (per == 3) {
                for (std::size_t i = 0; i < idx.size(); i += 3) mesh->triangles.push_back({u(i), u(i + 1), u(i + 2)});
            } else {
                // pbrt-v4's bilinear patch (p00, p10, p01, p11) as two triangles
                for (std::size_t i = 0; i < idx.size(); i += 4) {
                    mesh->triangles.push_back({u(i), u(i + 1), u(i + 3)});
                    mesh->triangles.push_back({u(i), u(i + 3), u(i + 2)});
                }
                note(t.at, "bilinearmesh: each patch split into two triangles (exact when it is planar)");
            }
            if (type == "loopsubdiv") {
                const int levels = ps.integer("levels", 3);
                if (levels < 0 || levels > 10) fail(t.at, "\"integer levels\" must lie in [0, 10]");
                if (static_cast<double>(mesh->triangles.size()) * std::pow(4.0, levels) > static_cast<double>(max_triangles))
                    fail(t.at, "loopsubdiv: " + std::to_string(levels) + " levels would make more than 2^28 triangles: refused");
                if (ps.string("scheme", "loop") != "loop") fail(t.at, "loopsubdiv: the only scheme is \"loop\"");
                s.levels = levels;  // subdivided when the scene is built (iris::geometry::loop_subdivide)
            }
            if (parameter* q = type == "loopsubdiv" ? nullptr : ps.find("N")) {
                const auto& nv = ps.expect(*q, {"normal", "normal3"}, 3 * n).numbers;
                for (std::size_t i = 0; i < nv.size(); i += 3) mesh->normals.emplace_back(nv[i], nv[i + 1], nv[i + 2]);
                // pbrt-v4 turns a triangle's geometric normal toward its shading normals, iris keeps
                // the winding's: say where they disagree (the inside of glass, the side a light emits)
                std::size_t against = 0;
                for (const auto& tri : mesh->triangles) {
                    const auto& P = mesh->positions;
                    const glm::vec3 ng = glm::cross(P[tri[1]] - P[tri[0]], P[tri[2]] - P[tri[0]]);
                    const glm::vec3 ns = mesh->normals[tri[0]] + mesh->normals[tri[1]] + mesh->normals[tri[2]];
                    against += glm::dot(ng, ns) < 0.0f;
                }
                if (against > 0)
                    note(q->at, std::to_string(against) + " of " + std::to_string(mesh->triangles.size()) +
                                    " triangles wind against their \"normal N\": pbrt-v4 orients them by N, iris by the winding");
            }
            if (parameter* q = type == "loopsubdiv" ? nullptr : ps.find("uv")) {
                const auto& uv = ps.expect(*q, {"point2", "float"}, 2 * n).numbers;
                for (std::size_t i = 0; i < uv.size(); i += 2) mesh->uvs.emplace_back(uv[i], uv[i + 1]);
            }
            if (parameter* q = type == "loopsubdiv" ? nullptr : ps.find("S")) note(q->at, "\"vector3 S\" (tangents) ignored");
            if (parameter* q = type == "loopsubdiv" ? nullptr : ps.find("faceIndices")) note(q->at, "\"integer faceIndices\" ignored", false);
            s.type = type == "loopsubdiv" ? shape_type::subdivision : shape_type::triangles;
            s.triangles = std::move(mesh);
        } else if (type == "plymesh") {
            const std::string f = ps.string("filename", "");
            if (f.empty()) fail(t.at, "Shape \"plymesh\" has no \"string filename\"");
            if (ps.find("displacement") || ps.find("edgelength")) fail(t.at, "displaced meshes are not supported");
            const std::filesystem::path p = resolve(f);
            s.type = shape_type::mesh;
            s.file = p;
        } else if (type == "sphere") {
            const double r = ps.number("radius", 1.0);
            if (!(r > 0.0 && r < max_coordinate)) fail(t.at, "a sphere's radius must be > 0");
            if (ps.number("zmin", -r) != -r || ps.number("zmax", r) != r || ps.number("phimax", 360.0) != 360.0)
                fail(t.at, "partial spheres (zmin, zmax, phimax) are not supported");
            s.type = shape_type::sphere;
            s.size = glm::vec3(static_cast<float>(r), 0.0f, 0.0f);
            note(t.at, "sphere tessellated into 36 480 triangles", false);
        } else if (type == "disk") {
            const double r = ps.number("radius", 1.0), inner = ps.number("innerradius", 0.0), h = ps.number("height", 0.0);
            if (!(r > 0.0) || !(inner >= 0.0 && inner < r)) fail(t.at, "a disk needs radius > innerradius ≥ 0");
            if (ps.number("phimax", 360.0) != 360.0) fail(t.at, "partial disks (phimax) are not supported");
            s.type = shape_type::disk;
            s.size = glm::vec3(static_cast<float>(r), static_cast<float>(inner), static_cast<float>(h));
            note(t.at, "disk tessellated into 192 segments", false);
        } else {
            fail(t.at, "Shape \"" + type + "\" is not supported (iris: trianglemesh, plymesh, loopsubdiv, sphere, disk, bilinearmesh)");
        }
        ps.finish();
        s.material = current_material();
        if (s.type == shape_type::sphere || s.type == shape_type::disk)
            if (const auto* d = diffuse_part(m_doc.desc.materials[s.material]); d && d->texture)
                fail(t.at, "a textured material on a " + type + ": iris tessellates spheres and disks without pbrt-v4's (phi, theta) "
                           "texture coordinates");
        if (m_state.area_light) s.emitter = m_state.area_light;
        if (m_state.area_power) s.emitter = powered_emitter(s, type, t.at);
        s.name = type + "." + std::to_string(m_doc.shapes.size());
        s.file_name = t.at.file;
        // pbrt-v4's normal is the object-space winding's, carried by the transform as a normal
        // and turned by ReverseOrientation (its handedness rule undoes the turn a mirroring
        // transform gives the winding); iris's `transformed` keeps the winding outward under a
        // mirror the same way, the pbrt-to-iris mirror included: flip exactly when reversed
        s.flip = m_state.reverse_orientation;
        if (m_object) {
            s.transform = glm::mat4(m_state.ctm);
            if (s.emitter) fail(t.at, "an area light inside ObjectBegin is not supported");
            m_objects[*m_object].push_back(std::move(s));
            m_object_media[*m_object].push_back({m_state.inside_medium, m_state.outside_medium, t.at});
            return;
        }
        s.transform = glm::mat4(world(m_state.ctm));
        add_shape(std::move(s), {m_state.inside_medium, m_state.outside_medium, t.at}, t.at);
    }

    /// The emitter of one shape under an AreaLightSource with "power" φ: pbrt-v4 gives each shape
    /// (each triangle of a mesh, a whole sphere or disk) radiance scale·S/Y(S)·φ/(π·A·sides), A
    /// its area (a sphere's and a disk's in object space, as pbrt-v4's Area()); iris's emitter
    /// has one radiance, so a mesh's triangles must have equal areas.
    std::uint32_t powered_emitter(const shape_spec& s, const std::string& type, const location& at) {
        const auto& l = *m_state.area_power;
        double area = 0.0;
        if (s.type == shape_type::sphere) {
            area = 4.0 * std::numbers::pi * double(s.size.x) * double(s.size.x);
        } else if (s.type == shape_type::disk) {
            area = std::numbers::pi * (double(s.size.x) * double(s.size.x) - double(s.size.y) * double(s.size.y));
        } else if (s.type == shape_type::triangles && type == "trianglemesh") {
            const glm::dmat4 w = world(m_state.ctm);
            double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
            for (const auto& tri : s.triangles->triangles) {
                glm::dvec3 p[3];
                for (int i = 0; i < 3; ++i) p[i] = glm::dvec3(w * glm::dvec4(glm::dvec3(s.triangles->positions[tri[static_cast<std::size_t>(i)]]), 1.0));
                const double a = 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
                lo = std::min(lo, a);
                hi = std::max(hi, a);
            }
            if (!(hi - lo <= 1e-4 * hi))
                fail(at, "an area light with \"power\" on a trianglemesh whose triangles differ in area: pbrt-v4 gives each "
                         "triangle that power (radiance φ/(π·A·sides) of its own area), iris's emitter has one radiance");
            area = hi;
        } else {
            fail(at, "an area light with \"power\" on a " + type + " is not supported (iris: trianglemesh with triangles of "
                     "equal area, sphere, disk)");
        }
        if (!(area > 0.0)) fail(at, "an area light with \"power\" on a shape of zero area");
        const double k = l.power / (std::numbers::pi * area * (l.two_sided ? 2.0 : 1.0));
        return add_emitter(l.name, light_radiance(spectrum_value{l.name, l.radiance, true, std::nullopt, std::nullopt}, k, at), l.two_sided);
    }

    /// The triangles a shape will have (a PLY file's are not known yet: 0).
    static std::size_t triangle_count(const shape_spec& s) {
        switch (s.type) {
            case shape_type::triangles: return s.triangles ? s.triangles->triangles.size() : 0;
            case shape_type::subdivision:
                return s.triangles ? s.triangles->triangles.size() << (2 * s.levels) : 0;
            case shape_type::sphere: return 36480;
            case shape_type::disk: return s.size.y > 0.0f ? 384 : 192;
            default: return 0;
        }
    }
    /// `at`: the directive that adds it (a Shape, or the ObjectInstance of an object's shape).
    void add_shape(shape_spec s, shape_media media, const location& at) {
        m_triangles += triangle_count(s);
        if (m_triangles > max_triangles) fail(at, "the scene would have more than 2^28 triangles: refused");
        m_doc.shapes.push_back(std::move(s));
        m_shape_media.push_back(std::move(media));
    }

    // -- media (docs/pbrt-import.md, "Media")
    /// `MakeNamedMedium "name" "string type" "homogeneous"`: σ_a, σ_s (unbounded spectra, pbrt-v4's
    /// default 1 each) times "scale", Henyey–Greenstein "g".
    void named_medium(const token& t) {
        const std::string n = quoted(t.at, "the medium's name");
        if (n.empty()) fail(t.at, "MakeNamedMedium: the name \"\" means no medium and cannot be defined");
        if (m_media.count(n)) fail(t.at, "medium '" + n + "' is defined twice");
        auto ps = read_parameters("MakeNamedMedium \"" + n + "\"");
        parameter* type = ps.find("type");
        if (!type) fail(t.at, "MakeNamedMedium \"" + n + "\" has no \"string type\"");
        const std::string ty = ps.expect(*type, {"string"}, 1).strings[0];
        if (ty != "homogeneous")
            fail(type->at, "medium type '" + ty + "' is not supported (iris: homogeneous; density grids are not yet, docs/pbrt-import.md)");
        if (parameter* p = ps.find("preset"))
            fail(p->at, "medium '" + n + "': \"preset\" (pbrt-v4's measured media) is not supported: give sigma_a and sigma_s");
        const double scale = ps.number("scale", 1.0);
        if (!(scale >= 0.0 && scale <= 1e9)) fail(t.at, "medium '" + n + "': \"float scale\" must lie in [0, 1e9]");
        auto coefficient = [&](const char* name) {
            auto v = spectrum(ps, name, spectrum_use::unbounded);
            tabulated_spectrum table = v ? v->table.scaled(scale) : tabulate([&](double) { return scale; }, outside::clamp);
            for (double x : table.values())
                if (!(x >= 0.0 && x <= 1e9))
                    fail(v ? ps.find(name)->at : t.at, "medium '" + n + "': \"" + std::string(name) + "\" times scale must lie in [0, 1e9] (1/scene unit)");
            return table;
        };
        medium_desc m;
        tabulated_spectrum sigma_a = coefficient("sigma_a"), sigma_s = coefficient("sigma_s");
        const double g = ps.number("g", 0.0);
        if (!(g >= -0.99 && g <= 0.99)) fail(t.at, "medium '" + n + "': \"float g\" must lie in [-0.99, 0.99] (iris's Henyey-Greenstein)");
        auto any = [](const tabulated_spectrum& s) {
            for (double x : s.values())
                if (x > 0.0) return true;
            return false;
        };
        if (any(sigma_a)) m.absorption = std::move(sigma_a);
        if (any(sigma_s)) m.scattering = medium_scattering{std::move(sigma_s), static_cast<float>(g)};
        if (auto le = spectrum(ps, "Le", spectrum_use::illuminant); le && any(le->table))
            fail(ps.find("Le")->at, "medium '" + n + "': emissive media (\"Le\") are not supported");
        ps.number("Lescale", 1.0);
        ps.finish();
        m_media[n] = {std::move(m), t.at};
    }

    const medium_desc* find_medium(const std::string& n, const location& at, const std::string& where) {
        if (n.empty()) return nullptr;
        const auto it = m_media.find(n);
        if (it == m_media.end()) fail(at, where + " names medium '" + n + "', which no MakeNamedMedium defines");
        return &it->second.desc;
    }

    /// pbrt-v4's media onto iris's model (docs/method.md §10): one medium outside the solids —
    /// the camera's — and a dielectric's own medium inside it. A shape whose two sides name the
    /// same medium is no boundary (pbrt-v4 keeps the ray's medium there), so such a glass is
    /// filled with the camera's medium (`build_scene` then needs no closed solid around it).
    void resolve_media() {
        const medium_desc* outside = find_medium(m_camera_medium, m_camera_at, "the camera (its MediumInterface)");
        if (outside) m_doc.desc.medium = *outside;
        std::map<std::pair<std::uint32_t, std::string>, std::uint32_t> filled;  // (material, medium) → material
        std::set<std::string> opaque_noted;
        for (std::size_t i = 0; i < m_doc.shapes.size(); ++i) {
            const shape_media& sm = m_shape_media[i];
            const bool boundary = sm.inside != sm.outside;
            find_medium(sm.outside, sm.at, "the shape's MediumInterface");
            find_medium(sm.inside, sm.at, "the shape's MediumInterface");
            if (boundary && sm.outside != m_camera_medium)
                fail(sm.at, "the shape's outside medium is '" + sm.outside + "' but the camera's is '" + m_camera_medium +
                                "': iris has one medium outside the solids (docs/pbrt-import.md, \"Media\")");
            shape_spec& s = m_doc.shapes[i];
            const bool glass = std::holds_alternative<material::dielectric>(m_doc.desc.materials[s.material]);
            if (!glass) {
                // an empty inside is pbrt-v4's usual "" "fog": nothing there to model
                if (boundary && !sm.inside.empty() && opaque_noted.insert(sm.inside).second)
                    note(sm.at, "the inside medium '" + sm.inside + "' of an opaque shape is not modelled: iris's rays never pass an opaque "
                                "surface (pbrt-v4 sends the rays leaving its back face into it)");
                continue;
            }
            const std::string inside = boundary ? sm.inside : m_camera_medium;
            if (inside.empty()) continue;
            const auto key = std::make_pair(s.material, inside);
            if (auto it = filled.find(key); it != filled.end()) {
                s.material = it->second;
                continue;
            }
            material::dielectric d = std::get<material::dielectric>(m_doc.desc.materials[s.material]);
            const medium_desc& m = *find_medium(inside, sm.at, "the shape's MediumInterface");
            d.absorption = m.absorption;
            d.scattering = m.scattering;
            m_doc.desc.materials.push_back(std::move(d));
            m_doc.desc.material_names.push_back(m_doc.desc.material_names[s.material] + "+" + inside);
            s.material = filled[key] = static_cast<std::uint32_t>(m_doc.desc.materials.size() - 1);
        }
    }

    pbrt_import_options m_options;
    scene_document m_doc;
    std::vector<tokenizer> m_files;
    struct import_entry {
        std::size_t files = 0, stack = 0;  ///< the file stack's size without it; the stack's with its entry
        bool ended = false;                ///< its file has been read to the end
        location at;                       ///< where it ended
    };
    std::vector<import_entry> m_imports;
    location m_last;          ///< the last token read (where the input ended, for messages)
    std::size_t m_included = 0, m_included_bytes = 0;  ///< every file read, for the budget
    std::filesystem::path m_base;  ///< the main file's directory: relative paths resolve here (pbrt-v4's rule)
    std::size_t m_triangles = 0;   ///< the triangles the shapes will have, for the budget
    std::optional<token> m_peeked;
    location m_end;
    graphics_state m_state;
    /// What opened a stack entry: AttributeBegin (and TransformBegin, which pbrt-v4 reads as
    /// it), ObjectBegin, or an Import (whose state changes stay inside the imported file).
    enum class opened { attribute, object, import };
    struct stack_entry {
        graphics_state state;
        location at;
        opened kind = opened::attribute;
    };
    std::vector<stack_entry> m_stack;
    std::map<std::string, glm::dmat4> m_coordinate_systems;
    std::map<std::string, std::uint32_t> m_named_materials;
    std::map<std::pair<std::string, std::string>, texture_def> m_textures;  ///< by (kind, name)
    int m_texture_depth = 0;  ///< the nesting of `named_texture` calls
    std::map<std::string, std::vector<shape_spec>> m_objects;
    std::map<std::string, std::vector<shape_media>> m_object_media;  ///< per object, its shapes' media
    std::vector<shape_media> m_shape_media;                          ///< per shape of m_doc
    struct medium_def {
        medium_desc desc;
        location at;
    };
    std::map<std::string, medium_def> m_media;
    std::string m_camera_medium;
    std::optional<std::string> m_object;
    location m_object_at, m_camera_at;
    std::optional<std::uint32_t> m_default_material;
    glm::dmat4 m_camera_from_world{1.0};
    glm::dmat4 m_mirror{1.0};
    double m_fov = 90.0;
    double m_exposure_time = 1.0, m_iso = 100.0;  ///< pbrt-v4's imaging ratio (`imaging_ratio`)
    location m_iso_at;
    bool m_world = false;
    bool m_filter_given = false;
    std::vector<std::string> m_notes;
};

}  // namespace

scene_document parse_pbrt_document(std::string_view text, const std::string& source_name,
                                   const std::filesystem::path& base_dir, const pbrt_import_options& options) {
    importer imp(source_name, options);
    return imp.run(std::string(text), source_name, base_dir);
}

}  // namespace iris::scene
