// Every builder's output is a valid closed solid (CGAL check), has the closed-form area
// and volume, survives rotations, translations and mirrors, and is built bit-identically
// twice.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <iris/geometry/mesh.hpp>

#include "mesh_io.hpp"

namespace {

namespace g = iris::geometry;

struct named_mesh {
    std::string name;
    std::function<g::triangle_mesh()> build;
};

// The solids: one of each builder, plus a general prism given in both windings.
std::vector<named_mesh> solids() {
    return {
        {"cube", [] { return g::make_cube({0.5f, -1.0f, 2.0f}, 1.5f); }},
        {"box", [] { return g::make_box({-1.0f, 0.0f, 0.25f}, {2.0f, 0.5f, 3.0f}); }},
        {"prism", [] { return g::make_prism({0.0f, 1.0f, 0.0f}, 2.0f, 0.75f); }},
        {"general_prism_ccw", [] { return g::make_prism({glm::vec3(0, 0, 0), glm::vec3(2, 0, 0), glm::vec3(0.5f, 1, 0.2f)}, {0.3f, 0.2f, 1.5f}); }},
        {"general_prism_cw", [] { return g::make_prism({glm::vec3(0, 0, 0), glm::vec3(0.5f, 1, 0.2f), glm::vec3(2, 0, 0)}, {0.3f, 0.2f, 1.5f}); }},
        {"hollow_cube", [] { return g::make_hollow_cube({1.0f, 2.0f, 3.0f}, 2.0f, 1.0f); }},
        {"sphere0", [] { return g::make_sphere({0, 0, 0}, 1.0f, 0); }},
        {"sphere3", [] { return g::make_sphere({0.25f, 0, -1}, 2.0f, 3); }},
    };
}

// Rotations about all three axes, translations, non-uniform scales and a mirror.
std::vector<glm::mat4> transforms() {
    return {
        g::make_transform({0, 0, 0}, {0, 0, 0}, {1, 1, 1}),
        g::make_transform({3, -2, 1}, {0, 0, 0}, {1, 1, 1}),
        g::make_transform({0, 0, 0}, {30, 45, 60}, {1, 1, 1}),
        g::make_transform({-1.5f, 4, 0.5f}, {17, -123, 271}, {1, 1, 1}),
        g::make_transform({0.1f, 0.2f, 0.3f}, {90, 0, 0}, {2, 0.5f, 1.25f}),
        g::make_transform({0, 1, 0}, {10, 20, 30}, {-1, 1, 1}),  // mirror: winding must flip
    };
}

TEST(Builders, EverySolidPassesTheCgalCheckInEveryPose) {
    for (const auto& s : solids())
        for (std::size_t k = 0; const auto& m : transforms()) {
            const auto mesh = g::transformed(s.build(), m);
            const auto c = g::check_mesh(mesh);
            EXPECT_TRUE(c.closed) << s.name << " pose " << k << ": " << c.detail;
            EXPECT_TRUE(c.manifold) << s.name << " pose " << k << ": " << c.detail;
            EXPECT_TRUE(c.outward) << s.name << " pose " << k << ": " << c.detail;
            EXPECT_TRUE(c.self_intersection_free) << s.name << " pose " << k << ": " << c.detail;
            EXPECT_TRUE(c.ok());
            EXPECT_TRUE(c.detail.empty()) << c.detail;
            ++k;
        }
}

TEST(Builders, OpenQuadsAreManifoldButNotClosed) {
    for (const auto& q : {g::make_quad({0, 1, 0}, {2, 0, 0}, {0, 0, 1}), g::make_rectangle({0, 0, 0}, {1, 2}, {0.3f, -1, 0.2f})}) {
        const auto c = g::check_mesh(q);
        EXPECT_EQ(q.triangle_count(), 2u);
        EXPECT_FALSE(c.closed);
        EXPECT_TRUE(c.manifold);
        EXPECT_TRUE(c.self_intersection_free);
        EXPECT_FALSE(c.outward);  // undecidable without a bounded volume
        EXPECT_FALSE(c.ok());
        EXPECT_NE(c.detail.find("4 boundary edge"), std::string::npos) << c.detail;
    }
}

glm::vec3 normal(const g::triangle_mesh& m, std::size_t t) {
    const auto& tri = m.triangles[t];
    return glm::cross(m.positions[tri[1]] - m.positions[tri[0]], m.positions[tri[2]] - m.positions[tri[0]]);
}

TEST(Builders, QuadAndRectangleFaceTheirNormal) {
    const auto q = g::make_quad({1, 2, 3}, {2, 0, 0}, {0, 3, 0});
    EXPECT_NEAR(g::surface_area(q), 6.0, 1e-6);
    for (std::size_t t = 0; t < 2; ++t) EXPECT_GT(normal(q, t).z, 0.0f);  // u × v = +z
    // A floor: normal +y, size.x along x and size.y along z.
    const auto floor = g::make_rectangle({0, -1, 0}, {4, 2}, {0, 1, 0});
    EXPECT_NEAR(g::surface_area(floor), 8.0, 1e-6);
    for (const auto& p : floor.positions) {
        EXPECT_FLOAT_EQ(p.y, -1.0f);
        EXPECT_FLOAT_EQ(std::abs(p.x), 2.0f);
        EXPECT_FLOAT_EQ(std::abs(p.z), 1.0f);
    }
    for (std::size_t t = 0; t < 2; ++t) EXPECT_GT(glm::normalize(normal(floor, t)).y, 0.999f);
    const glm::vec3 n = glm::normalize(glm::vec3(1, -2, 0.5f));
    const auto tilted = g::make_rectangle({0, 0, 0}, {1, 1}, n);
    for (std::size_t t = 0; t < 2; ++t) EXPECT_GT(glm::dot(glm::normalize(normal(tilted, t)), n), 0.99999f);
}

TEST(Builders, AreasAndVolumesMatchClosedForms) {
    const double a = 1.5, b = 0.5, s = 2.0, d = 0.75;
    EXPECT_NEAR(g::surface_area(g::make_cube({1, 1, 1}, 1.5f)), 6 * a * a, 1e-5);
    EXPECT_NEAR(g::enclosed_volume(g::make_cube({1, 1, 1}, 1.5f)), a * a * a, 1e-5);
    EXPECT_NEAR(g::surface_area(g::make_box({0, 0, 0}, {1, 2, 3})), 2 * (2 + 6 + 3), 1e-5);
    EXPECT_NEAR(g::enclosed_volume(g::make_box({0, 0, 0}, {1, 2, 3})), 6.0, 1e-5);
    const double tri = std::sqrt(3.0) / 4 * s * s;
    EXPECT_NEAR(g::surface_area(g::make_prism({0, 0, 0}, 2.0f, 0.75f)), 2 * tri + 3 * s * d, 1e-5);
    EXPECT_NEAR(g::enclosed_volume(g::make_prism({0, 0, 0}, 2.0f, 0.75f)), tri * d, 1e-5);
    // The hollow cube: the cavity is subtracted, a³ − b³; both shells count for the area.
    EXPECT_NEAR(g::enclosed_volume(g::make_hollow_cube({0, 0, 0}, 1.5f, 0.5f)), a * a * a - b * b * b, 1e-5);
    EXPECT_NEAR(g::surface_area(g::make_hollow_cube({0, 0, 0}, 1.5f, 0.5f)), 6 * (a * a + b * b), 1e-5);
    // A general prism: |base| · (extrusion · base normal).
    EXPECT_NEAR(g::enclosed_volume(g::make_prism({glm::vec3(0, 0, 0), glm::vec3(2, 0, 0), glm::vec3(0, 1, 0)}, {0.5f, 0.5f, 3})), 3.0, 1e-5);
    // The icosphere is inscribed: below the sphere's area and volume, and converging.
    double last_area = 0, last_volume = 0;
    for (unsigned k = 0; k <= 4; ++k) {
        const auto sphere = g::make_sphere({0, 0, 0}, 1.0f, k);
        EXPECT_EQ(sphere.triangle_count(), 20u << (2 * k));
        const double area = g::surface_area(sphere), volume = g::enclosed_volume(sphere);
        EXPECT_LT(area, 4 * std::numbers::pi);
        EXPECT_LT(volume, 4 * std::numbers::pi / 3);
        EXPECT_GT(area, last_area);
        EXPECT_GT(volume, last_volume);
        last_area = area;
        last_volume = volume;
    }
    EXPECT_NEAR(last_area, 4 * std::numbers::pi, 0.01 * 4 * std::numbers::pi);
}

TEST(Builders, TransformsScaleVolumesAndKeepThemPositive) {
    const auto cube = g::make_cube({0, 0, 0}, 1.0f);
    for (const auto& m : transforms()) {
        const double det = std::abs(static_cast<double>(glm::determinant(glm::mat3(m))));
        EXPECT_NEAR(g::enclosed_volume(g::transformed(cube, m)), det, 1e-5 * det);
        EXPECT_NEAR(g::enclosed_volume(g::transformed(g::make_hollow_cube({0, 0, 0}, 2.0f, 1.0f), m)), 7 * det, 1e-4 * det);
    }
}

TEST(Builders, MakeTransformAppliesScaleThenXThenYThenZThenTranslation) {
    const auto apply = [](const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); };
    // Rx(90°) takes +y to +z; Ry(90°) then takes +z to +x.
    const glm::vec3 p = apply(g::make_transform({0, 0, 0}, {90, 90, 0}, {1, 1, 1}), {0, 1, 0});
    EXPECT_NEAR(p.x, 1.0f, 1e-6f);
    EXPECT_NEAR(p.y, 0.0f, 1e-6f);
    EXPECT_NEAR(p.z, 0.0f, 1e-6f);
    // Scale before rotation: (1,0,0) scaled by x2 then Rz(90°) → (0,2,0); then translated.
    const glm::vec3 q = apply(g::make_transform({1, 1, 1}, {0, 0, 90}, {2, 3, 4}), {1, 0, 0});
    EXPECT_NEAR(q.x, 1.0f, 1e-6f);
    EXPECT_NEAR(q.y, 3.0f, 1e-6f);
    EXPECT_NEAR(q.z, 1.0f, 1e-6f);
}

