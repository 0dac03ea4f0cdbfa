// iris::embree: the only file that includes <embree3/rtcore.h>. Shaped like Embree's
// `minimal` tutorial: device + error callback, geometry created/filled/committed/
// attached/released, scene committed; plus the checks that turn Embree's error reports
// into iris::embree::error at each building call.
#include "iris/embree/embree.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <string>
#include <utility>

#include <embree3/rtcore.h>

namespace iris::embree {
namespace detail {

// Shared by the device and its scenes, so that the callback's user pointer stays valid
// for as long as Embree may call it, whatever order the wrappers are destroyed in.
struct device_state {
    RTCDevice handle = nullptr;
    std::mutex mutex;      // the callback may run on any thread (BVH builds, queries)
    std::string messages;  // what the callback reported since the last check

    device_state() = default;
    device_state(const device_state&) = delete;
    device_state& operator=(const device_state&) = delete;
    ~device_state() {
        if (handle) {
            rtcSetDeviceErrorFunction(handle, nullptr, nullptr);
            rtcReleaseDevice(handle);
        }
    }
};

}  // namespace detail

namespace {

const char* code_name(RTCError e) noexcept {
    switch (e) {
    case RTC_ERROR_NONE: return "RTC_ERROR_NONE";
    case RTC_ERROR_UNKNOWN: return "RTC_ERROR_UNKNOWN";
    case RTC_ERROR_INVALID_ARGUMENT: return "RTC_ERROR_INVALID_ARGUMENT";
    case RTC_ERROR_INVALID_OPERATION: return "RTC_ERROR_INVALID_OPERATION";
    case RTC_ERROR_OUT_OF_MEMORY: return "RTC_ERROR_OUT_OF_MEMORY";
    case RTC_ERROR_UNSUPPORTED_CPU: return "RTC_ERROR_UNSUPPORTED_CPU";
    case RTC_ERROR_CANCELLED: return "RTC_ERROR_CANCELLED";
    }
    return "unknown RTCError";
}

// Embree's error callback: remember the report; the building call that caused it throws.
// Never lets an exception escape into Embree.
void on_error(void* user, RTCError code, const char* text) noexcept {
    auto* state = static_cast<detail::device_state*>(user);
    try {
        const std::lock_guard lock(state->mutex);
        if (state->messages.size() > 4096) return;  // a storm of errors: the first ones say enough
        if (!state->messages.empty()) state->messages += "; ";
        state->messages += code_name(code);
        if (text && *text) state->messages += std::string(": ") + text;
    } catch (...) {
    }
}

// Throw if Embree reported anything since the last check: the callback's messages (from
// any thread) or this thread's error code.
void check_state(detail::device_state& state, const char* what) {
    const RTCError code = rtcGetDeviceError(state.handle);
    std::string messages;
    {
        const std::lock_guard lock(state.mutex);
        messages.swap(state.messages);
    }
    if (code == RTC_ERROR_NONE && messages.empty()) return;
    throw error(std::string("iris::embree: ") + what + " failed: " + (messages.empty() ? code_name(code) : messages));
}

bool finite(const glm::vec3& v) noexcept { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Embree's ray segment must satisfy 0 ≤ tnear ≤ tfar, with finite origin and direction;
// anything else is reported as a miss instead of being handed to Embree.
bool valid_ray(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar) noexcept {
    return finite(o) && finite(d) && tnear >= 0.0f && tnear <= tfar;
}

void init_ray(RTCRay& r, const glm::vec3& o, const glm::vec3& d, float tnear, float tfar) noexcept {
    r.org_x = o.x;
    r.org_y = o.y;
    r.org_z = o.z;
    r.tnear = tnear;
    r.dir_x = d.x;
    r.dir_y = d.y;
    r.dir_z = d.z;
    r.time = 0.0f;
    r.tfar = tfar;
    r.mask = std::numeric_limits<unsigned>::max();
    r.id = 0;
    r.flags = 0;
}

struct geometry_release {
    void operator()(RTCGeometryTy* g) const noexcept { rtcReleaseGeometry(g); }
};

// The layouts copied into Embree's buffers as they are.
static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
static_assert(sizeof(std::array<std::uint32_t, 3>) == 3 * sizeof(unsigned));

}  // namespace

// ---- device ------------------------------------------------------------------------------

device::device(const char* config) {
    auto state = std::make_shared<detail::device_state>();
    state->handle = rtcNewDevice(config);
    if (!state->handle)
        throw error(std::string("iris::embree: cannot create an Embree device with configuration \"") +
                    (config ? config : "") + "\": " + code_name(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(state->handle, on_error, state.get());
    m_state = std::move(state);
}

device::~device() = default;
device::device(device&&) noexcept = default;
device& device::operator=(device&&) noexcept = default;

void device::check(const char* what) const {
    if (m_state) check_state(*m_state, what);
}

RTCDeviceTy* device::handle() const noexcept { return m_state ? m_state->handle : nullptr; }

// ---- scene -------------------------------------------------------------------------------

scene::scene(const device& d) : m_device(d.m_state) {
    if (!m_device) throw error("iris::embree: cannot create a scene on a moved-from device");
    m_scene = rtcNewScene(m_device->handle);
    try {
        if (!m_scene) {
            check_state(*m_device, "rtcNewScene");
            throw error("iris::embree: rtcNewScene returned no scene");
        }
        rtcSetSceneFlags(m_scene, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(m_scene, RTC_BUILD_QUALITY_HIGH);
        check_state(*m_device, "configuring the scene");
    } catch (...) {
        if (m_scene) rtcReleaseScene(m_scene);
        throw;
    }
}

scene::~scene() {
    if (m_scene) rtcReleaseScene(m_scene);
}

scene::scene(scene&& o) noexcept
    : m_device(std::move(o.m_device)),
      m_scene(std::exchange(o.m_scene, nullptr)),
      m_geometries(std::exchange(o.m_geometries, 0u)),
      m_committed(std::exchange(o.m_committed, false)) {}

scene& scene::operator=(scene&& o) noexcept {
    if (this != &o) {
        if (m_scene) rtcReleaseScene(m_scene);
        m_device = std::move(o.m_device);
        m_scene = std::exchange(o.m_scene, nullptr);
        m_geometries = std::exchange(o.m_geometries, 0u);
        m_committed = std::exchange(o.m_committed, false);
    }
    return *this;
}

void scene::check(const char* what) const { check_state(*m_device, what); }

unsigned scene::add_mesh(const geometry::triangle_mesh& mesh) {
    if (!m_scene) throw error("iris::embree: add_mesh on a moved-from scene");
    // Refuse what Embree would accept silently and trace wrongly (or read out of bounds).
    if (mesh.triangles.empty()) throw error("iris::embree: add_mesh: the mesh has no triangles");
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        if (!finite(mesh.positions[i]))
            throw error("iris::embree: add_mesh: vertex " + std::to_string(i) + " is not finite");
    if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size())
        throw error("iris::embree: add_mesh: " + std::to_string(mesh.normals.size()) + " normals for " +
                    std::to_string(mesh.positions.size()) + " vertices (need none or one per vertex)");
    if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size())
        throw error("iris::embree: add_mesh: " + std::to_string(mesh.uvs.size()) + " uvs for " +
                    std::to_string(mesh.positions.size()) + " vertices (need none or one per vertex)");
    for (std::size_t i = 0; i < mesh.normals.size(); ++i)
        if (!finite(mesh.normals[i])) throw error("iris::embree: add_mesh: normal " + std::to_string(i) + " is not finite");
    for (std::size_t i = 0; i < mesh.uvs.size(); ++i)
        if (!std::isfinite(mesh.uvs[i].x) || !std::isfinite(mesh.uvs[i].y))
            throw error("iris::embree: add_mesh: uv " + std::to_string(i) + " is not finite");
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (const std::uint32_t v : mesh.triangles[t])
            if (v >= mesh.positions.size())
                throw error("iris::embree: add_mesh: triangle " + std::to_string(t) + " refers to vertex " +
                            std::to_string(v) + " of " + std::to_string(mesh.positions.size()));

    const std::unique_ptr<RTCGeometryTy, geometry_release> g(rtcNewGeometry(m_device->handle, RTC_GEOMETRY_TYPE_TRIANGLE));
    if (!g) {
        check("rtcNewGeometry");
        throw error("iris::embree: rtcNewGeometry returned no geometry");
    }
    // Embree allocates (and pads for its vector loads) the buffers; we copy into them.
    void* vertices = rtcSetNewGeometryBuffer(g.get(), RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(glm::vec3),
                                             mesh.positions.size());
    void* indices = rtcSetNewGeometryBuffer(g.get(), RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                            sizeof(std::array<std::uint32_t, 3>), mesh.triangles.size());
    check("allocating the mesh buffers");
    if (!vertices || !indices) throw error("iris::embree: rtcSetNewGeometryBuffer returned no buffer");
    std::memcpy(vertices, mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
    std::memcpy(indices, mesh.triangles.data(), mesh.triangles.size() * sizeof(std::array<std::uint32_t, 3>));
    rtcCommitGeometry(g.get());
    const unsigned id = rtcAttachGeometry(m_scene, g.get());
    check("add_mesh");
    ++m_geometries;
    m_committed = false;
    return id;  // Embree numbers attached geometries 0, 1, 2, … in order
}

void scene::commit() {
    if (!m_scene) throw error("iris::embree: commit on a moved-from scene");
    rtcCommitScene(m_scene);
    check("rtcCommitScene");
    m_committed = true;
}

std::optional<hit> scene::intersect(const glm::vec3& origin, const glm::vec3& direction, float tnear,
                                    float tfar) const noexcept {
    if (!m_committed || !valid_ray(origin, direction, tnear, tfar)) return std::nullopt;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    init_ray(rh.ray, origin, direction, tnear, tfar);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return hit{rh.ray.tfar, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v,
               glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z)};
}

bool scene::occluded(const glm::vec3& origin, const glm::vec3& direction, float tnear, float tfar) const noexcept {
    if (!m_committed || !valid_ray(origin, direction, tnear, tfar)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray;
    init_ray(ray, origin, direction, tnear, tfar);
    rtcOccluded1(m_scene, &context, &ray);
    return ray.tfar == -std::numeric_limits<float>::infinity();  // Embree's mark for "hit"
}

}  // namespace iris::embree
