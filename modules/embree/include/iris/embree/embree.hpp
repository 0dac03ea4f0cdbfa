#pragma once
/// \file
/// \brief iris::embree — an Embree 3 device and scene as move-only RAII types.
///
/// The client follows Embree's `minimal` tutorial: device and error callback first; each
/// geometry created, filled, committed, attached and released; the scene committed.
/// Every Embree failure — a null handle, a code from `rtcGetDeviceError`, or a message
/// sent to the device's error callback — leaves the building calls (constructors,
/// `add_mesh`, `commit`) as one exception type, `iris::embree::error`. The hot-path
/// queries `intersect` and `occluded` are `noexcept` and may be called from any number of
/// threads at once after `commit()`; an Embree error during a query (there should be
/// none) is recorded and thrown by the next building call or `device::check()`.
///
/// Scenes are built in robust mode (`RTC_SCENE_FLAG_ROBUST`: acceleration structures for
/// robust traversal, no optimisations that cost arithmetic accuracy), which Embree offers
/// against rays slipping through the shared edges of neighbouring triangles; a ray leaving
/// a closed mesh's interior must hit it. tests/embree measures this against CGAL.
/// The BVH is built at `RTC_BUILD_QUALITY_HIGH`: scenes are static and traced for many
/// samples, so a slower build pays for itself. <embree3/rtcore.h> stays out of this header.

#include <memory>
#include <optional>
#include <stdexcept>

#include <glm/vec3.hpp>

#include "iris/geometry/triangle_mesh.hpp"

// Embree's opaque handle types (RTCDevice, RTCScene are pointers to these), declared so
// that callers who include <embree3/rtcore.h> themselves can use the native handles.
struct RTCDeviceTy;
struct RTCSceneTy;

namespace iris::embree {

/// \brief Every Embree failure, and every mesh this module refuses, as one exception.
class error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// \brief The closest hit of a ray.
struct hit {
    float t = 0.0f;          ///< distance in units of |direction|
    unsigned geom_id = 0;    ///< `scene::add_mesh` order: 0, 1, 2, …
    unsigned prim_id = 0;    ///< the triangle's index in its mesh
    float u = 0.0f, v = 0.0f;  ///< barycentric weights of the triangle's vertices 1 and 2
    /// Embree's unnormalised geometric normal Ng = (p1 − p0) × (p2 − p0): outward for the
    /// counter-clockwise-from-outside triangles of iris::geometry, whichever side was hit.
    glm::vec3 geometric_normal{0.0f};
};

namespace detail {
struct device_state;
}

/// \brief An Embree device (`rtcNewDevice`) whose error callback collects messages for
/// the module boundary. Move-only; scenes keep the device alive, so it may be destroyed
/// or moved before them.
class device {
public:
    /// \brief `config` is Embree's device configuration string (e.g. "threads=2"); null
    /// or empty for the defaults. \throws error if Embree rejects it.
    explicit device(const char* config = nullptr);
    ~device();
    device(device&&) noexcept;
    device& operator=(device&&) noexcept;
    device(const device&) = delete;
    device& operator=(const device&) = delete;

    /// \brief Throw `error` if Embree reported an error since the last check, e.g. from a
    /// `noexcept` query or from native calls made through `handle()`. `what` prefixes the
    /// message.
    void check(const char* what = "embree") const;

    /// \brief The native RTCDevice (null after a move).
    RTCDeviceTy* handle() const noexcept;

private:
    friend class scene;
    std::shared_ptr<detail::device_state> m_state;
};

/// \brief An Embree scene of triangle meshes: add meshes, commit, then query from any
/// number of threads. Move-only. Adding a mesh after `commit()` needs another `commit()`
/// before the next query; until then queries report no hit.
class scene {
public:
    /// \throws error if Embree cannot create the scene (or `d` was moved from).
    explicit scene(const device& d);
    ~scene();
    scene(scene&&) noexcept;
    scene& operator=(scene&&) noexcept;
    scene(const scene&) = delete;
    scene& operator=(const scene&) = delete;

    /// \brief Copy a triangle mesh into Embree; returns its geometry id, 0, 1, 2, … in
    /// insertion order. \throws error for an empty mesh, indices out of range, non-finite
    /// positions, or any Embree failure.
    unsigned add_mesh(const geometry::triangle_mesh& mesh);

    /// \brief Build the BVH (robust, high quality). \throws error on any Embree failure.
    void commit();

    /// \brief The closest hit with t in [tnear, tfar] of origin + t·direction (`rtcIntersect1`).
    /// An invalid ray (non-finite origin or direction, tnear < 0, tnear > tfar) or a scene
    /// not committed since its last change reports no hit.
    std::optional<hit> intersect(const glm::vec3& origin, const glm::vec3& direction, float tnear,
                                 float tfar) const noexcept;

    /// \brief Whether anything is hit with t in [tnear, tfar] (`rtcOccluded1`, any hit);
    /// false for invalid rays and uncommitted scenes, as for `intersect`.
    bool occluded(const glm::vec3& origin, const glm::vec3& direction, float tnear, float tfar) const noexcept;

    /// \brief The number of meshes added so far.
    unsigned geometry_count() const noexcept { return m_geometries; }

    /// \brief The native RTCScene (null after a move), for callers using Embree directly.
    RTCSceneTy* handle() const noexcept { return m_scene; }

private:
    void check(const char* what) const;

    std::shared_ptr<detail::device_state> m_device;
    RTCSceneTy* m_scene = nullptr;
    unsigned m_geometries = 0;
    bool m_committed = false;
};

}  // namespace iris::embree
