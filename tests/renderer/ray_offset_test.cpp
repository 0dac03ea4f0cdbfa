// Ray offsets (iris/render/frame.hpp) against Embree: a ray leaving a surface must neither
// re-hit it nor start beyond a surface 0.1 mm away (cornell's glass cube stands 0.1 mm
// above the floor), and a shadow ray aimed at a lamp must not hit the lamp.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include <iris/render/frame.hpp>
#include <iris/render/random.hpp>
#include <iris/embree/intersector.hpp>
#include <iris/scene/scene.hpp>

namespace {

iris::scene_desc two_planes(float gap) {
    // the floor y = 0 (facing up) and, `gap` above it, a quad facing down, 1.2 m off the origin
    const std::string json = R"({"camera": {"position": [0, 1, 3], "look_at": [0, 0, 0], "resolution": [8, 8]}, "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
      "emitters": {"l": {"spd": "D65", "luminance": 1}},
      "shapes": [{"type": "quad", "size": [4, 4], "material": "m", "emitter": "l"},
                 {"type": "quad", "size": [0.5, 0.5], "material": "m",
                  "transform": [{"rotate": {"axis": [1, 0, 0], "degrees": 180}}, {"translate": [1.2, )" +
                             std::to_string(gap) + R"(, 0.9]}]}]})";
    return iris::scene::parse_scene(json, "two-planes", ".");
}

iris::surface_point on(const iris::scene_desc& s, std::uint32_t shape, float b1, float b2) {
    const auto& m = s.shapes[shape].mesh;
    const auto& t = m.triangles[0];
    return iris::point_on_triangle(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]], b1, b2);
}

}  // namespace

TEST(RayOffset, RaysBetweenSurfacesATenthOfAMillimetreApartHitTheOther) {
    const auto s = two_planes(1e-4f);
    const iris::embree::intersector tracer(s);
    iris::counter_rng rng(3);
    for (int i = 0; i < 2000; ++i) {
        // a point of the floor under the small quad, going up at any angle; and back down
        const float x = 1.0f + 0.4f * rng.next(), z = 0.7f + 0.4f * rng.next();
        const float phi = 6.2831853f * rng.next(), c = 0.05f + 0.95f * rng.next(), sn = std::sqrt(1.0f - c * c);
        const glm::vec3 up_dir(sn * std::cos(phi), c, sn * std::sin(phi));
        const iris::surface_point floor_p{{x, 0.0f, z}, iris::point_on_triangle({-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, 0.3f, 0.3f).error};
        const auto up = tracer.intersect(iris::offset_ray_origin(floor_p, {0, 1, 0}, up_dir), up_dir, 1.0f);
        ASSERT_TRUE(up && up->shape == 1) << "a ray from the floor at (" << x << ", 0, " << z << ") missed the surface 0.1 mm above";
        const iris::surface_point top{{x, 1e-4f, z}, on(s, 1, 0.3f, 0.3f).error};
        const auto down = tracer.intersect(iris::offset_ray_origin(top, {0, -1, 0}, -up_dir), -up_dir, 1.0f);
        ASSERT_TRUE(down && down->shape == 0) << "a ray from 0.1 mm above the floor missed it";
    }
}

TEST(RayOffset, RaysLeavingTheBuiltinScenesSurfacesNeverHitTheirOwnTriangle) {
    for (const auto& info : iris::scene::builtin_scenes()) {
        const auto s = iris::scene::builtin_scene(info.name);
        const iris::embree::intersector tracer(s);
        iris::counter_rng rng(9);
        int self = 0, tried = 0;
        for (std::uint32_t si = 0; si < s.shapes.size(); ++si)
            for (std::uint32_t ti = 0; ti < s.shapes[si].mesh.triangles.size(); ++ti) {
                const auto& m = s.shapes[si].mesh;
                const auto& t = m.triangles[ti];
                const glm::vec3 a = m.positions[t[0]], b = m.positions[t[1]], c = m.positions[t[2]];
                const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
                const iris::frame f = iris::frame::from_normal(n);
                for (int k = 0; k < 64; ++k) {
                    float b1 = rng.next(), b2 = rng.next();
                    if (b1 + b2 > 1.0f) {
                        b1 = 1.0f - b1;
                        b2 = 1.0f - b2;
                    }
                    const auto sp = iris::point_on_triangle(a, b, c, b1, b2);
                    // either side, down to grazing (cos θ ≥ 10⁻³)
                    const float phi = 6.2831853f * rng.next(), ct = (k % 2 ? 1.0f : -1.0f) * (1e-3f + rng.next() * rng.next());
                    const float st = std::sqrt(1.0f - ct * ct);
                    const glm::vec3 w = f.to_world({st * std::cos(phi), st * std::sin(phi), ct});
                    const auto h = tracer.intersect(iris::offset_ray_origin(sp, n, w), w, 1e30f);
                    ++tried;
                    if (h && h->shape == si && h->prim == ti) ++self;
                }
            }
        EXPECT_EQ(self, 0) << info.name << ": " << self << " of " << tried << " rays re-hit their own triangle";
    }
}

TEST(RayOffset, AShadowRayToALampPointIsNotBlockedByTheLamp) {
    const auto s = iris::scene::parse_scene(R"({"camera": {"position": [0, 1, 3], "look_at": [0, 0, 0], "resolution": [8, 8]}, "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
      "emitters": {"l": {"spd": "D65", "luminance": 1}},
      "shapes": [{"type": "quad", "size": [6, 6], "material": "m"},
                 {"type": "quad", "size": [0.2, 0.2], "material": "m", "emitter": "l",
                  "transform": [{"rotate": {"axis": [1, 0, 0], "degrees": 180}}, {"translate": [0, 0.3, 0]}]}]})",
                                            "lamp", ".");
    const iris::embree::intersector tracer(s);
    const auto& lamp = s.shapes[1].mesh;
    iris::counter_rng rng(4);
    for (int i = 0; i < 4000; ++i) {
        const float r = 2.5f * rng.next();  // on-axis to very grazing (cos θ ≈ 0.1)
        const iris::surface_point p{{r, 0.0f, 0.1f}, on(s, 0, 0.5f, 0.2f).error};
        const auto& t = lamp.triangles[i % 2];
        float b1 = rng.next(), b2 = rng.next();
        if (b1 + b2 > 1.0f) {
            b1 = 1.0f - b1;
            b2 = 1.0f - b2;
        }
        const auto q = iris::point_on_triangle(lamp.positions[t[0]], lamp.positions[t[1]], lamp.positions[t[2]], b1, b2);
        const auto seg = iris::shadow_ray_between(p, {0, 1, 0}, q, {0, -1, 0});
        ASSERT_FALSE(tracer.occluded(seg.origin, seg.direction, seg.t_max)) << "point at " << r << " m from the axis";
    }
}
