// The scene's triangles as one mesh file. Plain ASCII writers for the three formats that
// iris::geometry::load_mesh reads back (the tests round-trip through it), kept here so
// that CGAL's headers stay inside iris::geometry.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <limits>
#include <system_error>

#include "iris/scene/scene.hpp"

namespace iris::scene {
namespace {

enum class mesh_format { obj, ply, off };

void write_vertices(std::ofstream& out, const iris::scene_desc& s, const char* prefix) {
    for (const auto& sh : s.shapes)
        for (const auto& p : sh.mesh.positions) out << prefix << p.x << ' ' << p.y << ' ' << p.z << '\n';
}

/// Faces with indices into the concatenated vertex list, plus `base` (1 for OBJ).
void write_faces(std::ofstream& out, const iris::scene_desc& s, mesh_format f) {
    std::size_t offset = f == mesh_format::obj ? 1 : 0;
    for (const auto& sh : s.shapes) {
        if (f == mesh_format::obj) out << "o " << sh.name << '\n';
        for (const auto& t : sh.mesh.triangles)
            out << (f == mesh_format::obj ? "f " : "3 ") << offset + t[0] << ' ' << offset + t[1] << ' ' << offset + t[2]
                << '\n';
        offset += sh.mesh.positions.size();
    }
}

}  // namespace

void export_scene_mesh(const iris::scene_desc& s, const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    mesh_format f;
    if (ext == ".obj") f = mesh_format::obj;
    else if (ext == ".ply") f = mesh_format::ply;
    else if (ext == ".off") f = mesh_format::off;
    else
        throw error(path.string(), 0, "",
                    "unsupported mesh format '" + ext + "'; expected .obj, .ply or .off (or .pbrt: the whole scene in pbrt-v4's format)");

    std::size_t vertices = 0, triangles = 0;
    for (const auto& sh : s.shapes) {
        vertices += sh.mesh.positions.size();
        triangles += sh.mesh.triangles.size();
    }
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        if (!out) throw error(path.string(), 0, "", "cannot write the mesh file");
        out.precision(std::numeric_limits<float>::max_digits10);  // positions survive the round trip exactly
        switch (f) {
            case mesh_format::obj:
                out << "# " << s.name << ": " << vertices << " vertices, " << triangles << " triangles (iris-scene export)\n";
                write_vertices(out, s, "v ");
                break;
            case mesh_format::ply:
                out << "ply\nformat ascii 1.0\ncomment " << s.name << " (iris-scene export)\nelement vertex " << vertices
                    << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << triangles
                    << "\nproperty list uchar int vertex_indices\nend_header\n";
                write_vertices(out, s, "");
                break;
            case mesh_format::off:
                out << "OFF\n# " << s.name << " (iris-scene export)\n" << vertices << ' ' << triangles << " 0\n";
                write_vertices(out, s, "");
                break;
        }
        write_faces(out, s, f);
        out.flush();
        if (out) return;
    }
    std::error_code ec;
    std::filesystem::remove(path, ec);  // no half-written file behind an error
    throw error(path.string(), 0, "", "cannot write the mesh file");
}

}  // namespace iris::scene