TEST(Builders, HollowCubeHasItsInnerWallsFacingTheCavity) {
    const glm::vec3 c(1, 2, 3);
    const auto m = g::make_hollow_cube(c, 2.0f, 1.0f);
    EXPECT_EQ(m.positions.size(), 16u);
    EXPECT_EQ(m.triangle_count(), 24u);
    int inner = 0;
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
        const auto& tri = m.triangles[t];
        const glm::vec3 centroid = (m.positions[tri[0]] + m.positions[tri[1]] + m.positions[tri[2]]) / 3.0f;
        const glm::vec3 r = centroid - c;
        const bool on_inner = std::max({std::abs(r.x), std::abs(r.y), std::abs(r.z)}) < 0.75f;
        inner += on_inner;
        // outer walls point away from the centre, inner walls towards it
        EXPECT_EQ(glm::dot(normal(m, t), r) < 0.0f, on_inner) << t;
    }
    EXPECT_EQ(inner, 12);
}

TEST(Builders, BuildingTwiceGivesTheSameBytes) {
    for (const auto& s : solids()) {
        const std::string first = iris::test::to_off(g::transformed(s.build(), transforms()[3]));
        const std::string second = iris::test::to_off(g::transformed(s.build(), transforms()[3]));
        EXPECT_EQ(first, second) << s.name;
        EXPECT_GT(first.size(), 100u);
    }
}

