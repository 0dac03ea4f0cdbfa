#pragma once
/// \file
/// \brief `embree_tracer`: the `Intersector` over a scene description, backed by
/// iris::embree (shapes added in order, so the geometry id is the shape index).

#include <optional>

#include "iris/embree/embree.hpp"
#include "iris/render/intersector.hpp"
#include "iris/render/scene.hpp"

namespace iris::renderer {

class embree_tracer {
public:
    /// \throws iris::embree::error if Embree cannot build the scene.
    explicit embree_tracer(const scene_desc& s) : m_scene(m_device) {
        for (const auto& shape : s.shapes) {
            geometry::triangle_mesh m;  // the module's mesh type: same layout as the core's
            m.positions = shape.mesh.positions;
            m.triangles = shape.mesh.triangles;
            m_scene.add_mesh(m);
        }
        m_scene.commit();
    }

    std::optional<ray_hit> intersect(const glm::vec3& o, const glm::vec3& d, float t_max) const noexcept {
        const auto h = m_scene.intersect(o, d, 0.0f, t_max);
        if (!h) return std::nullopt;
        return ray_hit{h->t, h->geom_id, h->prim_id, h->u, h->v, h->geometric_normal};
    }
    bool occluded(const glm::vec3& o, const glm::vec3& d, float t_max) const noexcept {
        return m_scene.occluded(o, d, 0.0f, t_max);
    }

private:
    embree::device m_device;
    embree::scene m_scene;
};
static_assert(Intersector<embree_tracer>);

}  // namespace iris::renderer
