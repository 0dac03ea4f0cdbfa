#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include "iris/geometry/mesh.hpp"

namespace iris::geometry {
namespace {

void append(triangle_mesh& dst, const triangle_mesh& src, bool flip) {
    const auto base = static_cast<std::uint32_t>(dst.positions.size());
    dst.positions.insert(dst.positions.end(), src.positions.begin(), src.positions.end());
    for (auto t : src.triangles) {
        if (flip) std::swap(t[1], t[2]);
        dst.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    }
}

}  // namespace

triangle_mesh make_box(glm::vec3 lo, glm::vec3 hi) {
    if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z))
        throw error("box: max must exceed min on every axis");
    triangle_mesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
    // faces as CCW quads seen from outside
    const std::array<std::array<std::uint32_t, 4>, 6> faces{{{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                                             {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}}};
    for (const auto& f : faces) {
        m.triangles.push_back({f[0], f[1], f[2]});
        m.triangles.push_back({f[0], f[2], f[3]});
    }
    return m;
}

triangle_mesh make_cube(glm::vec3 c, float edge) {
    if (!(edge > 0.0f)) throw error("cube: edge must be > 0");
    const glm::vec3 h(0.5f * edge);
    return make_box(c - h, c + h);
}

triangle_mesh make_prism(glm::vec3 c, float side, float depth) {
    if (!(side > 0.0f) || !(depth > 0.0f)) throw error("prism: side and depth must be > 0");
    const float r = side / std::sqrt(3.0f);  // circumradius
    triangle_mesh m;
    for (float z : {-0.5f * depth, 0.5f * depth})
        for (int k = 0; k < 3; ++k) {
            const float a = 1.5707963f + 2.0943951f * static_cast<float>(k);  // 90°, 210°, 330°: CCW
            m.positions.push_back(c + glm::vec3(r * std::cos(a), r * std::sin(a), z));
        }
    m.triangles.push_back({0, 2, 1});  // back cap (z−), facing −z
    m.triangles.push_back({3, 4, 5});  // front cap (z+), facing +z
    for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t n = (k + 1) % 3;
        m.triangles.push_back({k, n, n + 3});
        m.triangles.push_back({k, n + 3, k + 3});
    }
    return m;
}

triangle_mesh make_hollow_cube(glm::vec3 c, float outer, float inner) {
    if (!(inner > 0.0f && inner < outer)) throw error("hollow cube: need 0 < inner edge < outer edge");
    triangle_mesh m = make_cube(c, outer);
    append(m, make_cube(c, inner), true);  // the cavity's walls face into the cavity
    return m;
}

triangle_mesh make_quad(glm::vec3 c, glm::vec3 u, glm::vec3 v) {
    if (!(glm::length(glm::cross(u, v)) > 0.0f)) throw error("quad: edges must span an area");
    triangle_mesh m;
    m.positions = {c - 0.5f * u - 0.5f * v, c + 0.5f * u - 0.5f * v, c + 0.5f * u + 0.5f * v, c - 0.5f * u + 0.5f * v};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

glm::mat4 make_transform(glm::vec3 t, glm::vec3 r, glm::vec3 s) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), t);
    m = glm::rotate(m, glm::radians(r.z), {0, 0, 1});
    m = glm::rotate(m, glm::radians(r.y), {0, 1, 0});
    m = glm::rotate(m, glm::radians(r.x), {1, 0, 0});
    return glm::scale(m, s);
}

triangle_mesh transformed(const triangle_mesh& in, const glm::mat4& t) {
    triangle_mesh m = in;
    for (auto& p : m.positions) p = glm::vec3(t * glm::vec4(p, 1.0f));
    if (glm::determinant(glm::mat3(t)) < 0.0f)
        for (auto& tri : m.triangles) std::swap(tri[1], tri[2]);
    return m;
}

double surface_area(const triangle_mesh& m) {
    double a = 0.0;
    for (const auto& t : m.triangles)
        a += 0.5 * static_cast<double>(glm::length(glm::cross(m.positions[t[1]] - m.positions[t[0]],
                                                                m.positions[t[2]] - m.positions[t[0]])));
    return a;
}

}  // namespace iris::geometry
