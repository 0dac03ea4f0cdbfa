#pragma once
/// \file
/// \brief `embree_intersector`: the `iris::Intersector` (include/iris/render/intersector.hpp)
/// over a scene's shapes, backed by Embree 3.

#include <memory>
#include <optional>

#include <glm/vec3.hpp>

#include "iris/render/intersector.hpp"
#include "iris/render/scene.hpp"

namespace iris::embree {
class device;
class scene;
}  // namespace iris::embree

namespace iris::scene {

/// \brief Closest-hit and shadow queries against the shapes of a `scene_desc`.
///
/// Shapes are added in order, so `ray_hit::shape` is the index into
/// `scene_desc::shapes` (and the Embree geometry id); `ray_hit::prim` is the triangle of
/// that shape, `u`/`v` the barycentrics of its vertices 1 and 2, and `geometric_normal`
/// is (v1 − v0) × (v2 − v0), unnormalised (Embree's Ng, whose orientation is tested). Hits count for t in (0, t_max). The triangles are copied into Embree:
/// the `scene_desc` need not outlive the intersector. Move-only; queries are noexcept and
/// thread-safe. \throws iris::embree::error if Embree cannot build the scene.
class embree_intersector {
public:
    explicit embree_intersector(const iris::scene_desc& scene);
    ~embree_intersector();
    embree_intersector(embree_intersector&&) noexcept;
    embree_intersector& operator=(embree_intersector&&) noexcept;
    embree_intersector(const embree_intersector&) = delete;
    embree_intersector& operator=(const embree_intersector&) = delete;

    std::optional<iris::ray_hit> intersect(const glm::vec3& o, const glm::vec3& d, float t_max) const noexcept;
    bool occluded(const glm::vec3& o, const glm::vec3& d, float t_max) const noexcept;

private:
    // Held by pointer: embree::scene keeps the address of its device, which must not move.
    std::unique_ptr<embree::device> m_device;
    std::unique_ptr<embree::scene> m_scene;
};

static_assert(iris::Intersector<embree_intersector>);

}  // namespace iris::scene
