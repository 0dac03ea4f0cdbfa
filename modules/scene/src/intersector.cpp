#include "iris/scene/intersector.hpp"

#include <limits>
#include <type_traits>

#include "iris/embree/embree.hpp"

namespace iris::scene {
namespace {

/// Embree's triangle normal Ng is already (v1 − v0) × (v2 − v0), the core's convention
/// (checked against the mesh's own triangles by tests/scene/intersector_test.cpp).
constexpr float embree_ng_sign = 1.0f;

/// tnear just above 0: a hit exactly at the origin is excluded, as the concept requires t > 0.
constexpr float t_min = std::numeric_limits<float>::min();

/// The core mesh as the embree module's mesh type (the same layout; a copy if the types differ).
template <class Mesh>
Mesh as_mesh(const iris::triangle_mesh& m) {
    if constexpr (std::is_same_v<Mesh, iris::triangle_mesh>) {
        return m;
    } else {
        Mesh g;
        g.positions = m.positions;
        g.triangles = m.triangles;
        return g;
    }
}

}  // namespace

embree_intersector::embree_intersector(const iris::scene_desc& scene)
    : m_device(std::make_unique<embree::device>()), m_scene(std::make_unique<embree::scene>(*m_device)) {
    for (const auto& shape : scene.shapes) m_scene->add_mesh(as_mesh<geometry::triangle_mesh>(shape.mesh));
    m_scene->commit();
}

embree_intersector::~embree_intersector() {
    m_scene.reset();  // the scene before its device
    m_device.reset();
}

embree_intersector::embree_intersector(embree_intersector&&) noexcept = default;
embree_intersector& embree_intersector::operator=(embree_intersector&& o) noexcept {
    if (this != &o) {
        m_scene = std::move(o.m_scene);  // releases our old scene before our old device
        m_device = std::move(o.m_device);
    }
    return *this;
}

std::optional<iris::ray_hit> embree_intersector::intersect(const glm::vec3& o, const glm::vec3& d,
                                                           float t_max) const noexcept {
    if (!m_scene) return std::nullopt;
    const auto h = m_scene->intersect(o, d, t_min, t_max);
    if (!h || !(h->t > 0.0f)) return std::nullopt;
    return iris::ray_hit{h->t, h->geom_id, h->prim_id, h->u, h->v, embree_ng_sign * h->geometric_normal};
}

bool embree_intersector::occluded(const glm::vec3& o, const glm::vec3& d, float t_max) const noexcept {
    return m_scene && m_scene->occluded(o, d, t_min, t_max);
}

}  // namespace iris::scene
