#pragma once
/// \file
/// \brief A reference ray caster independent of Embree: CGAL's AABB tree over the
/// triangles, in double precision with exact predicates (target `iris::geometry`).
/// Slow next to Embree; it exists to check Embree (tests/embree) and for one-off queries.

#include <cstdint>
#include <memory>
#include <optional>

#include <glm/vec3.hpp>

#include "iris/geometry/triangle_mesh.hpp"

namespace iris::geometry {

/// \brief The first triangle a ray meets, as CGAL computes it.
struct reference_hit {
    double t = 0.0;            ///< distance along the ray in units of |direction|
    std::uint32_t prim = 0;    ///< index into the mesh's triangles
    double edge_distance = 0;  ///< distance from the hit point to the triangle's nearest edge
};

/// \brief CGAL `AABB_tree` ray shooting (`first_intersection`) over one mesh. The mesh is
/// copied; do/don't-hit decisions use CGAL's exact predicates (Epick), so a ray through
/// an edge or a vertex of a closed mesh never slips through; hit points are computed in
/// double precision. Move-only; queries are const and may run concurrently.
class ray_shooter {
public:
    /// \throws error if the mesh has indices out of range or non-finite positions.
    explicit ray_shooter(const triangle_mesh& mesh);
    ~ray_shooter();
    ray_shooter(ray_shooter&&) noexcept;
    ray_shooter& operator=(ray_shooter&&) noexcept;
    ray_shooter(const ray_shooter&) = delete;
    ray_shooter& operator=(const ray_shooter&) = delete;

    /// \brief The first hit of the ray origin + t·direction, t > 0; nullopt if it misses
    /// (or `direction` is zero). A ray running inside a triangle's plane reports the
    /// entry point of that segment.
    std::optional<reference_hit> first_hit(const glm::dvec3& origin, const glm::dvec3& direction) const;

private:
    struct impl;
    std::unique_ptr<impl> m_impl;
};

}  // namespace iris::geometry
