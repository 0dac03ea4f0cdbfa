#include "iris/embree/embree.hpp"

#include <cstring>
#include <limits>
#include <utility>

#include <embree3/rtcore.h>

namespace iris::embree {
namespace {

void on_error(void* user, RTCError code, const char* message) {
    auto* last = static_cast<std::string*>(user);
    if (last->empty()) *last = std::string("Embree error ") + std::to_string(static_cast<int>(code)) + ": " + (message ? message : "");
}

}  // namespace

device::device(const char* config) : m_last_error(new std::string) {
    m_device = rtcNewDevice(config);
    if (!m_device) {
        const std::string msg = "cannot create Embree device (config '" + std::string(config ? config : "") +
                                "'): error " + std::to_string(static_cast<int>(rtcGetDeviceError(nullptr)));
        delete m_last_error;
        throw error(msg);
    }
    rtcSetDeviceErrorFunction(m_device, on_error, m_last_error);
}

device::~device() {
    if (m_device) rtcReleaseDevice(m_device);
    delete m_last_error;
}

device::device(device&& o) noexcept
    : m_device(std::exchange(o.m_device, nullptr)), m_last_error(std::exchange(o.m_last_error, nullptr)) {}

device& device::operator=(device&& o) noexcept {
    if (this != &o) {
        if (m_device) rtcReleaseDevice(m_device);
        delete m_last_error;
        m_device = std::exchange(o.m_device, nullptr);
        m_last_error = std::exchange(o.m_last_error, nullptr);
    }
    return *this;
}

void device::check(const char* what) const {
    if (m_last_error && !m_last_error->empty()) {
        const std::string msg = std::string(what) + ": " + *m_last_error;
        m_last_error->clear();
        throw error(msg);
    }
}

scene::scene(const device& d) : m_device(&d), m_scene(rtcNewScene(d.handle())) {
    d.check("rtcNewScene");
    rtcSetSceneFlags(m_scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(m_scene, RTC_BUILD_QUALITY_HIGH);
}

scene::~scene() {
    if (m_scene) rtcReleaseScene(m_scene);
}

scene::scene(scene&& o) noexcept : m_device(o.m_device), m_scene(std::exchange(o.m_scene, nullptr)) {}

scene& scene::operator=(scene&& o) noexcept {
    if (this != &o) {
        if (m_scene) rtcReleaseScene(m_scene);
        m_device = o.m_device;
        m_scene = std::exchange(o.m_scene, nullptr);
    }
    return *this;
}

unsigned scene::add_mesh(const geometry::triangle_mesh& mesh) {
    RTCGeometry g = rtcNewGeometry(m_device->handle(), RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), mesh.positions.size()));
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(unsigned), mesh.triangles.size()));
    if (!v || !idx) {
        rtcReleaseGeometry(g);
        m_device->check("rtcSetNewGeometryBuffer");
        throw error("rtcSetNewGeometryBuffer failed");
    }
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        v[3 * i] = mesh.positions[i].x;
        v[3 * i + 1] = mesh.positions[i].y;
        v[3 * i + 2] = mesh.positions[i].z;
    }
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        for (std::size_t k = 0; k < 3; ++k) {
            if (mesh.triangles[i][k] >= mesh.positions.size()) {
                rtcReleaseGeometry(g);
                throw error("triangle " + std::to_string(i) + " indexes vertex " + std::to_string(mesh.triangles[i][k]) +
                            " of " + std::to_string(mesh.positions.size()));
            }
            idx[3 * i + k] = mesh.triangles[i][k];
        }
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(m_scene, g);
    rtcReleaseGeometry(g);
    m_device->check("add_mesh");
    return id;
}

void scene::commit() {
    rtcCommitScene(m_scene);
    m_device->check("rtcCommitScene");
}

std::optional<hit> scene::intersect(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar) const noexcept {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh{};
    rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
    rh.ray.tnear = tnear;
    rh.ray.tfar = tfar;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return hit{rh.ray.tfar, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z}};
}

bool scene::occluded(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar) const noexcept {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r{};
    r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
    r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
    r.tnear = tnear;
    r.tfar = tfar;
    r.mask = 0xffffffffu;
    rtcOccluded1(m_scene, &ctx, &r);
    return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

}  // namespace iris::embree
