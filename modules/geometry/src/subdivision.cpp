// loop_subdivide(): pbrt-v4's `loopsubdiv` shape — Loop subdivision refined by CGAL's
// primal triangle quadrisection (PTQ) with pbrt-v4's masks, then every vertex moved to its
// limit position and given the limit surface's normal (pbrt-v4's tangents of it).
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Subdivision_method_3/subdivision_hosts_3.h>
#include <CGAL/Subdivision_method_3/subdivision_masks_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include "iris/geometry/mesh.hpp"

namespace iris::geometry {
namespace {

using kernel = CGAL::Simple_cartesian<double>;
using point = kernel::Point_3;
using vec = kernel::Vector_3;
using surface = CGAL::Surface_mesh<point>;
using vertex_map = surface::Property_map<surface::Vertex_index, point>;

/// Loop's weight of an even (old) vertex's ring in Warren's form, as pbrt-v4 uses it:
/// 3/16 for valence 3, 3/(8n) otherwise (CGAL's Loop_mask_3 uses Loop's original weight,
/// which differs away from valence 6).
double beta(std::size_t n) { return n == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * static_cast<double>(n)); }
/// The weight of the ring in a vertex's limit position.
double gamma(std::size_t n) { return 1.0 / (static_cast<double>(n) + 3.0 / (8.0 * beta(n))); }

/// CGAL's Loop stencils (edge and border rules are pbrt-v4's: 3/8, 3/8, 1/8, 1/8 for an
/// interior edge, the midpoint of a border edge, 1/8 6/8 1/8 along a border) with pbrt-v4's
/// weight of an interior even vertex.
struct pbrt_loop_mask : CGAL::Loop_mask_3<surface, vertex_map> {
    using base = CGAL::Loop_mask_3<surface, vertex_map>;
    using base::base;

    void vertex_node(vertex_descriptor v, point& pt) {
        const surface& m = *this->pmesh;
        std::size_t n = 0;
        vec ring(0.0, 0.0, 0.0);
        for (auto h : CGAL::halfedges_around_target(v, m)) {
            ring = ring + (get(this->vpmap, m.source(h)) - CGAL::ORIGIN);
            ++n;
        }
        const double b = beta(n);
        const vec self = get(this->vpmap, v) - CGAL::ORIGIN;
        pt = CGAL::ORIGIN + (1.0 - static_cast<double>(n) * b) * self + b * ring;
    }
};

/// The one-ring of v in cyclic order; at a border vertex, from one border neighbour round to
/// the other.
std::vector<point> one_ring(const surface& m, surface::Vertex_index v, bool& border) {
    surface::Halfedge_index start = m.halfedge(v);
    border = false;
    for (auto h : CGAL::halfedges_around_target(v, m))
        if (m.is_border(h)) {
            // h runs along the border into v; after it (around v) comes the other border
            // neighbour, then the interior: start there and the ring ends at h's source
            start = m.opposite(m.next(h));
            border = true;
            break;
        }
    std::vector<point> ring;
    for (auto h : CGAL::halfedges_around_target(start, m)) ring.push_back(m.point(m.source(h)));
    return ring;
}

}  // namespace

