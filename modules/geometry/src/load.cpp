// load_mesh: .obj through tinyobjloader, .off and .ply through the small strict readers
// below. CGAL's OFF/PLY readers were the other candidate; they size their arrays from the
// header counts before reading (a corrupt count exhausts memory) and report only a bool,
// so a broken file could neither fail safely nor say what is wrong. These readers grow as
// they read, check every bound and name the line (text) or element (binary) at fault.
#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/geometric.hpp>
#include <tiny_obj_loader.h>
#include "iris/gzip.hpp"

#include "iris/geometry/triangle_mesh.hpp"

namespace iris::geometry {
namespace {

namespace fs = std::filesystem;

// A polygon soup as read, before triangulation and validation. The polygons' vertex
// indices are stored one after another (polygon f is indices[ends[f − 1], ends[f])): a
// vector per polygon cost 10 M heap blocks and ~0.7 GB for a 10 M-triangle mesh.
struct soup {
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> normals;  ///< empty, or one per position
    std::vector<glm::dvec2> uvs;      ///< empty, or one per position
    std::vector<long long> indices;
    std::vector<std::size_t> ends;

    void add_polygon(const std::vector<long long>& p) {
        indices.insert(indices.end(), p.begin(), p.end());
        ends.push_back(indices.size());
    }
};

[[noreturn]] void fail(const fs::path& path, const std::string& what) {
    throw error("load_mesh: '" + path.string() + "': " + what);
}

std::string read_file(const fs::path& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) fail(path, "no such file");
    if (fs::is_directory(path, ec)) fail(path, "is a directory, not a mesh file");
    const auto size = fs::file_size(path, ec);
    if (ec) fail(path, "cannot determine the file size (" + ec.message() + ")");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open the file for reading");
    std::string bytes(static_cast<std::size_t>(size), '\0');
    if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) fail(path, "read error");
    return bytes;
}

// ---- text helpers ---------------------------------------------------------------------

// Splits text into lines (LF or CRLF) and lines into whitespace-separated tokens.
class line_reader {
public:
    explicit line_reader(std::string_view text) : m_text(text) {}

    // The next line with `#` comments removed that has at least one token; false at the end.
    bool next(std::vector<std::string_view>& tokens) {
        while (m_pos < m_text.size()) {
            const std::size_t end = std::min(m_text.find('\n', m_pos), m_text.size());
            std::string_view line = m_text.substr(m_pos, end - m_pos);
            m_pos = end + 1;
            ++m_line;
            if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
            split(line, tokens);
            if (!tokens.empty()) return true;
        }
        return false;
    }
    std::size_t line() const noexcept { return m_line; }
    // Everything after the current line (for binary PLY bodies).
    std::string_view rest() const noexcept { return m_pos < m_text.size() ? m_text.substr(m_pos) : std::string_view{}; }

    static void split(std::string_view line, std::vector<std::string_view>& tokens) {
        tokens.clear();
        std::size_t i = 0;
        while (i < line.size()) {
            while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
            const std::size_t start = i;
            while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
            if (i > start) tokens.push_back(line.substr(start, i - start));
        }
    }

private:
    std::string_view m_text;
    std::size_t m_pos = 0;
    std::size_t m_line = 0;
};

std::optional<double> to_double(std::string_view s) {
    double v = 0.0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc{} || end != s.data() + s.size()) return std::nullopt;
    return v;
}

std::optional<long long> to_integer(std::string_view s) {
    long long v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc{} || end != s.data() + s.size()) return std::nullopt;
    return v;
}

std::string at_line(std::size_t line) { return "line " + std::to_string(line) + ": "; }

// ---- OFF --------------------------------------------------------------------------------

