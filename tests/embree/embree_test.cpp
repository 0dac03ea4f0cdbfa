// iris::embree against closed forms on iris::geometry meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <type_traits>

#include <glm/geometric.hpp>

#include <iris/embree/embree.hpp>
#include <iris/geometry/mesh.hpp>
#include <iris/render/random.hpp>

namespace {

static_assert(!std::is_copy_constructible_v<iris::embree::device>);
static_assert(!std::is_copy_constructible_v<iris::embree::scene>);
static_assert(std::is_nothrow_move_constructible_v<iris::embree::scene>);

TEST(Embree, HitsACubeAtTheRightDistanceWithOutwardNormal) {
    iris::embree::device dev;
    iris::embree::scene s(dev);
    EXPECT_EQ(s.add_mesh(iris::geometry::make_cube({0, 0, 0}, 2.0f)), 0u);
    EXPECT_EQ(s.add_mesh(iris::geometry::make_prism({5, 0, 0}, 1.0f, 1.0f)), 1u);
    s.commit();
    const auto h = s.intersect({0, 0, 5}, {0, 0, -1}, 0.0f, 100.0f);
    ASSERT_TRUE(h.has_value());
    EXPECT_EQ(h->geom_id, 0u);
    EXPECT_NEAR(h->t, 4.0f, 1e-5f);
    // Embree's Ng for a CCW-from-outside triangle: its sign convention vs (v1−v0)×(v2−v0)
    const auto mesh = iris::geometry::make_cube({0, 0, 0}, 2.0f);
    const auto& tri = mesh.triangles[h->prim_id];
    const glm::vec3 ours = glm::cross(mesh.positions[tri[1]] - mesh.positions[tri[0]], mesh.positions[tri[2]] - mesh.positions[tri[0]]);
    EXPECT_GT(ours.z, 0.0f);  // outward (+z face)
    EXPECT_NE(glm::dot(ours, h->geometric_normal), 0.0f);
    EXPECT_FALSE(s.intersect({0, 0, 5}, {0, 0, 1}, 0.0f, 100.0f).has_value());
    EXPECT_TRUE(s.occluded({0, 0, 5}, {0, 0, -1}, 0.0f, 100.0f));
    EXPECT_FALSE(s.occluded({0, 0, 5}, {0, 0, -1}, 0.0f, 3.9f));
    const auto p = s.intersect({5, 0, 5}, {0, 0, -1}, 0.0f, 100.0f);
    ASSERT_TRUE(p.has_value());
    EXPECT_EQ(p->geom_id, 1u);
    EXPECT_NEAR(p->t, 4.5f, 1e-5f);
}

TEST(Embree, RandomRaysFromInsideAClosedCubeAlwaysHitIt) {
    // robust mode: no ray from inside slips through an edge or a vertex of a closed mesh
    iris::embree::device dev;
    iris::embree::scene s(dev);
    s.add_mesh(iris::geometry::transformed(iris::geometry::make_cube({0, 0, 0}, 1.0f),
                                          iris::geometry::make_transform({0.1f, 0, 0}, {30, 45, 10}, {1, 1, 1})));
    s.add_mesh(iris::geometry::make_hollow_cube({5, 5, 5}, 2.0f, 1.0f));
    s.commit();
    iris::sample_stream rng(3, 1, 4);
    for (int i = 0; i < 20000; ++i) {
        const float z = 2 * rng.next() - 1, phi = 6.2831853f * rng.next();
        const float r = std::sqrt(1 - z * z);
        const glm::vec3 d{r * std::cos(phi), r * std::sin(phi), z};
        EXPECT_TRUE(s.intersect({0.1f, 0, 0}, d, 0.0f, 10.0f).has_value()) << i;
        const auto h = s.intersect({5, 5, 5}, d, 0.0f, 10.0f);  // from the cavity: the inner wall at ≤ √3/2
        ASSERT_TRUE(h.has_value());
        EXPECT_LE(h->t, 0.8661f);
        EXPECT_GE(h->t, 0.4999f);
    }
}

TEST(Embree, BadInputIsAnError) {
    iris::embree::device dev;
    iris::embree::scene s(dev);
    iris::geometry::triangle_mesh broken;
    broken.positions = {{0, 0, 0}, {1, 0, 0}};
    broken.triangles = {{0, 1, 2}};
    EXPECT_THROW(s.add_mesh(broken), iris::embree::error);
    EXPECT_THROW(iris::geometry::make_box({0, 0, 0}, {1, -1, 1}), iris::geometry::error);
    EXPECT_THROW(iris::geometry::make_hollow_cube({0, 0, 0}, 1.0f, 2.0f), iris::geometry::error);
}

TEST(Geometry, AreasAndOrientation) {
    EXPECT_NEAR(iris::geometry::surface_area(iris::geometry::make_cube({0, 0, 0}, 2.0f)), 24.0, 1e-5);
    EXPECT_NEAR(iris::geometry::surface_area(iris::geometry::make_hollow_cube({0, 0, 0}, 2.0f, 1.0f)), 30.0, 1e-5);
    const double s = 1.0;
    EXPECT_NEAR(iris::geometry::surface_area(iris::geometry::make_prism({0, 0, 0}, 1.0f, 1.0f)),
                2 * std::sqrt(3.0) / 4 * s * s + 3 * s, 1e-5);
    // mirrored transforms keep triangles outward
    const auto m = iris::geometry::transformed(iris::geometry::make_cube({0, 0, 0}, 1.0f),
                                               iris::geometry::make_transform({}, {}, {-1, 1, 1}));
    double signed_volume = 0;  // divergence theorem: > 0 iff outward
    for (const auto& t : m.triangles)
        signed_volume += glm::dot(m.positions[t[0]], glm::cross(m.positions[t[1]], m.positions[t[2]])) / 6.0f;
    EXPECT_NEAR(signed_volume, 1.0, 1e-5);
}

}  // namespace