triangle_mesh loop_subdivide(const triangle_mesh& control, int levels) {
    if (levels < 0 || levels > 10) throw error("loopsubdiv: levels must lie in [0, 10], got " + std::to_string(levels));
    // the points the triangles use, renumbered (an unused point would be an isolated vertex)
    std::vector<std::size_t> index(control.positions.size(), SIZE_MAX);
    std::vector<point> points;
    std::vector<std::vector<std::size_t>> faces;
    for (const auto& t : control.triangles) {
        std::vector<std::size_t> f;
        for (std::uint32_t i : t) {
            if (i >= control.positions.size()) throw error("loopsubdiv: an index beyond the points");
            if (index[i] == SIZE_MAX) {
                index[i] = points.size();
                const glm::vec3& p = control.positions[i];
                points.emplace_back(p.x, p.y, p.z);
            }
            f.push_back(index[i]);
        }
        faces.push_back(std::move(f));
    }
    if (faces.empty()) throw error("loopsubdiv: no triangles");
    if (!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(faces))
        throw error("loopsubdiv: the control mesh is not an oriented manifold (an edge of more than two triangles, a "
                    "pinched vertex, neighbours wound in opposite directions, or a degenerate triangle)");
    surface m;
    CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, faces, m);
    if (levels > 0) CGAL::Subdivision_method_3::PTQ(m, pbrt_loop_mask(&m, m.points()), CGAL::parameters::number_of_iterations(levels));

    // limit positions (computed from the level-n positions, then moved together). A border
    // vertex's is the cubic B-spline's, 1/6 4/6 1/6 — the limit of the border rule; pbrt-v4
    // uses 1/5 3/5 1/5, which is not (LoopSubdivision.LimitPositionsDoNotMove… fails with it)
    std::vector<point> limit(m.num_vertices());
    for (auto v : m.vertices()) {
        bool border = false;
        const auto ring = one_ring(m, v, border);
        const vec self = m.point(v) - CGAL::ORIGIN;
        if (border) {
            limit[v] = CGAL::ORIGIN + (4.0 / 6.0) * self + (1.0 / 6.0) * ((ring.front() - CGAL::ORIGIN) + (ring.back() - CGAL::ORIGIN));
        } else {
            vec sum(0.0, 0.0, 0.0);
            for (const auto& p : ring) sum = sum + (p - CGAL::ORIGIN);
            const double g = gamma(ring.size());
            limit[v] = CGAL::ORIGIN + (1.0 - static_cast<double>(ring.size()) * g) * self + g * sum;
        }
    }
    for (auto v : m.vertices()) m.point(v) = limit[v];

    triangle_mesh out;
    std::vector<std::uint32_t> number(m.num_vertices());
    out.positions.reserve(m.num_vertices());
    out.normals.reserve(m.num_vertices());
    for (auto v : m.vertices()) {
        const point& p = m.point(v);
        number[v] = static_cast<std::uint32_t>(out.positions.size());
        out.positions.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
        // the limit surface's tangents (pbrt-v4's), their cross product oriented by the winding
        bool border = false;
        const auto ring = one_ring(m, v, border);
        const std::size_t n = ring.size();
        vec s(0.0, 0.0, 0.0), t(0.0, 0.0, 0.0);
        const auto r = [&](std::size_t j) { return ring[j] - CGAL::ORIGIN; };
        const vec self = p - CGAL::ORIGIN;
        if (!border) {
            for (std::size_t j = 0; j < n; ++j) {
                const double a = 2.0 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(n);
                s = s + std::cos(a) * r(j);
                t = t + std::sin(a) * r(j);
            }
        } else {
            s = r(n - 1) - r(0);
            if (n == 2) t = r(0) + r(1) - 2.0 * self;
            else if (n == 3) t = r(1) - self;
            else if (n == 4) t = -1.0 * r(0) + 2.0 * r(1) + 2.0 * r(2) - 1.0 * r(3) - 2.0 * self;
            else {
                const double theta = std::numbers::pi / static_cast<double>(n - 1);
                t = std::sin(theta) * (r(0) + r(n - 1));
                for (std::size_t k = 1; k + 1 < n; ++k) t = t + (2.0 * std::cos(theta) - 2.0) * std::sin(static_cast<double>(k) * theta) * r(k);
                t = -t;
            }
        }
        vec nrm = CGAL::cross_product(s, t);
        vec wind(0.0, 0.0, 0.0);  // the area-weighted normal of the triangles around v
        for (auto f : CGAL::faces_around_target(m.halfedge(v), m)) {
            if (f == surface::null_face()) continue;
            const auto h = m.halfedge(f);
            const point a = m.point(m.target(h)), b = m.point(m.target(m.next(h))), c = m.point(m.source(h));
            wind = wind + CGAL::cross_product(b - a, c - a);
        }
        if (nrm * wind < 0.0) nrm = -nrm;
        double len = std::sqrt(nrm.squared_length());
        if (!(len > 0.0) || !std::isfinite(len)) {  // a degenerate ring: the faces' normal
            nrm = wind;
            len = std::sqrt(nrm.squared_length());
            if (!(len > 0.0)) throw error("loopsubdiv: a vertex has no normal (its triangles have no area)");
        }
        nrm = nrm / len;
        out.normals.emplace_back(static_cast<float>(nrm.x()), static_cast<float>(nrm.y()), static_cast<float>(nrm.z()));
    }
    for (auto f : m.faces()) {
        std::array<std::uint32_t, 3> tri{};
        std::size_t k = 0;
        for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) tri[k++] = number[v];
        out.triangles.push_back(tri);
    }
    return out;
}

}  // namespace iris::geometry