soup read_off(const fs::path& path, std::string_view text) {
    line_reader lines(text);
    std::vector<std::string_view> tok;
    if (!lines.next(tok)) fail(path, "empty file (expected an OFF header)");
    // OFF with optional prefixes for texture (ST), colour (C) and normal (N) data, which
    // follow x y z on each vertex line. Colours are not used (materials are the scene's);
    // normals and texture coordinates would be, so a file that has them is refused rather
    // than rendered without them (PLY and OBJ carry them: docs/scene-format.md).
    const std::string_view key = tok[0];
    const std::string_view prefix = key.size() >= 3 ? key.substr(0, key.size() - 3) : std::string_view{};
    const bool off_key = key.size() >= 3 && key.substr(key.size() - 3) == "OFF" &&
                         prefix.find_first_not_of("STCN") == std::string_view::npos;
    if (!off_key) fail(path, at_line(lines.line()) + "expected the OFF header keyword, got '" + std::string(key) + "'");
    if (prefix.find_first_of("STN") != std::string_view::npos)
        fail(path, at_line(lines.line()) + "'" + std::string(key) +
                       "': the normals and texture coordinates of OFF files are not read; use PLY or OBJ for them "
                       "(or plain OFF / COFF without them)");
    if (tok.size() > 1 && tok[1] == "BINARY") fail(path, "binary OFF is not supported (use ASCII OFF or PLY)");
    std::vector<std::string_view> counts(tok.begin() + 1, tok.end());
    if (counts.empty()) {
        if (!lines.next(tok)) fail(path, "missing the vertex and face counts after the header");
        counts = tok;
    }
    const auto nv = counts.size() >= 2 ? to_integer(counts[0]) : std::nullopt;
    const auto nf = counts.size() >= 2 ? to_integer(counts[1]) : std::nullopt;
    if (!nv || !nf || *nv < 0 || *nf < 0)
        fail(path, at_line(lines.line()) + "expected the counts 'vertices faces [edges]' as non-negative integers");
    soup s;
    for (long long i = 0; i < *nv; ++i) {
        if (!lines.next(tok))
            fail(path, "unexpected end of file after " + std::to_string(i) + " of " + std::to_string(*nv) + " vertices");
        if (tok.size() < 3) fail(path, at_line(lines.line()) + "a vertex needs x y z");
        glm::dvec3 p;
        for (int k = 0; k < 3; ++k) {
            const auto v = to_double(tok[static_cast<std::size_t>(k)]);
            if (!v) fail(path, at_line(lines.line()) + "'" + std::string(tok[static_cast<std::size_t>(k)]) + "' is not a number");
            p[k] = *v;
        }
        s.positions.push_back(p);
    }
    for (long long f = 0; f < *nf; ++f) {
        if (!lines.next(tok))
            fail(path, "unexpected end of file after " + std::to_string(f) + " of " + std::to_string(*nf) + " faces");
        const auto n = to_integer(tok[0]);
        if (!n || *n < 0) fail(path, at_line(lines.line()) + "a face starts with its vertex count");
        if (static_cast<std::size_t>(*n) + 1 > tok.size())
            fail(path, at_line(lines.line()) + "the face announces " + std::to_string(*n) + " vertices but lists fewer");
        std::vector<long long> poly;
        for (std::size_t k = 1; k <= static_cast<std::size_t>(*n); ++k) {
            const auto idx = to_integer(tok[k]);
            if (!idx) fail(path, at_line(lines.line()) + "'" + std::string(tok[k]) + "' is not a vertex index");
            poly.push_back(*idx);
        }
        s.add_polygon(poly);
    }
    return s;
}

// ---- PLY --------------------------------------------------------------------------------

