// The CGAL-free builders and transforms of iris::geometry (target iris::geometry_mesh).
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <glm/vector_relational.hpp>

#include "iris/geometry/triangle_mesh.hpp"

namespace iris::geometry {
namespace {

bool finite(glm::vec3 v) noexcept { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string str(glm::vec3 v) {
    return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
}

// Two triangles of a quad a, b, c, d given counter-clockwise around its normal.
void add_quad(triangle_mesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    m.triangles.push_back({a, b, c});
    m.triangles.push_back({a, c, d});
}

}  // namespace

double surface_area(const triangle_mesh& mesh) noexcept {
    double area = 0.0;
    for (const auto& t : mesh.triangles) {
        const glm::dvec3 p0(mesh.positions[t[0]]);
        area += 0.5 * glm::length(glm::cross(glm::dvec3(mesh.positions[t[1]]) - p0, glm::dvec3(mesh.positions[t[2]]) - p0));
    }
    return area;
}

glm::mat4 make_transform(glm::vec3 translate, glm::vec3 rotate_degrees_xyz, glm::vec3 scale) {
    // glm::rotate/scale/translate post-multiply, so the calls read outermost first.
    glm::mat4 m = glm::translate(glm::mat4(1.0f), translate);
    m = glm::rotate(m, glm::radians(rotate_degrees_xyz.z), glm::vec3(0.0f, 0.0f, 1.0f));
    m = glm::rotate(m, glm::radians(rotate_degrees_xyz.y), glm::vec3(0.0f, 1.0f, 0.0f));
    m = glm::rotate(m, glm::radians(rotate_degrees_xyz.x), glm::vec3(1.0f, 0.0f, 0.0f));
    return glm::scale(m, scale);
}

triangle_mesh transformed(const triangle_mesh& mesh, const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        if (!finite(glm::vec3(m[c])) || !std::isfinite(m[c][3])) throw error("transform: the matrix is not finite");
    const float det = glm::determinant(glm::mat3(m));
    if (!(det != 0.0f) || !std::isfinite(det)) throw error("transform: the matrix is singular (determinant 0)");
    triangle_mesh out;
    out.positions.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) out.positions.emplace_back(m * glm::vec4(p, 1.0f));
    out.triangles = mesh.triangles;
    // normals transform by the inverse transpose (they stay perpendicular to the surface);
    // a mirror needs no flip for them, as the shading normal is turned to the winding's side
    const glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(m)));
    out.normals.reserve(mesh.normals.size());
    for (const glm::vec3& n : mesh.normals) out.normals.push_back(nm * n);
    out.uvs = mesh.uvs;
    // A mirror turns counter-clockwise into clockwise: swap two corners to stay outward.
    if (det < 0.0f)
        for (auto& t : out.triangles) std::swap(t[1], t[2]);
    return out;
}

