#pragma once
// The property every mesh-format target checks (mesh_obj, mesh_off, mesh_ply): the bytes
// either parse into a mesh with at least one triangle, every index in range and every
// coordinate finite, or throw iris::geometry::error naming the file — never another
// exception, never a crash, never an allocation the input's size does not justify.
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include <iris/geometry/triangle_mesh.hpp>

#include "fuzz_input.hpp"

namespace iris::fuzz {

inline int check_mesh_bytes(const std::uint8_t* data, std::size_t size, iris::geometry::mesh_format format) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        const auto m = iris::geometry::parse_mesh(bytes, format, "fuzz-mesh");
        if (m.triangles.empty()) fail("a mesh without triangles was accepted");
        for (const auto& p : m.positions)
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) fail("a non-finite vertex was accepted");
        for (const auto& t : m.triangles)
            for (const auto i : t)
                if (i >= m.positions.size()) fail("a vertex index out of range was accepted");
    } catch (const iris::geometry::error& e) {
        if (std::string_view(e.what()).find("fuzz-mesh") == std::string_view::npos) fail("an error that does not name the file");
    }
    return 0;
}

}  // namespace iris::fuzz