enum class ply_type { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

std::optional<ply_type> parse_ply_type(std::string_view s) {
    if (s == "char" || s == "int8") return ply_type::int8;
    if (s == "uchar" || s == "uint8") return ply_type::uint8;
    if (s == "short" || s == "int16") return ply_type::int16;
    if (s == "ushort" || s == "uint16") return ply_type::uint16;
    if (s == "int" || s == "int32") return ply_type::int32;
    if (s == "uint" || s == "uint32") return ply_type::uint32;
    if (s == "float" || s == "float32") return ply_type::float32;
    if (s == "double" || s == "float64") return ply_type::float64;
    return std::nullopt;
}

std::size_t ply_size(ply_type t) {
    switch (t) {
    case ply_type::int8:
    case ply_type::uint8: return 1;
    case ply_type::int16:
    case ply_type::uint16: return 2;
    case ply_type::int32:
    case ply_type::uint32:
    case ply_type::float32: return 4;
    case ply_type::float64: return 8;
    }
    return 1;
}

struct ply_property {
    std::string name;
    ply_type type = ply_type::float32;
    bool is_list = false;
    ply_type count_type = ply_type::uint8;
};

struct ply_element {
    std::string name;
    unsigned long long count = 0;
    std::vector<ply_property> properties;
};

// Reads PLY values either from ASCII tokens (one element per line) or from binary bytes.
class ply_values {
public:
    ply_values(const fs::path& path, std::string_view body, bool ascii, bool big_endian)
        : m_path(path), m_lines(body), m_bytes(body), m_ascii(ascii), m_big_endian(big_endian) {}

    // Start the next element instance (ASCII: the next non-empty line).
    void begin_item(const std::string& element, unsigned long long index) {
        m_element = &element;  // the message is built only on failure (10 M items: no 10 M strings)
        m_index = index;
        if (m_ascii) {
            if (!m_lines.next(m_tokens)) fail(m_path, "unexpected end of file in " + where());
            m_token = 0;
        }
    }
    std::string where() const { return "element '" + *m_element + "' #" + std::to_string(m_index); }
    // ASCII: the line must hold exactly the element's values.
    void end_item() {
        if (m_ascii && m_token != m_tokens.size())
            fail(m_path, at_line(m_header_lines + m_lines.line()) + "too many values in " + where());
    }

    double read(ply_type t) {
        if (m_ascii) {
            if (m_token >= m_tokens.size())
                fail(m_path, at_line(m_header_lines + m_lines.line()) + "too few values in " + where());
            const std::string_view s = m_tokens[m_token++];
            const auto v = to_double(s);
            if (!v) fail(m_path, at_line(m_header_lines + m_lines.line()) + "'" + std::string(s) + "' is not a number");
            return *v;
        }
        const std::size_t n = ply_size(t);
        if (m_offset + n > m_bytes.size()) fail(m_path, "unexpected end of file in " + where());
        unsigned char b[8];
        std::memcpy(b, m_bytes.data() + m_offset, n);
        m_offset += n;
        if (m_big_endian != (std::endian::native == std::endian::big)) std::reverse(b, b + n);
        return decode(t, b);
    }

    void set_header_lines(std::size_t n) noexcept { m_header_lines = n; }

private:
    static double decode(ply_type t, const unsigned char* b) {
        switch (t) {
        case ply_type::int8: { std::int8_t v; std::memcpy(&v, b, 1); return v; }
        case ply_type::uint8: return b[0];
        case ply_type::int16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
        case ply_type::uint16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
        case ply_type::int32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
        case ply_type::uint32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
        case ply_type::float32: { float v; std::memcpy(&v, b, 4); return static_cast<double>(v); }
        case ply_type::float64: { double v; std::memcpy(&v, b, 8); return v; }
        }
        return 0.0;
    }

