#pragma once
/// \file
/// \brief The `Intersector` concept: the ray-tracing half of a scene.
///
/// Required expressions (all `noexcept`, thread-safe after construction):
///   `t.intersect(origin, direction, t_max)` → `std::optional<ray_hit>` (closest hit with
///       t in (0, t_max); `direction` need not be normalised, t is in its units);
///   `t.occluded(origin, direction, t_max)` → `bool` (any hit with t in (0, t_max)).
/// `ray_hit::shape` indexes `scene_desc::shapes`; `prim` the shape's triangle.
/// Model: `iris::embree::intersector` (modules/embree, Embree 3), the one ray tracer of
/// iris; tests may define their own (e.g. one that never hits).
/// Callers offset ray origins themselves (see `offset_ray_origin`).

#include <concepts>
#include <cstdint>
#include <optional>

#include <glm/vec3.hpp>

namespace iris {

struct ray_hit {
    float t = 0.0f;
    std::uint32_t shape = 0;
    std::uint32_t prim = 0;
    float u = 0.0f, v = 0.0f;  ///< barycentrics of vertices 1 and 2
    glm::vec3 geometric_normal{0.0f};  ///< (v1 − v0) × (v2 − v0), unnormalised
};

template <class T>
concept Intersector = requires(const T& t, const glm::vec3& o, const glm::vec3& d, float t_max) {
    { t.intersect(o, d, t_max) } noexcept -> std::same_as<std::optional<ray_hit>>;
    { t.occluded(o, d, t_max) } noexcept -> std::same_as<bool>;
};

}  // namespace iris
