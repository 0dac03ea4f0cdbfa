// iris::embree::intersector: shape index = position in scene_desc::shapes, t, barycentrics, and
// the geometric normal's orientation (v1 − v0) × (v2 − v0).
#include <gtest/gtest.h>

#include <type_traits>

#include <glm/geometric.hpp>

#include <iris/embree/intersector.hpp>
#include <iris/scene/scene.hpp>

namespace {

using embree_intersector = iris::embree::intersector;

static_assert(iris::Intersector<embree_intersector>);
static_assert(!std::is_copy_constructible_v<embree_intersector>);
static_assert(std::is_nothrow_move_constructible_v<embree_intersector>);

// shape 0: a floor quad at y = 0; shape 1: a unit cube centred at (0, 0.5, -5);
// shape 2: a 2 × 2 × 2 box centred at (4, 1, 0)
iris::scene_desc test_scene() {
    return iris::scene::parse_scene(R"({
      "camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
      "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
      "environment": {"spd": "D65"},
      "shapes": [
        {"type": "quad", "size": [20, 20], "material": "m"},
        {"type": "cube", "size": 1, "material": "m", "transform": [{"translate": [0, 0.5, -5]}]},
        {"type": "box", "size": [2, 2, 2], "material": "m", "transform": [{"translate": [4, 1, 0]}]}
      ]})",
                                    "test.json", {});
}

glm::vec3 triangle_normal(const iris::scene_desc& s, const iris::ray_hit& h) {
    const auto& m = s.shapes[h.shape].mesh;
    const auto& t = m.triangles[h.prim];
    return glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
}

TEST(EmbreeIntersector, HitsTheRightShapeAtTheRightDistanceWithOutwardNormal) {
    const auto s = test_scene();
    const embree_intersector tracer(s);
    // towards −z at height 0.5: the cube's front face z = −4.5
    const auto h = tracer.intersect({0.0f, 0.5f, 0.0f}, {0.0f, 0.0f, -1.0f}, 100.0f);
    ASSERT_TRUE(h);
    EXPECT_EQ(h->shape, 1u);
    EXPECT_NEAR(h->t, 4.5f, 1e-5f);
    ASSERT_LT(h->prim, s.shapes[1].mesh.triangles.size());
    const glm::vec3 n = glm::normalize(h->geometric_normal);
    EXPECT_NEAR(n.z, 1.0f, 1e-5f);  // the front face faces the ray's origin (+z): outward
    const glm::vec3 expected = triangle_normal(s, *h);
    EXPECT_NEAR(glm::length(h->geometric_normal - expected), 0.0f, 1e-5f * glm::length(expected));
}

TEST(EmbreeIntersector, NormalsFollowTheWindingForEveryShape) {
    const auto s = test_scene();
    const embree_intersector tracer(s);
    struct ray {
        glm::vec3 o, d;
        std::uint32_t shape;
    };
    const ray rays[] = {{{0.3f, 2.0f, 1.0f}, {0.0f, -1.0f, 0.0f}, 0u},     // floor from above: normal +y
                        {{0.2f, 3.0f, -5.1f}, {0.0f, -1.0f, 0.0f}, 1u},    // cube top
                        {{8.0f, 1.2f, 0.3f}, {-1.0f, 0.0f, 0.0f}, 2u},     // box, +x side
                        {{4.1f, 1.1f, 0.2f}, {0.3f, 0.1f, -1.0f}, 2u}};   // box from inside
    for (const auto& r : rays) {
        const auto h = tracer.intersect(r.o, r.d, 1e3f);
        ASSERT_TRUE(h);
        EXPECT_EQ(h->shape, r.shape);
        const glm::vec3 expected = triangle_normal(s, *h);
        EXPECT_GT(glm::dot(glm::normalize(h->geometric_normal), glm::normalize(expected)), 0.9999f);
        // barycentrics reproduce the hit point
        const auto& m = s.shapes[h->shape].mesh;
        const auto& t = m.triangles[h->prim];
        const glm::vec3 p = (1.0f - h->u - h->v) * m.positions[t[0]] + h->u * m.positions[t[1]] + h->v * m.positions[t[2]];
        EXPECT_LT(glm::length(p - (r.o + h->t * r.d)), 1e-4f);
    }
    // from inside the box the hit face's outward normal points along the ray
    const auto inside = tracer.intersect({4.1f, 1.1f, 0.2f}, {0.0f, 0.0f, -1.0f}, 1e3f);
    ASSERT_TRUE(inside);
    EXPECT_GT(glm::dot(inside->geometric_normal, glm::vec3(0, 0, -1)), 0.0f);
    EXPECT_NEAR(inside->t, 1.2f, 1e-5f);
}

TEST(EmbreeIntersector, TMaxAndOcclusion) {
    const auto s = test_scene();
    const embree_intersector tracer(s);
    const glm::vec3 o(0.0f, 0.5f, 0.0f), d(0.0f, 0.0f, -1.0f);
    EXPECT_FALSE(tracer.intersect(o, d, 4.4f));
    EXPECT_TRUE(tracer.intersect(o, d, 4.6f));
    EXPECT_FALSE(tracer.occluded(o, d, 4.4f));
    EXPECT_TRUE(tracer.occluded(o, d, 4.6f));
    EXPECT_FALSE(tracer.intersect({0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 1e3f));  // up into nothing
    EXPECT_FALSE(tracer.occluded({0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 1e30f));
    // an unnormalised direction: t is in its units
    const auto h = tracer.intersect(o, 2.0f * d, 100.0f);
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, 2.25f, 1e-5f);
}

TEST(EmbreeIntersector, IsMovableAndOutlivesTheScene) {
    std::optional<embree_intersector> moved;
    {
        const auto s = test_scene();
        embree_intersector a(s);
        moved.emplace(std::move(a));
    }  // the scene_desc is gone: Embree holds its own copy of the triangles
    const auto h = moved->intersect({0.0f, 0.5f, 0.0f}, {0.0f, 0.0f, -1.0f}, 100.0f);
    ASSERT_TRUE(h);
    EXPECT_EQ(h->shape, 1u);
    embree_intersector b(test_scene());
    b = std::move(*moved);
    EXPECT_TRUE(b.occluded({0.0f, 0.5f, 0.0f}, {0.0f, 0.0f, -1.0f}, 100.0f));
}

}  // namespace
