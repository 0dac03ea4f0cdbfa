// ray_shooter: CGAL's AABB tree as an Embree-independent reference (the second of the two
// CGAL translation units of iris::geometry).
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "iris/geometry/ray_shooting.hpp"

namespace iris::geometry {
namespace {

using kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using point = kernel::Point_3;
using triangle = kernel::Triangle_3;
using primitive = CGAL::AABB_triangle_primitive<kernel, std::vector<triangle>::const_iterator>;
using tree = CGAL::AABB_tree<CGAL::AABB_traits<kernel, primitive>>;

point to_point(const glm::dvec3& p) { return {p.x, p.y, p.z}; }

}  // namespace

struct ray_shooter::impl {
    std::vector<triangle> triangles;   // non-degenerate ones only (CGAL's ray/triangle test needs a plane)
    std::vector<std::uint32_t> index;  // their indices in the input mesh
    tree aabb;
};

ray_shooter::ray_shooter(const triangle_mesh& mesh) : m_impl(std::make_unique<impl>()) {
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3 p = mesh.positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw error("ray_shooter: vertex " + std::to_string(i) + " is not finite");
    }
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        for (const std::uint32_t v : tri)
            if (v >= mesh.positions.size()) throw error("ray_shooter: triangle " + std::to_string(t) + " indexes a missing vertex");
        const triangle k(to_point(mesh.positions[tri[0]]), to_point(mesh.positions[tri[1]]), to_point(mesh.positions[tri[2]]));
        if (k.is_degenerate()) continue;
        m_impl->triangles.push_back(k);
        m_impl->index.push_back(static_cast<std::uint32_t>(t));
    }
    // Built after the vector is final: the primitives hold iterators into it.
    m_impl->aabb.insert(m_impl->triangles.cbegin(), m_impl->triangles.cend());
    m_impl->aabb.build();
}

ray_shooter::~ray_shooter() = default;
ray_shooter::ray_shooter(ray_shooter&&) noexcept = default;
ray_shooter& ray_shooter::operator=(ray_shooter&&) noexcept = default;

std::optional<reference_hit> ray_shooter::first_hit(const glm::dvec3& origin, const glm::dvec3& direction) const {
    const auto finite = [](const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    if (!finite(origin) || !finite(direction) || direction == glm::dvec3(0.0) || m_impl->triangles.empty())
        return std::nullopt;
    const point o = to_point(origin);
    const kernel::Vector_3 d(direction.x, direction.y, direction.z);
    const auto found = m_impl->aabb.first_intersection(kernel::Ray_3(o, d));
    if (!found) return std::nullopt;
    // A point, or, for a ray lying in the triangle's plane, a segment whose nearer end
    // is where the ray enters the triangle.
    point p;
    if (const point* q = boost::get<point>(&found->first)) {
        p = *q;
    } else if (const kernel::Segment_3* s = boost::get<kernel::Segment_3>(&found->first)) {
        p = CGAL::compare_distance_to_point(o, s->source(), s->target()) == CGAL::SMALLER ? s->source() : s->target();
    } else {
        return std::nullopt;
    }
    const auto slot = static_cast<std::size_t>(found->second - m_impl->triangles.cbegin());
    const triangle& tri = m_impl->triangles[slot];
    double edge2 = CGAL::squared_distance(p, kernel::Segment_3(tri[0], tri[1]));
    edge2 = std::min(edge2, CGAL::squared_distance(p, kernel::Segment_3(tri[1], tri[2])));
    edge2 = std::min(edge2, CGAL::squared_distance(p, kernel::Segment_3(tri[2], tri[0])));
    const kernel::Vector_3 op = p - o;
    return reference_hit{(op * d) / d.squared_length(), m_impl->index[slot], std::sqrt(edge2)};
}

}  // namespace iris::geometry
