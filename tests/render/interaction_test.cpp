// The surface interaction against hand-computed values: the point, the geometric normal
// on the winding's side, the shading frame around the interpolated vertex normal (turned
// to ng's side, ng where it degenerates), the texture coordinates (the mesh's, or pbrt-v4's
// default), and no interaction for a degenerate triangle.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include <iris/render/interaction.hpp>

namespace {

/// One triangle in the plane z = 1, wound counter-clockwise seen from +z.
iris::scene_desc one_triangle() {
    iris::scene_desc s;
    iris::shape_desc sh;
    sh.mesh.positions = {{0, 0, 1}, {2, 0, 1}, {0, 2, 1}};
    sh.mesh.triangles = {{0, 1, 2}};
    s.shapes.push_back(sh);
    return s;
}

iris::ray_hit hit_of(const iris::scene_desc& s, float b1, float b2) {
    const auto& m = s.shapes[0].mesh;
    const auto& t = m.triangles[0];
    iris::ray_hit h;
    h.t = 3.0f;
    h.u = b1;
    h.v = b2;
    h.geometric_normal = glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
    return h;
}

void expect_vec(const glm::vec3& a, const glm::vec3& b, float tol, const char* what) {
    EXPECT_NEAR(a.x, b.x, tol) << what;
    EXPECT_NEAR(a.y, b.y, tol) << what;
    EXPECT_NEAR(a.z, b.z, tol) << what;
}

void expect_orthonormal(const iris::frame& f) {
    EXPECT_NEAR(glm::length(f.s), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(f.t), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(f.n), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(f.s, f.t), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(f.s, f.n), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(f.t, f.n), 0.0f, 1e-6f);
    expect_vec(glm::cross(f.s, f.t), f.n, 1e-6f, "right-handed");
}

TEST(Interaction, WithoutNormalsOrUvs) {
    const auto s = one_triangle();
    const glm::vec3 dir = glm::normalize(glm::vec3(0.3f, -0.2f, -1.0f));
    const auto si = iris::make_interaction(s, hit_of(s, 0.25f, 0.5f), dir);
    ASSERT_TRUE(si.has_value());
    expect_vec(si->sp.p, {0.5f, 1.0f, 1.0f}, 1e-6f, "point");
    EXPECT_GT(si->sp.error.z, 0.0f);  // the error bound is there (its size: frame tests)
    expect_vec(si->ng, {0, 0, 1}, 0.0f, "ng");
    expect_vec(si->shading.n, si->ng, 0.0f, "ns = ng without normals");
    expect_orthonormal(si->shading);
    EXPECT_FLOAT_EQ(si->uv.x, 0.75f);  // pbrt-v4's default: (b1 + b2, b2)
    EXPECT_FLOAT_EQ(si->uv.y, 0.5f);
    expect_vec(si->wo, -dir, 0.0f, "wo");
    EXPECT_EQ(si->t, 3.0f);
    // local ↔ world round trip, and ns is +z locally
    const glm::vec3 w = glm::normalize(glm::vec3(0.1f, 0.7f, -0.4f));
    expect_vec(si->to_world(si->to_local(w)), w, 1e-6f, "round trip");
    expect_vec(si->to_local(si->shading.n), {0, 0, 1}, 1e-6f, "n is +z");
    EXPECT_NEAR(si->to_local(w).z, glm::dot(w, si->ng), 1e-7f);
}

TEST(Interaction, InterpolatesNormalsAndUvs) {
    auto s = one_triangle();
    auto& m = s.shapes[0].mesh;
    m.normals = {{0, 0, 1}, {1, 0, 1}, {0, 0, 2}};  // not unit: normalised after interpolation
    m.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 4.0f}};
    const float b1 = 0.5f, b2 = 0.25f, b0 = 1.0f - b1 - b2;
    const auto si = iris::make_interaction(s, hit_of(s, b1, b2), {0, 0, -1});
    ASSERT_TRUE(si.has_value());
    const glm::vec3 expected = glm::normalize(b0 * m.normals[0] + b1 * m.normals[1] + b2 * m.normals[2]);
    expect_vec(si->shading.n, expected, 1e-6f, "interpolated ns");
    expect_vec(si->ng, {0, 0, 1}, 0.0f, "ng stays the triangle's");
    expect_orthonormal(si->shading);
    EXPECT_FLOAT_EQ(si->uv.x, 0.5f);
    EXPECT_FLOAT_EQ(si->uv.y, 1.0f);
}

TEST(Interaction, ShadingNormalTurnedToTheWindingsSide) {
    auto s = one_triangle();
    s.shapes[0].mesh.normals = {{0.2f, 0, -1}, {0.2f, 0, -1}, {0.2f, 0, -1}};  // against the winding
    const auto si = iris::make_interaction(s, hit_of(s, 0.2f, 0.2f), {0, 0, -1});
    ASSERT_TRUE(si.has_value());
    expect_vec(si->shading.n, -glm::normalize(glm::vec3(0.2f, 0, -1)), 1e-6f, "flipped");
    EXPECT_GT(glm::dot(si->shading.n, si->ng), 0.0f);
}

TEST(Interaction, DegenerateInterpolationFallsBackToNg) {
    auto s = one_triangle();
    s.shapes[0].mesh.normals = {{1, 0, 0}, {-1, 0, 0}, {1, 0, 0}};
    // b0 = b1 = 0.5, b2 = 0: the normals cancel exactly
    const auto si = iris::make_interaction(s, hit_of(s, 0.5f, 0.0f), {0, 0, -1});
    ASSERT_TRUE(si.has_value());
    expect_vec(si->shading.n, si->ng, 0.0f, "cancelled normals");
}

TEST(Interaction, DegenerateTriangleHasNone) {
    iris::scene_desc s;
    iris::shape_desc sh;
    sh.mesh.positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};  // collinear
    sh.mesh.triangles = {{0, 1, 2}};
    s.shapes.push_back(sh);
    iris::ray_hit h;  // Ng = 0
    EXPECT_FALSE(iris::make_interaction(s, h, {0, 0, -1}).has_value());
    h.geometric_normal = {std::numeric_limits<float>::quiet_NaN(), 0, 0};
    EXPECT_FALSE(iris::make_interaction(s, h, {0, 0, -1}).has_value());
}

}  // namespace
