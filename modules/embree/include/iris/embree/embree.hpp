#pragma once
/// \file
/// \brief iris::embree — move-only RAII wrappers around an Embree 3 device and scene.
///
/// Every Embree failure (the device error callback included) leaves this module as one
/// exception type, `iris::embree::error`. After `commit()`, `intersect` and `occluded`
/// are noexcept and safe to call from many threads at once.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/vec3.hpp>

#include "iris/geometry/mesh.hpp"

// Opaque Embree handles, so that <embree3/rtcore.h> stays out of this header.
struct RTCDeviceTy;
struct RTCSceneTy;

namespace iris::embree {

class error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct hit {
    float t = 0.0f;
    unsigned geom_id = 0;
    unsigned prim_id = 0;
    float u = 0.0f, v = 0.0f;
    glm::vec3 geometric_normal{0.0f};  ///< Embree's unnormalised Ng
};

class device {
public:
    explicit device(const char* config = nullptr);
    ~device();
    device(device&& o) noexcept;
    device& operator=(device&& o) noexcept;
    device(const device&) = delete;
    device& operator=(const device&) = delete;

    RTCDeviceTy* handle() const noexcept { return m_device; }
    /// \brief Throw `error` if Embree reported one since the last check (via the callback).
    void check(const char* what) const;

private:
    RTCDeviceTy* m_device = nullptr;
    std::string* m_last_error = nullptr;  // written by the error callback
};

class scene {
public:
    explicit scene(const device& d);
    ~scene();
    scene(scene&& o) noexcept;
    scene& operator=(scene&& o) noexcept;
    scene(const scene&) = delete;
    scene& operator=(const scene&) = delete;

    /// \brief Add a triangle mesh; returns its geometry id (0, 1, 2, … in insertion order).
    unsigned add_mesh(const geometry::triangle_mesh& mesh);
    /// \brief Build the BVH (robust mode: rays grazing edges do not slip through closed meshes).
    void commit();

    std::optional<hit> intersect(const glm::vec3& origin, const glm::vec3& direction, float tnear,
                                 float tfar) const noexcept;
    bool occluded(const glm::vec3& origin, const glm::vec3& direction, float tnear, float tfar) const noexcept;

private:
    const device* m_device = nullptr;
    RTCSceneTy* m_scene = nullptr;
};

}  // namespace iris::embree
