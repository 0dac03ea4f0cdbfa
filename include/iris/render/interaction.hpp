#pragma once
/// \file
/// \brief `surface_interaction`: what a ray hit is to everything after the ray tracer —
/// the point with its error bound, the geometric normal, the shading frame, the texture
/// coordinates, the direction back along the ray — built once per vertex by
/// `make_interaction` and read by both estimators.
///
/// Two normals, two jobs. The unit geometric normal `ng` is the triangle's, in its winding's
/// orientation (Embree's Ng, (v1 − v0) × (v2 − v0)): it decides which side is outside, which
/// side an emitter shines from, and where ray origins are moved (iris/render/frame.hpp). The
/// shading frame's normal ns is the mesh's interpolated vertex normal, or ng when the mesh
/// has none; it is turned to ng's side when it points away (the winding stays the authority
/// on orientation; pbrt-v4 instead turns ng towards the vertex normals, which its importer
/// must undo). BxDFs see directions only in the shading frame, where ns is +z
/// (iris/render/materials/bxdf.hpp).

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/intersector.hpp"
#include "iris/render/scene.hpp"

namespace iris {

struct surface_interaction {
    surface_point sp;    ///< the point, rebuilt from barycentrics, with its error bound
    glm::vec3 ng{0.0f};  ///< unit geometric normal, on the winding's outside
    frame shading{};     ///< around the shading normal ns (ns = `shading.n`, on ng's side)
    glm::vec2 uv{0.0f};  ///< the mesh's texture coordinates, or (b1 + b2, b2) without them
    glm::vec3 wo{0.0f};  ///< unit direction back along the ray
    float t = 0.0f;      ///< the ray's parameter at the hit, in units of its direction
    std::uint32_t shape = 0, prim = 0;

    glm::vec3 to_local(const glm::vec3& w) const noexcept { return shading.to_local(w); }
    glm::vec3 to_world(const glm::vec3& w) const noexcept { return shading.to_world(w); }
};

/// \brief Interpolated vertex normal of `mesh`'s triangle `tri` at barycentrics (b1, b2),
/// unit and on the side of unit `ng`; `ng` itself where the mesh has no normals or the
/// interpolation degenerates (opposite normals cancelling, a non-finite input).
inline glm::vec3 shading_normal(const triangle_mesh& mesh, const std::array<std::uint32_t, 3>& tri, float b1, float b2,
                                const glm::vec3& ng) noexcept {
    if (mesh.normals.empty()) return ng;
    const float b0 = 1.0f - b1 - b2;
    const glm::vec3 n = b0 * mesh.normals[tri[0]] + b1 * mesh.normals[tri[1]] + b2 * mesh.normals[tri[2]];
    const float len = glm::length(n);
    if (!(len > 0.0f) || !std::isfinite(len)) return ng;
    const glm::vec3 ns = n / len;
    return glm::dot(ns, ng) < 0.0f ? -ns : ns;
}

/// \brief Texture coordinates of `mesh`'s triangle `tri` at barycentrics (b1, b2): the
/// interpolated vertex uvs, or pbrt-v4's default (0, 0), (1, 0), (1, 1) at the three
/// vertices, i.e. (b1 + b2, b2), where the mesh has none.
inline glm::vec2 surface_uv(const triangle_mesh& mesh, const std::array<std::uint32_t, 3>& tri, float b1,
                            float b2) noexcept {
    if (mesh.uvs.empty()) return {b1 + b2, b2};
    const float b0 = 1.0f - b1 - b2;
    return b0 * mesh.uvs[tri[0]] + b1 * mesh.uvs[tri[1]] + b2 * mesh.uvs[tri[2]];
}

/// \brief The interaction of `hit`, found along `dir` (unit), in `scene`; nothing for a
/// degenerate triangle (no normal).
inline std::optional<surface_interaction> make_interaction(const scene_desc& scene, const ray_hit& hit,
                                                           const glm::vec3& dir) noexcept {
    const triangle_mesh& mesh = scene.shapes[hit.shape].mesh;
    const auto& tri = mesh.triangles[hit.prim];
    const float len = glm::length(hit.geometric_normal);
    if (!(len > 0.0f) || !std::isfinite(len)) return std::nullopt;
    surface_interaction si;
    si.sp = point_on_triangle(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]], hit.u, hit.v);
    si.ng = hit.geometric_normal / len;
    si.shading = frame::from_normal(shading_normal(mesh, tri, hit.u, hit.v, si.ng));
    si.uv = surface_uv(mesh, tri, hit.u, hit.v);
    si.wo = -dir;
    si.t = hit.t;
    si.shape = hit.shape;
    si.prim = hit.prim;
    return si;
}

}  // namespace iris