    const fs::path& m_path;
    line_reader m_lines;
    std::string_view m_bytes;
    bool m_ascii;
    bool m_big_endian;
    std::size_t m_offset = 0;
    std::vector<std::string_view> m_tokens;
    std::size_t m_token = 0;
    std::size_t m_header_lines = 0;
    const std::string* m_element = nullptr;
    unsigned long long m_index = 0;
};

soup read_ply(const fs::path& path, std::string_view text) {
    // Header: text lines up to `end_header`. The body starts right after that line.
    line_reader header(text);
    std::vector<std::string_view> tok;
    if (!header.next(tok) || tok[0] != "ply") fail(path, "not a PLY file (the first line must be 'ply')");
    std::optional<bool> ascii;
    bool big_endian = false;
    std::vector<ply_element> elements;
    bool ended = false;
    while (header.next(tok)) {
        const std::string_view key = tok[0];
        const std::string where = at_line(header.line());
        if (key == "format") {
            if (tok.size() < 3 || tok[2] != "1.0") fail(path, where + "expected 'format <encoding> 1.0'");
            if (tok[1] == "ascii") {
                ascii = true;
            } else if (tok[1] == "binary_little_endian" || tok[1] == "binary_big_endian") {
                ascii = false;
                big_endian = tok[1] == "binary_big_endian";
            } else {
                fail(path, where + "unknown PLY format '" + std::string(tok[1]) + "'");
            }
        } else if (key == "comment" || key == "obj_info") {
        } else if (key == "element") {
            const auto n = tok.size() == 3 ? to_integer(tok[2]) : std::nullopt;
            if (!n || *n < 0) fail(path, where + "expected 'element <name> <count>'");
            elements.push_back({std::string(tok[1]), static_cast<unsigned long long>(*n), {}});
        } else if (key == "property") {
            if (elements.empty()) fail(path, where + "a property before any element");
            ply_property p;
            if (tok.size() == 5 && tok[1] == "list") {
                const auto ct = parse_ply_type(tok[2]);
                const auto it = parse_ply_type(tok[3]);
                if (!ct || !it || *ct == ply_type::float32 || *ct == ply_type::float64)
                    fail(path, where + "expected 'property list <integer type> <type> <name>'");
                p = {std::string(tok[4]), *it, true, *ct};
            } else if (tok.size() == 3) {
                const auto t = parse_ply_type(tok[1]);
                if (!t) fail(path, where + "unknown property type '" + std::string(tok[1]) + "'");
                p = {std::string(tok[2]), *t, false, ply_type::uint8};
            } else {
                fail(path, where + "expected 'property <type> <name>' or 'property list <count type> <type> <name>'");
            }
            elements.back().properties.push_back(std::move(p));
        } else if (key == "end_header") {
            ended = true;
            break;
        } else {
            fail(path, where + "unknown header keyword '" + std::string(key) + "'");
        }
    }
    if (!ended) fail(path, "the header has no 'end_header'");
    if (!ascii) fail(path, "the header has no 'format' line");

    ply_values values(path, header.rest(), *ascii, big_endian);
    values.set_header_lines(header.line());
    soup s;
    bool have_vertices = false, have_faces = false;
    for (const ply_element& e : elements) {
        const bool is_vertex = e.name == "vertex";
        const bool is_face = e.name == "face";
        int xyz[3] = {-1, -1, -1}, normal[3] = {-1, -1, -1}, uv[2] = {-1, -1};
        int indices = -1;
        // the names of texture coordinates in the wild: u v (pbrt-v4's writer), s t, texture_u/v, texture_s/t
        static constexpr const char* uv_names[4][2] = {{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
        for (std::size_t k = 0; k < e.properties.size(); ++k) {
            const auto& p = e.properties[k];
            const auto at = static_cast<int>(k);
            if (is_vertex && !p.is_list) {
                for (int c = 0; c < 3; ++c) {
                    if (p.name == std::string(1, static_cast<char>('x' + c))) xyz[c] = at;
                    if (p.name == "n" + std::string(1, static_cast<char>('x' + c))) normal[c] = at;
                }
                for (const auto& names : uv_names)
                    for (int c = 0; c < 2; ++c)
                        if (p.name == names[c]) {
                            if (uv[c] >= 0)
                                fail(path, "the 'vertex' element has two texture coordinates for " + std::string(c ? "v" : "u") +
                                               " ('" + e.properties[static_cast<std::size_t>(uv[c])].name + "' and '" + p.name + "')");
                            uv[c] = at;
                        }
            }
            if (is_face && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) indices = static_cast<int>(k);
        }
        if (is_vertex && (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)) fail(path, "the 'vertex' element lacks x, y or z");
        const bool has_normal = normal[0] >= 0 || normal[1] >= 0 || normal[2] >= 0;
        if (has_normal && (normal[0] < 0 || normal[1] < 0 || normal[2] < 0))
            fail(path, "the 'vertex' element has some of the normal's nx, ny, nz but not all three");
        const bool has_uv = uv[0] >= 0 || uv[1] >= 0;
        if (has_uv && (uv[0] < 0 || uv[1] < 0))
            fail(path, "the 'vertex' element has one texture coordinate ('" +
                           e.properties[static_cast<std::size_t>(uv[0] >= 0 ? uv[0] : uv[1])].name + "') without the other");
        if (is_face && indices < 0) fail(path, "the 'face' element lacks a 'vertex_indices' list");
        have_vertices = have_vertices || is_vertex;
        have_faces = have_faces || is_face;
        std::vector<long long> poly;  // one face's indices, reused
        // No reserve(e.count): a corrupt count must fail at the end of the data, not allocate.
        // An element without properties holds no data: in a binary file its instances take
        // no bytes, so a corrupt count would loop without ever reaching the end (found by
        // fuzz_mesh_ply: 444 444 444 of them, a minute of nothing). Refused.
        if (e.properties.empty() && e.count > 0)
            fail(path, "element '" + e.name + "' has " + std::to_string(e.count) + " instances but no properties");
        for (unsigned long long i = 0; i < e.count; ++i) {
            values.begin_item(e.name, i);
            glm::dvec3 p(0.0), nrm(0.0);
            glm::dvec2 t(0.0);
            poly.clear();
            for (std::size_t k = 0; k < e.properties.size(); ++k) {
                const auto& prop = e.properties[k];
                if (prop.is_list) {
                    const double n = values.read(prop.count_type);
                    if (!(n >= 0.0)) fail(path, "a negative list length in element '" + e.name + "' #" + std::to_string(i));
                    const bool keep = static_cast<int>(k) == indices;
                    for (double j = 0; j < n; ++j) {
                        const double v = values.read(prop.type);
                        if (keep) {
                            if (v != std::floor(v) || !(std::abs(v) < 9e18))
                                fail(path, "face #" + std::to_string(i) + " has a non-integer vertex index");
                            poly.push_back(static_cast<long long>(v));
                        }
                    }
                } else {
                    const double v = values.read(prop.type);
                    for (int c = 0; c < 3; ++c) {
                        if (static_cast<int>(k) == xyz[c]) p[c] = v;
                        if (static_cast<int>(k) == normal[c]) nrm[c] = v;
                    }
                    for (int c = 0; c < 2; ++c)
                        if (static_cast<int>(k) == uv[c]) t[c] = v;
                }
            }
            values.end_item();
            if (is_vertex) {
                s.positions.push_back(p);
                if (has_normal) s.normals.push_back(nrm);
                if (has_uv) s.uvs.push_back(t);
            }
            if (is_face) s.add_polygon(poly);
        }
    }
    if (!have_vertices) fail(path, "no 'vertex' element");
    if (!have_faces) fail(path, "no 'face' element");
    return s;
}

// ---- OBJ --------------------------------------------------------------------------------

soup read_obj(const fs::path& path, const std::string& text) {
    tinyobj::ObjReaderConfig config;
    // tinyobjloader's own triangulation reads vertex data through unchecked indices (and
    // drops quads with bad indices with only a warning), so polygons are kept as read and
    // fanned after the indices are checked.
    config.triangulate = false;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    // ParseFromString ignores `mtllib`: materials are the scene file's business.
    if (!reader.ParseFromString(text, std::string{}, config)) {
        std::string why = reader.Error();
        while (!why.empty() && std::isspace(static_cast<unsigned char>(why.back()))) why.pop_back();
        fail(path, "OBJ parse error: " + (why.empty() ? std::string("unknown") : why));
    }
    if (reader.Warning().find("Degenerated face") != std::string::npos)
        fail(path, "a face with fewer than 3 vertices");
    soup s;
    const auto& attrib = reader.GetAttrib();
    const auto& v = attrib.vertices;
    for (std::size_t i = 0; i + 2 < v.size(); i += 3)
        s.positions.emplace_back(static_cast<double>(v[i]), static_cast<double>(v[i + 1]), static_cast<double>(v[i + 2]));
    // Normals (vn) and texture coordinates (vt) are indexed per face corner, apart from the
    // positions: every corner has them or none does (a mesh half with normals would be
    // shaded half smooth), and a mesh with them gets one vertex per distinct
    // (position, normal, uv) triple. Without them the positions stay as in the file.
    bool any_normal = false, any_uv = false, all_normal = true, all_uv = true;
    for (const auto& shape : reader.GetShapes())
        for (const auto& c : shape.mesh.indices) {
            if (c.normal_index >= 0) any_normal = true;
            else all_normal = false;
            if (c.texcoord_index >= 0) any_uv = true;
            else all_uv = false;
        }
    if (any_normal && !all_normal) fail(path, "some face corners have a normal (v//vn or v/vt/vn) and some do not");
    if (any_uv && !all_uv) fail(path, "some face corners have texture coordinates (v/vt) and some do not");
    const auto nn = static_cast<long long>(attrib.normals.size() / 3), nt = static_cast<long long>(attrib.texcoords.size() / 2);
    std::vector<glm::dvec3> positions;  // split per distinct triple when there are normals or uvs
    std::map<std::array<long long, 3>, long long> split;
    std::size_t face = 0;
    for (const auto& shape : reader.GetShapes()) {
        const auto& m = shape.mesh;
        std::size_t at = 0;
        for (const unsigned n : m.num_face_vertices) {
            if (at + n > m.indices.size()) fail(path, "OBJ face data is inconsistent");
            for (std::size_t k = 0; k < n; ++k) {
                const auto& c = m.indices[at + k];
                if (!any_normal && !any_uv) {
                    s.indices.push_back(c.vertex_index);
                    continue;
                }
                if (c.vertex_index < 0 || c.vertex_index >= static_cast<long long>(s.positions.size()))
                    fail(path, "face " + std::to_string(face) + " refers to vertex " + std::to_string(c.vertex_index) +
                                   ", but there are " + std::to_string(s.positions.size()) + " vertices (index out of range)");
                if (any_normal && c.normal_index >= nn)
                    fail(path, "face " + std::to_string(face) + " refers to normal " + std::to_string(c.normal_index) +
                                   ", but there are " + std::to_string(nn) + " normals (vn; index out of range)");
                if (any_uv && c.texcoord_index >= nt)
                    fail(path, "face " + std::to_string(face) + " refers to texture coordinate " + std::to_string(c.texcoord_index) +
                                   ", but there are " + std::to_string(nt) + " (vt; index out of range)");
                const std::array<long long, 3> key{c.vertex_index, any_normal ? c.normal_index : -1, any_uv ? c.texcoord_index : -1};
                const auto [it, added] = split.try_emplace(key, static_cast<long long>(positions.size()));
                if (added) {
                    positions.push_back(s.positions[static_cast<std::size_t>(c.vertex_index)]);
                    if (any_normal) {
                        const auto i = static_cast<std::size_t>(3 * c.normal_index);
                        s.normals.emplace_back(static_cast<double>(attrib.normals[i]), static_cast<double>(attrib.normals[i + 1]),
                                               static_cast<double>(attrib.normals[i + 2]));
                    }
                    if (any_uv) {
                        const auto i = static_cast<std::size_t>(2 * c.texcoord_index);
                        s.uvs.emplace_back(static_cast<double>(attrib.texcoords[i]), static_cast<double>(attrib.texcoords[i + 1]));
                    }
                }
                s.indices.push_back(it->second);
            }
            at += n;
            ++face;
            s.ends.push_back(s.indices.size());
        }
    }
    if (any_normal || any_uv) s.positions = std::move(positions);
    return s;
}

// Check the soup and fan its polygons into triangles.
triangle_mesh to_mesh(const fs::path& path, const soup& s) {
    triangle_mesh m;
    m.positions.reserve(s.positions.size());
    for (std::size_t i = 0; i < s.positions.size(); ++i) {
        const glm::dvec3& p = s.positions[i];
        const glm::vec3 q(p);
        if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
            fail(path, "vertex " + std::to_string(i) + " has a non-finite coordinate (or one beyond float range)");
        m.positions.push_back(q);
    }
    for (std::size_t i = 0; i < s.normals.size(); ++i) {
        const glm::vec3 n(s.normals[i]);
        if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z))
            fail(path, "vertex " + std::to_string(i) + " has a non-finite normal (or one beyond float range)");
        if (!(glm::dot(n, n) > 0.0f)) fail(path, "vertex " + std::to_string(i) + " has a zero normal");
        m.normals.push_back(n);
    }
    for (std::size_t i = 0; i < s.uvs.size(); ++i) {
        const glm::vec2 t(s.uvs[i]);
        if (!std::isfinite(t.x) || !std::isfinite(t.y))
            fail(path, "vertex " + std::to_string(i) + " has non-finite texture coordinates (or ones beyond float range)");
        m.uvs.push_back(t);
    }
    const auto nv = static_cast<long long>(m.positions.size());
    std::size_t triangles = 0;
    for (std::size_t f = 0, begin = 0; f < s.ends.size(); begin = s.ends[f++])
        if (s.ends[f] - begin >= 3) triangles += s.ends[f] - begin - 2;
    m.triangles.reserve(triangles);  // bounded by the data read, not by a header count
    for (std::size_t f = 0, begin = 0; f < s.ends.size(); begin = s.ends[f++]) {
        const long long* poly = s.indices.data() + begin;
        const std::size_t n = s.ends[f] - begin;
        if (n < 3) fail(path, "face " + std::to_string(f) + " has fewer than 3 vertices");
        for (std::size_t k = 0; k < n; ++k)
            if (poly[k] < 0 || poly[k] >= nv)
                fail(path, "face " + std::to_string(f) + " refers to vertex " + std::to_string(poly[k]) + ", but there are " +
                               std::to_string(nv) + " vertices (index out of range)");
        for (std::size_t k = 1; k + 1 < n; ++k)
            m.triangles.push_back({static_cast<std::uint32_t>(poly[0]), static_cast<std::uint32_t>(poly[k]),
                                   static_cast<std::uint32_t>(poly[k + 1])});
    }
    if (m.triangles.empty()) fail(path, "the file holds no triangles");
    return m;
}

}  // namespace