TEST(Builders, BadArgumentsThrowGeometryErrors) {
    const float nan = std::nanf("");
    EXPECT_THROW(g::make_box({0, 0, 0}, {1, -1, 1}), g::error);
    EXPECT_THROW(g::make_box({0, 0, 0}, {1, 1, nan}), g::error);
    EXPECT_THROW(g::make_cube({0, 0, 0}, 0.0f), g::error);
    EXPECT_THROW(g::make_prism({0, 0, 0}, -1.0f, 1.0f), g::error);
    EXPECT_THROW(g::make_prism({glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(2, 0, 0)}, {0, 0, 1}), g::error);  // collinear
    EXPECT_THROW(g::make_prism({glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}, {1, 1, 0}), g::error);  // in plane
    EXPECT_THROW(g::make_hollow_cube({0, 0, 0}, 1.0f, 2.0f), g::error);
    EXPECT_THROW(g::make_hollow_cube({0, 0, 0}, 1.0f, 1.0f), g::error);
    EXPECT_THROW(g::make_hollow_cube({0, 0, 0}, 1.0f, 0.0f), g::error);
    EXPECT_THROW(g::make_quad({0, 0, 0}, {1, 0, 0}, {2, 0, 0}), g::error);
    EXPECT_THROW(g::make_rectangle({0, 0, 0}, {1, 0}, {0, 1, 0}), g::error);
    EXPECT_THROW(g::make_rectangle({0, 0, 0}, {1, 1}, {0, 0, 0}), g::error);
    EXPECT_THROW(g::make_sphere({0, 0, 0}, 1.0f, 8), g::error);
    EXPECT_THROW(g::make_sphere({0, 0, 0}, -1.0f, 1), g::error);
    EXPECT_THROW(g::transformed(g::make_cube({0, 0, 0}, 1.0f), g::make_transform({}, {}, {1, 0, 1})), g::error);
    EXPECT_THROW(g::transformed(g::make_cube({0, 0, 0}, 1.0f), g::make_transform({nan, 0, 0}, {}, {1, 1, 1})), g::error);
    EXPECT_THROW(g::enclosed_volume(g::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0})), g::error);
}

// Shading normals move with the surface (the inverse transpose keeps them perpendicular to
// it under a non-uniform scale), uvs are carried unchanged.
TEST(Builders, TransformedCarriesNormalsAndUvs) {
    g::triangle_mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.triangles = {{0, 1, 2}};
    const glm::vec3 n = glm::normalize(glm::vec3(1, 1, 1));
    m.normals = {n, n, n};
    m.uvs = {{0, 0}, {1, 0}, {0.5f, 2}};
    const glm::mat4 t = g::make_transform({1, 2, 3}, {30, 10, 0}, {2, 0.5f, 3});
    const auto out = g::transformed(m, t);
    ASSERT_EQ(out.normals.size(), 3u);
    ASSERT_EQ(out.uvs.size(), 3u);
    const glm::vec3 tangent = glm::normalize(glm::vec3(1, -1, 0));  // perpendicular to n
    const glm::vec3 moved = glm::mat3(t) * tangent;
    EXPECT_NEAR(glm::dot(glm::normalize(out.normals[0]), glm::normalize(moved)), 0.0f, 1e-6f);
    EXPECT_EQ(out.uvs[2].y, 2.0f);
}

}  // namespace
