// The CGAL half of iris::geometry: mesh checks (PMP), the hollow cube (corefinement) and
// enclosed volumes. One of the two translation units that include CGAL (with
// ray_shooting.cpp); everything crosses the boundary as iris::triangle_mesh.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <array>
#include <functional>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "iris/geometry/mesh.hpp"

namespace iris::geometry {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
// Exact predicates, double constructions: every decision (orientation, intersection,
// inclusion) is exact for the float input; the corefinement below creates no new
// intersection points (the inner cube does not touch the outer one), so inexact
// constructions lose nothing there either.
using kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using point = kernel::Point_3;
using surface_mesh = CGAL::Surface_mesh<point>;
using polygon = std::vector<std::size_t>;

std::string edge_name(std::size_t a, std::size_t b) {
    return "(" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

// A mesh as CGAL sees it: the check so far and, when the soup is a manifold, the surface
// mesh with the input's own orientation if that is consistent.
struct analysis {
    mesh_check check;
    std::optional<surface_mesh> mesh;  ///< set iff check.manifold
    bool consistent = false;           ///< neighbouring triangles agree on orientation
};

void note(mesh_check& c, const std::string& what) {
    if (!c.detail.empty()) c.detail += "; ";
    c.detail += what;
}

// Every shell outward, nested shells alternating: a shell at even nesting depth (0 = not
// inside any other) bounds material and must face out, one at odd depth bounds a cavity
// and must face into it. (`does_bound_a_volume` alone also accepts an inside-out solid,
// as a hole of the unbounded volume.) \pre closed, consistently oriented, no self-intersections
bool outward(const surface_mesh& sm) {
    std::vector<std::size_t> nesting;
    std::vector<bool> cc_outward;
    std::vector<PMP::Volume_error_code> errors;
    std::vector<std::size_t> volume_of_face(sm.number_of_faces());
    const auto volume_map = CGAL::make_property_map(volume_of_face);
    PMP::volume_connected_components(sm, volume_map,
                                     PMP::parameters::do_orientation_tests(true)
                                         .nesting_levels(std::ref(nesting))
                                         .is_cc_outward_oriented(std::ref(cc_outward))
                                         .error_codes(std::ref(errors)));
    for (const auto e : errors)
        if (e != PMP::VALID_VOLUME) return false;
    if (nesting.size() != cc_outward.size()) return false;
    for (std::size_t cc = 0; cc < nesting.size(); ++cc)
        if (cc_outward[cc] != (nesting[cc] % 2 == 0)) return false;
    return true;
}

analysis analyse(const triangle_mesh& in) {
    analysis a;
    mesh_check& c = a.check;
    if (in.triangles.empty()) {
        c.detail = "the mesh has no triangles";
        return a;
    }
    for (std::size_t i = 0; i < in.positions.size(); ++i) {
        const glm::vec3 p = in.positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            c.detail = "vertex " + std::to_string(i) + " is not finite";
            return a;
        }
    }
    for (std::size_t t = 0; t < in.triangles.size(); ++t)
        for (const std::uint32_t v : in.triangles[t])
            if (v >= in.positions.size()) {
                c.detail = "triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) + " of " +
                           std::to_string(in.positions.size());
                return a;
            }

    // Weld equal positions: closedness is about the surface, not about how a file
    // happened to number its corners. (Welding maps −0 and +0 together, which is right.)
    std::vector<point> points;
    std::vector<std::size_t> weld(in.positions.size());
    {
        std::map<std::array<float, 3>, std::size_t> seen;
        for (std::size_t i = 0; i < in.positions.size(); ++i) {
            const glm::vec3 p = in.positions[i];
            const auto [it, inserted] = seen.try_emplace({p.x + 0.0f, p.y + 0.0f, p.z + 0.0f}, points.size());
            if (inserted) points.emplace_back(p.x, p.y, p.z);
            weld[i] = it->second;
        }
    }
    std::vector<polygon> polygons;
    polygons.reserve(in.triangles.size());
    bool degenerate = false;
    for (std::size_t t = 0; t < in.triangles.size(); ++t) {
        const auto& tri = in.triangles[t];
        polygon p{weld[tri[0]], weld[tri[1]], weld[tri[2]]};
        if (p[0] == p[1] || p[1] == p[2] || p[0] == p[2]) {
            if (!degenerate) note(c, "triangle " + std::to_string(t) + " uses one vertex twice");
            degenerate = true;
        }
        polygons.push_back(std::move(p));
    }
    if (degenerate) return a;  // CGAL's soup functions require three distinct vertices

    // Edge census: each undirected edge with the number of triangles using it in each
    // direction. Two uses in one direction means the neighbours disagree on orientation.
    std::map<std::pair<std::size_t, std::size_t>, std::array<int, 2>> edges;
    for (const polygon& p : polygons)
        for (std::size_t k = 0; k < 3; ++k) {
            const std::size_t u = p[k], v = p[(k + 1) % 3];
            ++edges[std::minmax(u, v)][u < v ? 0 : 1];
        }
    std::size_t boundary = 0, non_manifold = 0, flipped = 0;
    std::string first_boundary, first_non_manifold, first_flipped;
    for (const auto& [e, uses] : edges) {
        const int n = uses[0] + uses[1];
        if (n == 1 && boundary++ == 0) first_boundary = edge_name(e.first, e.second);
        if (n > 2 && non_manifold++ == 0) first_non_manifold = edge_name(e.first, e.second);
        if (n == 2 && uses[0] != 1 && flipped++ == 0) first_flipped = edge_name(e.first, e.second);
    }
    a.consistent = flipped == 0;

    // Manifoldness as CGAL decides it: orienting the soup must not duplicate any point
    // (it duplicates them at edges with more than two triangles and at pinched vertices).
    std::vector<point> oriented_points = points;
    std::vector<polygon> oriented = polygons;
    c.manifold = PMP::orient_polygon_soup(oriented_points, oriented);
    if (!c.manifold) {
        note(c, non_manifold > 0 ? std::to_string(non_manifold) + " edge(s) with more than two triangles, first " + first_non_manifold
                                 : std::string("a vertex where separate sheets of triangles meet (pinched vertex)"));
        c.closed = boundary == 0 && non_manifold == 0;
        if (!c.closed && boundary > 0) note(c, std::to_string(boundary) + " boundary edge(s), first " + first_boundary);
        return a;
    }
    surface_mesh sm;
    PMP::polygon_soup_to_polygon_mesh(points, a.consistent ? polygons : oriented, sm);
    c.closed = CGAL::is_closed(sm);
    if (!c.closed) note(c, std::to_string(boundary) + " boundary edge(s), first " + first_boundary);
    if (!a.consistent) note(c, std::to_string(flipped) + " edge(s) where neighbouring triangles are oriented oppositely, first " + first_flipped);
    c.self_intersection_free = !PMP::does_self_intersect(sm);
    if (!c.self_intersection_free) note(c, "triangles intersect each other");
    if (a.consistent && c.closed && c.self_intersection_free) {
        c.outward = outward(sm);
        if (!c.outward) note(c, "the normals do not point out of the enclosed volume (inside-out shell)");
    } else if (c.closed && c.self_intersection_free) {
        note(c, "orientation undecided");
    }
    a.mesh = std::move(sm);
    return a;
}

surface_mesh to_surface_mesh(const triangle_mesh& m) {
    analysis a = analyse(m);
    if (!a.check.ok()) throw error("internal: a generated mesh failed its check: " + a.check.detail);
    return std::move(*a.mesh);
}

triangle_mesh from_surface_mesh(surface_mesh& sm) {
    if (sm.has_garbage()) sm.collect_garbage();
    triangle_mesh m;
    m.positions.reserve(sm.number_of_vertices());
    for (const auto v : sm.vertices()) {
        const point& p = sm.point(v);
        // The points came from floats and corefinement added none: exact round trip.
        m.positions.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
    }
    m.triangles.reserve(sm.number_of_faces());
    for (const auto f : sm.faces()) {
        std::array<std::uint32_t, 3> t{};
        std::size_t k = 0;
        for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
            if (k == 3) throw error("internal: corefinement returned a face that is not a triangle");
            t[k++] = static_cast<std::uint32_t>(static_cast<std::size_t>(v));
        }
        m.triangles.push_back(t);
    }
    return m;
}

}  // namespace

mesh_check check_mesh(const triangle_mesh& mesh) { return analyse(mesh).check; }

triangle_mesh make_hollow_cube(glm::vec3 centre, float outer_edge, float inner_edge) {
    if (!(inner_edge > 0.0f && inner_edge < outer_edge) || !std::isfinite(outer_edge))
        throw error("hollow cube: need 0 < inner edge < outer edge, got outer " + std::to_string(outer_edge) + ", inner " +
                    std::to_string(inner_edge));
    surface_mesh outer = to_surface_mesh(make_cube(centre, outer_edge));
    surface_mesh inner = to_surface_mesh(make_cube(centre, inner_edge));
    surface_mesh result;
    if (!PMP::corefine_and_compute_difference(outer, inner, result))
        throw error("hollow cube: CGAL corefinement could not compute the difference");
    return from_surface_mesh(result);
}

double enclosed_volume(const triangle_mesh& mesh) {
    const analysis a = analyse(mesh);
    if (!a.check.manifold || !a.check.closed || !a.consistent)
        throw error("enclosed volume: the mesh is not closed, manifold and consistently oriented (" + a.check.detail + ")");
    return PMP::volume(*a.mesh);
}

}  // namespace iris::geometry
