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

inline std::string to_obj(const geometry::triangle_mesh& m) {
    auto os = exact_stream();
    os << "# written by the iris tests\nmtllib missing.mtl\no mesh\n";
    for (const auto& p : m.positions) os << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const auto& t : m.triangles) os << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
    return os.str();
}

inline std::string ply_header(const geometry::triangle_mesh& m, const char* format, const char* coord_type) {
    std::ostringstream os;
    os << "ply\nformat " << format << " 1.0\ncomment written by the iris tests\n"
       << "element vertex " << m.positions.size() << "\nproperty " << coord_type << " x\nproperty " << coord_type
       << " y\nproperty " << coord_type << " z\nproperty uchar red\n"  // an extra property to skip
       << "element face " << m.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    return os.str();
}

inline std::string to_ascii_ply(const geometry::triangle_mesh& m) {
    auto os = exact_stream();
    os << ply_header(m, "ascii", "float");
    for (const auto& p : m.positions) os << p.x << ' ' << p.y << ' ' << p.z << " 255\n";
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
    for (const auto& p : m.positions) {
        for (int k = 0; k < 3; ++k) {
            if (doubles) put(static_cast<double>(p[k]));
            else put(p[k]);
        }
        put(std::uint8_t{255});
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