std::string lower_extension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

triangle_mesh load_mesh(const std::filesystem::path& path) {
    const std::string outer = lower_extension(path);
    const bool gz = outer == ".gz";
    const std::string ext = gz ? lower_extension(path.stem()) : outer;  // mesh.ply.gz: .ply inside gzip
    if (ext != ".obj" && ext != ".off" && ext != ".ply")
        fail(path, "unsupported extension '" + (gz ? ext + ".gz" : ext) +
                       "' (expected .obj, .off or .ply, each optionally gzip-compressed: .ply.gz)");
    const mesh_format format = ext == ".obj" ? mesh_format::obj : ext == ".off" ? mesh_format::off : mesh_format::ply;
    std::string bytes = read_file(path);
    if (gz) bytes = gunzip(bytes, path);
    return parse_mesh(bytes, format, path);
}

std::string gunzip(std::string_view compressed, const std::filesystem::path& name, std::size_t max_bytes) {
    std::string why;
    auto out = iris::gunzip_bytes(compressed, max_bytes, why);
    if (!out) fail(name, why);
    return std::move(*out);
}

triangle_mesh parse_mesh(std::string_view bytes, mesh_format format, const std::filesystem::path& name) {
    switch (format) {
        case mesh_format::obj: return to_mesh(name, read_obj(name, std::string(bytes)));
        case mesh_format::off: return to_mesh(name, read_off(name, bytes));
        case mesh_format::ply: return to_mesh(name, read_ply(name, bytes));
    }
    fail(name, "unknown mesh format");
}

}  // namespace iris::geometry
