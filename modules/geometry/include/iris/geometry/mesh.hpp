#pragma once
/// \file
/// \brief iris::geometry — closed triangle meshes: the CGAL-free mesh type, builders and
/// loader (`triangle_mesh.hpp`, target `iris::geometry_mesh`) plus what needs CGAL's
/// Polygon Mesh Processing: validity checks, the hollow cube (corefinement) and enclosed
/// volumes (target `iris::geometry`).
///
/// CGAL is linked PRIVATE to `iris::geometry` and none of its headers appear here:
/// including this header costs nothing extra and adds no `-frounding-math`.

#include <string>

#include "iris/geometry/triangle_mesh.hpp"

namespace iris::geometry {

/// \brief The result of `check_mesh`. The later properties need the earlier ones:
/// self-intersection freedom is only decided for manifold meshes and orientation only for
/// closed, manifold, self-intersection-free ones; a property that could not be decided
/// is false and `detail` says why.
struct mesh_check {
    bool closed = false;                  ///< every edge has exactly two triangles
    bool manifold = false;                ///< edge- and vertex-manifold, consistently oriented, no degenerate indices
    bool outward = false;                 ///< normals point out of the bounded volume (nested shells alternate)
    bool self_intersection_free = false;  ///< no two triangles intersect except at shared edges/vertices
    std::string detail;                   ///< empty if ok(), else what failed first, with indices

    /// \brief All four properties hold: a valid closed solid for the integrator.
    bool ok() const noexcept { return closed && manifold && outward && self_intersection_free; }
};

/// \brief Check a mesh with CGAL PMP (`orient_polygon_soup` for manifoldness,
/// `is_closed`, `does_self_intersect`, `does_bound_a_volume` for orientation, which
/// accepts nested shells such as the hollow cube's inward inner walls). Vertices with
/// bitwise-equal positions are treated as one vertex, so a mesh that repeats corners per
/// face is still closed. Invalid indices or non-finite positions give an all-false result.
mesh_check check_mesh(const triangle_mesh& mesh);

/// \brief A cube with a cubic cavity: the axis-aligned cube (`outer_edge`) minus the
/// concentric cube (`inner_edge`), computed by CGAL corefinement (`difference`). The inner
/// walls face the cavity (outward from the solid); 16 vertices, 24 triangles.
/// \throws error unless 0 < inner_edge < outer_edge.
triangle_mesh make_hollow_cube(glm::vec3 centre, float outer_edge, float inner_edge);

/// \brief The signed volume enclosed by a closed mesh (CGAL `volume`); positive for
/// outward meshes, and a hollow solid counts its cavity negatively (a³ − b³).
/// \throws error if the mesh is not closed and manifold.
double enclosed_volume(const triangle_mesh& mesh);

/// \brief pbrt-v4's `loopsubdiv` shape: `levels` steps of Loop subdivision of a triangle
/// mesh (CGAL's triangle quadrisection with pbrt-v4's masks: Warren's weight 3/(8n) of an
/// interior vertex's ring, 3/16 at valence 3; the border rules of Loop), every vertex then
/// moved to its limit position and given the limit surface's normal (per-vertex `normals`,
/// turned to agree with the triangles' winding). A border vertex's limit position is the
/// cubic B-spline's (1/6, 4/6, 1/6; pbrt-v4 uses 1/5, 3/5, 1/5, which is not the limit of
/// its border rule). Unused points are dropped.
/// \throws error unless 0 ≤ levels ≤ 10 and the mesh is an oriented manifold with borders.
triangle_mesh loop_subdivide(const triangle_mesh& control, int levels);

}  // namespace iris::geometry
