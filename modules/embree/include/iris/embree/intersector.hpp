#pragma once
/// \file
/// \brief `iris::embree::intersector`: the `iris::Intersector` (include/iris/render/intersector.hpp)
/// over a scene description — the one ray tracer of iris: the renderer's, the tests' and
/// the tools'.
///
/// Shapes are added in order, so `ray_hit::shape` is the index into `scene_desc::shapes`
/// (and the Embree geometry id); `ray_hit::prim` is the triangle of that shape, `u`/`v`
/// the barycentrics of its vertices 1 and 2, and `geometric_normal` is Embree's Ng =
/// (v1 − v0) × (v2 − v0), unnormalised (its orientation is tested). Hits count for t in
/// (0, t_max]: tnear is the smallest positive float, so a hit exactly at the origin is not
/// one. Each shape's triangles go straight from the `scene_desc` into Embree's own buffers
/// (Embree pads them for its vector loads), one copy and no intermediate mesh, so the
/// `scene_desc` need not outlive the intersector. Move-only; queries are noexcept and
/// thread-safe.

#include <limits>
#include <optional>

#include <glm/vec3.hpp>

#include "iris/embree/embree.hpp"
#include "iris/render/intersector.hpp"
#include "iris/render/scene.hpp"

namespace iris::embree {

class intersector {
public:
    /// \throws iris::embree::error if Embree cannot build the scene (or refuses a mesh:
    /// no triangles, indices out of range, non-finite positions).
    explicit intersector(const iris::scene_desc& scene) : m_scene(m_device) {
        for (const auto& shape : scene.shapes) m_scene.add_mesh(shape.mesh);
        m_scene.commit();
    }

    std::optional<iris::ray_hit> intersect(const glm::vec3& o, const glm::vec3& d, float t_max) const noexcept {
        const auto h = m_scene.intersect(o, d, t_min, t_max);
        if (!h) return std::nullopt;
        return iris::ray_hit{h->t, h->geom_id, h->prim_id, h->u, h->v, h->geometric_normal};
    }
    bool occluded(const glm::vec3& o, const glm::vec3& d, float t_max) const noexcept {
        return m_scene.occluded(o, d, t_min, t_max);
    }

    /// \brief The Embree scene (for callers that query Embree directly).
    const scene& embree_scene() const noexcept { return m_scene; }

private:
    static constexpr float t_min = std::numeric_limits<float>::min();
    device m_device;  // declared first: built before the scene (which keeps it alive itself)
    scene m_scene;
};

static_assert(iris::Intersector<intersector>);

}  // namespace iris::embree