triangle_mesh make_box(glm::vec3 min, glm::vec3 max) {
    if (!finite(min) || !finite(max) || !glm::all(glm::lessThan(min, max)))
        throw error("box: need finite min < max on every axis, got min " + str(min) + ", max " + str(max));
    triangle_mesh m;
    // Vertex i has bit 0 → x, bit 1 → y, bit 2 → z at max.
    for (int i = 0; i < 8; ++i)
        m.positions.emplace_back((i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z);
    add_quad(m, 0, 4, 6, 2);  // −x
    add_quad(m, 1, 3, 7, 5);  // +x
    add_quad(m, 0, 1, 5, 4);  // −y
    add_quad(m, 2, 6, 7, 3);  // +y
    add_quad(m, 0, 2, 3, 1);  // −z
    add_quad(m, 4, 5, 7, 6);  // +z
    return m;
}

triangle_mesh make_cube(glm::vec3 centre, float edge) {
    if (!(edge > 0.0f) || !std::isfinite(edge)) throw error("cube: the edge must be finite and > 0, got " + std::to_string(edge));
    const glm::vec3 h(0.5f * edge);
    return make_box(centre - h, centre + h);
}

triangle_mesh make_prism(const std::array<glm::vec3, 3>& base, glm::vec3 extrusion) {
    for (const auto& p : base)
        if (!finite(p)) throw error("prism: the base triangle has a non-finite corner " + str(p));
    if (!finite(extrusion)) throw error("prism: the extrusion is not finite");
    const glm::vec3 n = glm::cross(base[1] - base[0], base[2] - base[0]);
    const float along = glm::dot(n, extrusion);
    // Relative test: the extrusion must leave the base plane by a visible angle, not just
    // by rounding noise.
    if (!(glm::length(n) > 0.0f) || !(std::abs(along) > 1e-6f * glm::length(n) * glm::length(extrusion)))
        throw error("prism: the base triangle is degenerate or the extrusion lies in its plane");
    // Order the base counter-clockwise around the extrusion; the bottom cap then faces −e.
    const std::array<glm::vec3, 3> b = along > 0.0f ? base : std::array<glm::vec3, 3>{base[0], base[2], base[1]};
    triangle_mesh m;
    for (const auto& p : b) m.positions.push_back(p);
    for (const auto& p : b) m.positions.push_back(p + extrusion);
    m.triangles.push_back({0, 2, 1});  // bottom, facing −e
    m.triangles.push_back({3, 4, 5});  // top, facing +e
    // Side i→j: outward normal (pj − pi) × e for a base counter-clockwise around e.
    for (std::uint32_t i = 0; i < 3; ++i) {
        const std::uint32_t j = (i + 1) % 3;
        add_quad(m, i, j, j + 3, i + 3);
    }
    return m;
}

triangle_mesh make_prism(glm::vec3 centre, float side, float depth) {
    if (!(side > 0.0f) || !(depth > 0.0f) || !std::isfinite(side) || !std::isfinite(depth))
        throw error("prism: side and depth must be finite and > 0");
    const float r = side / std::sqrt(3.0f);  // circumradius; the centroid is the circumcentre
    const float z = centre.z - 0.5f * depth;
    const std::array<glm::vec3, 3> base{glm::vec3(centre.x, centre.y + r, z),
                                        glm::vec3(centre.x - 0.5f * side, centre.y - 0.5f * r, z),
                                        glm::vec3(centre.x + 0.5f * side, centre.y - 0.5f * r, z)};
    return make_prism(base, glm::vec3(0.0f, 0.0f, depth));
}

triangle_mesh make_quad(glm::vec3 centre, glm::vec3 u, glm::vec3 v) {
    if (!finite(centre) || !finite(u) || !finite(v) || !(glm::length(glm::cross(u, v)) > 0.0f))
        throw error("quad: the centre and edges must be finite and the edges must span an area");
    triangle_mesh m;
    m.positions = {centre - 0.5f * u - 0.5f * v, centre + 0.5f * u - 0.5f * v, centre + 0.5f * u + 0.5f * v,
                   centre - 0.5f * u + 0.5f * v};
    add_quad(m, 0, 1, 2, 3);
    return m;
}

triangle_mesh make_rectangle(glm::vec3 centre, glm::vec2 size, glm::vec3 normal) {
    if (!(size.x > 0.0f) || !(size.y > 0.0f) || !std::isfinite(size.x) || !std::isfinite(size.y))
        throw error("rectangle: the size must be finite and > 0");
    if (!finite(normal) || !(glm::length(normal) > 0.0f)) throw error("rectangle: the normal must be finite and non-zero");
    const glm::vec3 n = glm::normalize(normal);
    int axis = 0;  // the first world axis least aligned with n (ties keep the earlier axis)
    for (int k = 1; k < 3; ++k)
        if (std::abs(n[k]) < std::abs(n[axis])) axis = k;
    glm::vec3 a(0.0f);
    a[axis] = 1.0f;
    const glm::vec3 u = glm::normalize(a - glm::dot(a, n) * n);
    const glm::vec3 v = glm::cross(n, u);
    return make_quad(centre, size.x * u, size.y * v);
}

triangle_mesh make_sphere(glm::vec3 centre, float radius, unsigned subdivisions) {
    if (!(radius > 0.0f) || !std::isfinite(radius) || !finite(centre))
        throw error("sphere: the radius must be finite and > 0");
    if (subdivisions > 7) throw error("sphere: at most 7 subdivisions (327680 triangles), got " + std::to_string(subdivisions));
    // The icosahedron: three golden rectangles; its faces are counter-clockwise from outside.
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<glm::dvec3> p{{-1, g, 0}, {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                              {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    for (auto& q : p) q = glm::normalize(q);
    std::vector<std::array<std::uint32_t, 3>> t{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                                {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                                {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                                {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (unsigned s = 0; s < subdivisions; ++s) {
        // One midpoint per edge, shared by both triangles on it, so the mesh stays closed.
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoint;
        const auto mid = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto [it, inserted] = midpoint.try_emplace(key, static_cast<std::uint32_t>(p.size()));
            if (inserted) p.push_back(glm::normalize(p[a] + p[b]));
            return it->second;
        };
        std::vector<std::array<std::uint32_t, 3>> next;
        next.reserve(4 * t.size());
        for (const auto& f : t) {
            const std::uint32_t ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
            next.push_back({f[0], ab, ca});
            next.push_back({f[1], bc, ab});
            next.push_back({f[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        t = std::move(next);
    }
    triangle_mesh m;
    m.positions.reserve(p.size());
    for (const auto& q : p) m.positions.push_back(centre + radius * glm::vec3(q));
    m.triangles = std::move(t);
    return m;
}

}  // namespace iris::geometry
