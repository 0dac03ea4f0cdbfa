#pragma once
/// \file
/// \brief The CGAL-free half of iris::geometry (target `iris::geometry_mesh`): the triangle
/// mesh type, affine transforms, the builders that need no Boolean operation, and
/// `load_mesh`. `iris::embree` includes only this header, so CGAL (and its
/// `-frounding-math`) never reaches the ray tracer or the renderer.
///
/// Conventions: a triangle's vertices are counter-clockwise seen from outside, so
/// (p1 − p0) × (p2 − p0) is the outward normal; every builder returns a closed, manifold,
/// outward-oriented mesh without self-intersections unless it says otherwise (the quad
/// and the rectangle are open). Invalid arguments and unreadable files throw
/// `iris::geometry::error`; nothing here crashes on bad input.

#include <array>
#include <filesystem>
#include <stdexcept>
#include <string_view>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/scene.hpp"

namespace iris::geometry {

/// \brief Every failure of iris::geometry: bad builder arguments, unreadable or broken
/// mesh files (the message names the file and what is wrong), failed CGAL operations.
class error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// \brief The core's mesh type (include/iris/render/scene.hpp): `positions`, and
/// `triangles` as index triples, counter-clockwise seen from the side their normal
/// (p1 − p0) × (p2 − p0) points to, which is outside for closed meshes. One type from the
/// builders through the scene description to Embree, so nothing is copied on the way.
using triangle_mesh = iris::triangle_mesh;

/// \brief The sum of the triangle areas (double precision). \pre indices in range
double surface_area(const triangle_mesh& mesh) noexcept;

/// \brief The affine map T · Rz · Ry · Rx · S: scale first, then rotate about the x axis,
/// then about y, then about z (angles in degrees, right-handed, about the world axes),
/// then translate.
glm::mat4 make_transform(glm::vec3 translate, glm::vec3 rotate_degrees_xyz,
                         glm::vec3 scale = glm::vec3(1.0f));

/// \brief `mesh` with every position mapped by the affine part of `m` (the bottom row is
/// ignored). A mirroring map (negative determinant) also swaps each triangle's winding,
/// so an outward mesh stays outward. \throws error if `m` is singular or not finite.
triangle_mesh transformed(const triangle_mesh& mesh, const glm::mat4& m);

/// \brief The axis-aligned box [min, max] (8 vertices, 12 triangles).
/// \throws error unless min < max on every axis (and both are finite).
triangle_mesh make_box(glm::vec3 min, glm::vec3 max);

/// \brief The axis-aligned cube with the given centre and edge length. \throws error unless edge > 0.
triangle_mesh make_cube(glm::vec3 centre, float edge);

/// \brief A right prism with an equilateral triangular cross-section: the triangle (side
/// length `side`) lies in the xy-plane with one vertex towards +y and the opposite side
/// parallel to x; it is extruded along z over `depth`. `centre` is the prism's centroid
/// (the triangle's centroid at mid-depth). Rotate it with `transformed` for other axes.
/// \throws error unless side > 0 and depth > 0.
triangle_mesh make_prism(glm::vec3 centre, float side, float depth);

/// \brief A general triangular prism: the triangle `base` swept by `extrusion` (the top
/// triangle is base + extrusion). Either winding of `base` is accepted; the result is
/// outward. \throws error if `base` is degenerate or `extrusion` lies in its plane.
triangle_mesh make_prism(const std::array<glm::vec3, 3>& base, glm::vec3 extrusion);

/// \brief An open parallelogram (two triangles) centred on `centre` and spanned by the
/// full edge vectors `u` and `v` (corners centre ± u/2 ± v/2); its normal is u × v. Not
/// closed: for emitters, floors and screens, and excluded from the closedness checks.
/// \throws error if u × v is zero or not finite.
triangle_mesh make_quad(glm::vec3 centre, glm::vec3 u, glm::vec3 v);

/// \brief An open rectangle centred on `centre`, facing `normal`, of extent size.x along
/// u and size.y along v, where u is the first world axis (x, then y, then z) least
/// aligned with `normal` made orthogonal to it, and v = n × u (so u × v = n). A floor
/// `make_rectangle(c, {w, d}, {0, 1, 0})` spans x by w and z by d.
/// \throws error unless size > 0 and `normal` is non-zero.
triangle_mesh make_rectangle(glm::vec3 centre, glm::vec2 size, glm::vec3 normal);

/// \brief An icosphere: the icosahedron inscribed in the sphere, each triangle split into
/// four `subdivisions` times, vertices pushed onto the sphere (20 · 4^s triangles).
/// \throws error unless radius > 0 and subdivisions ≤ 7.
triangle_mesh make_sphere(glm::vec3 centre, float radius, unsigned subdivisions);

/// \brief Read a triangle mesh from .obj (tinyobjloader; polygons are triangulated),
/// .off (ASCII) or .ply (ASCII or binary, `vertex` x/y/z and `face` vertex_indices);
/// polygons with more than three vertices are split into fans. Per-vertex normals and
/// texture coordinates are read where the file has them (PLY `nx ny nz`, `u v` or `s t`
/// or `texture_u/v`/`texture_s/t`; OBJ `vn`, `vt`, indexed per corner: an OBJ vertex used
/// with different normals or uvs becomes one vertex per distinct combination). The mesh
/// is returned as stored (not checked for closedness; see `check_mesh`). A `.gz` after the
/// extension (`mesh.ply.gz`) means a gzip-compressed file (`gunzip`).
/// \throws error naming the file and the problem: missing or unreadable file, unsupported
/// extension, parse failure (with the line for text formats), no triangles, non-finite
/// coordinates, vertex indices out of range; normals or uvs given in part (some components,
/// some OBJ corners), zero or non-finite normals, normal or uv indices out of range, an
/// OFF file with normals or texture coordinates (NOFF, STOFF: not read, so refused).
triangle_mesh load_mesh(const std::filesystem::path& path);

/// \brief The formats `load_mesh` reads.
enum class mesh_format { obj, off, ply };

/// \brief What `load_mesh` does after reading the file: parse `bytes` as `format`, with
/// `name` in every error message. The fuzz targets call this.
/// \throws error as `load_mesh` does (never another exception for any bytes).
triangle_mesh parse_mesh(std::string_view bytes, mesh_format format, const std::filesystem::path& name);

/// \brief The bytes of a gzip (or zlib) stream, as `load_mesh` reads `mesh.ply.gz`.
/// \throws error naming `name`: not a gzip stream, truncated, or more than `max_bytes` once
/// decompressed (a bound on what a small corrupt or hostile file can make iris allocate).
std::string gunzip(std::string_view compressed, const std::filesystem::path& name,
                   std::size_t max_bytes = std::size_t{4} << 30);

}  // namespace iris::geometry
