#pragma once
// Test helpers: write meshes as OFF / OBJ / PLY text or bytes, exactly (max_digits10), so
// that load_mesh round trips can compare floats with ==, and the determinism test can
// compare bytes.
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include <iris/geometry/triangle_mesh.hpp>

namespace iris::test {

inline std::ostringstream exact_stream() {
    std::ostringstream os;
    os.precision(std::numeric_limits<float>::max_digits10);
    return os;
}

inline std::string to_off(const geometry::triangle_mesh& m) {
    auto os = exact_stream();
    os << "OFF\n" << m.positions.size() << ' ' << m.triangles.size() << " 0\n";
    for (const auto& p : m.positions) os << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const auto& t : m.triangles) os << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    return os.str();
}

// With the mesh's normals (vn) and uvs (vt), one of each per position, indexed as the positions.
inline std::string to_obj(const geometry::triangle_mesh& m) {
    auto os = exact_stream();
    os << "# written by the iris tests\nmtllib missing.mtl\no mesh\n";
    for (const auto& p : m.positions) os << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const auto& n : m.normals) os << "vn " << n.x << ' ' << n.y << ' ' << n.z << '\n';
    for (const auto& t : m.uvs) os << "vt " << t.x << ' ' << t.y << '\n';
    const auto corner = [&](std::uint32_t i) {
        const auto k = std::to_string(i + 1);
        if (m.normals.empty() && m.uvs.empty()) return k;
        return k + "/" + (m.uvs.empty() ? "" : k) + (m.normals.empty() ? "" : "/" + k);
    };
    for (const auto& t : m.triangles) os << "f " << corner(t[0]) << ' ' << corner(t[1]) << ' ' << corner(t[2]) << '\n';
    return os.str();
}

// Vertex properties x y z, nx ny nz (with normals), red (an extra property to skip), u v (with uvs).
inline std::string ply_header(const geometry::triangle_mesh& m, const char* format, const char* coord_type) {
    std::ostringstream os;
    os << "ply\nformat " << format << " 1.0\ncomment written by the iris tests\n"
       << "element vertex " << m.positions.size() << "\nproperty " << coord_type << " x\nproperty " << coord_type
       << " y\nproperty " << coord_type << " z\n";
    if (!m.normals.empty()) os << "property " << coord_type << " nx\nproperty " << coord_type << " ny\nproperty " << coord_type << " nz\n";
    os << "property uchar red\n";
    if (!m.uvs.empty()) os << "property " << coord_type << " u\nproperty " << coord_type << " v\n";
    os << "element face " << m.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    return os.str();
}

inline std::string to_ascii_ply(const geometry::triangle_mesh& m) {
    auto os = exact_stream();
    os << ply_header(m, "ascii", "float");
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        const auto& p = m.positions[i];
        os << p.x << ' ' << p.y << ' ' << p.z;
        if (!m.normals.empty()) os << ' ' << m.normals[i].x << ' ' << m.normals[i].y << ' ' << m.normals[i].z;
        os << " 255";
        if (!m.uvs.empty()) os << ' ' << m.uvs[i].x << ' ' << m.uvs[i].y;
        os << '\n';
    }
    for (const auto& t : m.triangles) os << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    return os.str();
}

// Binary PLY with float or double coordinates, in either byte order.
inline std::string to_binary_ply(const geometry::triangle_mesh& m, bool big_endian, bool doubles = false) {
    std::string s = ply_header(m, big_endian ? "binary_big_endian" : "binary_little_endian", doubles ? "double" : "float");
    const auto put = [&](auto value) {
        char b[sizeof value];
        std::memcpy(b, &value, sizeof value);
        if (big_endian != (std::endian::native == std::endian::big))
            for (std::size_t i = 0; i < sizeof value / 2; ++i) std::swap(b[i], b[sizeof value - 1 - i]);
        s.append(b, sizeof value);
    };
    const auto put_real = [&](float v) {
        if (doubles) put(static_cast<double>(v));
        else put(v);
    };
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        for (int k = 0; k < 3; ++k) put_real(m.positions[i][k]);
        if (!m.normals.empty())
            for (int k = 0; k < 3; ++k) put_real(m.normals[i][k]);
        put(std::uint8_t{255});
        if (!m.uvs.empty())
            for (int k = 0; k < 2; ++k) put_real(m.uvs[i][k]);
    }
    for (const auto& t : m.triangles) {
        put(std::uint8_t{3});
        for (const auto i : t) put(static_cast<std::int32_t>(i));
    }
    return s;
}

inline void write_file(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace iris::test
