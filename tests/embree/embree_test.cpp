// iris::embree against closed forms on iris::geometry meshes: distances, ids, normals,
// occlusion, RAII and moves, the error path, robustness at edges, concurrent queries.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

#include <iris/embree/embree.hpp>
#include <iris/geometry/mesh.hpp>

namespace {

namespace g = iris::geometry;
namespace e = iris::embree;

static_assert(!std::is_copy_constructible_v<e::device> && !std::is_copy_assignable_v<e::device>);
static_assert(!std::is_copy_constructible_v<e::scene> && !std::is_copy_assignable_v<e::scene>);
static_assert(std::is_nothrow_move_constructible_v<e::device> && std::is_nothrow_move_assignable_v<e::device>);
static_assert(std::is_nothrow_move_constructible_v<e::scene> && std::is_nothrow_move_assignable_v<e::scene>);
static_assert(noexcept(std::declval<const e::scene&>().intersect({}, {}, 0.0f, 1.0f)));
static_assert(noexcept(std::declval<const e::scene&>().occluded({}, {}, 0.0f, 1.0f)));

constexpr float inf = std::numeric_limits<float>::infinity();

glm::vec3 face_normal(const g::triangle_mesh& m, unsigned prim) {
    const auto& t = m.triangles[prim];
    return glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
}

TEST(Embree, HitsAtTheRightDistanceWithIdsInInsertionOrder) {
    const e::device dev("threads=1");
    e::scene s(dev);
    EXPECT_EQ(s.add_mesh(g::make_cube({0, 0, 0}, 2.0f)), 0u);
    EXPECT_EQ(s.add_mesh(g::make_prism({5, 0, 0}, 1.0f, 1.0f)), 1u);
    EXPECT_EQ(s.add_mesh(g::make_quad({-5, 0, 0}, {1, 0, 0}, {0, 1, 0})), 2u);
    EXPECT_EQ(s.geometry_count(), 3u);
    s.commit();
    const auto h = s.intersect({0, 0, 5}, {0, 0, -1}, 0.0f, inf);
    ASSERT_TRUE(h.has_value());
    EXPECT_EQ(h->geom_id, 0u);
    EXPECT_FLOAT_EQ(h->t, 4.0f);
    const auto p = s.intersect({5, 0, 5}, {0, 0, -2}, 0.0f, inf);  // t in units of |direction|
    ASSERT_TRUE(p.has_value());
    EXPECT_EQ(p->geom_id, 1u);
    EXPECT_FLOAT_EQ(p->t, 2.25f);
    const auto q = s.intersect({-5, 0, -3}, {0, 0, 1}, 0.0f, inf);  // the quad from behind
    ASSERT_TRUE(q.has_value());
    EXPECT_EQ(q->geom_id, 2u);
    EXPECT_FLOAT_EQ(q->t, 3.0f);
    EXPECT_GT(q->geometric_normal.z, 0.0f);  // u × v, whichever side is hit
    EXPECT_FALSE(s.intersect({0, 0, 5}, {0, 0, 1}, 0.0f, inf).has_value());
    EXPECT_FALSE(s.intersect({0, 0, 5}, {0, 0, -1}, 0.0f, 3.9f).has_value());  // tfar
    EXPECT_FLOAT_EQ(s.intersect({0, 0, 5}, {0, 0, -1}, 4.1f, inf)->t, 6.0f);  // tnear: the far side
}

TEST(Embree, GeometricNormalIsTheOutwardWindingNormal) {
    const auto mesh = g::transformed(g::make_cube({0, 0, 0}, 1.0f), g::make_transform({0.2f, 0, 0}, {20, 30, 40}, {1, 1, 1}));
    const e::device dev;
    e::scene s(dev);
    s.add_mesh(mesh);
    s.commit();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    int checked = 0;
    for (int i = 0; i < 500; ++i) {
        const glm::vec3 target(0.2f * u(rng) + 0.2f, 0.2f * u(rng), 0.2f * u(rng));
        const glm::vec3 origin = 4.0f * glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
        const auto h = s.intersect(origin, target - origin, 0.0f, inf);
        ASSERT_TRUE(h.has_value());
        const glm::vec3 ours = face_normal(mesh, h->prim_id);
        // same direction (Embree's Ng = (p1 − p0) × (p2 − p0)), and facing the ray from outside
        EXPECT_GT(glm::dot(glm::normalize(h->geometric_normal), glm::normalize(ours)), 0.9999f);
        EXPECT_LT(glm::dot(h->geometric_normal, target - origin), 0.0f);
        // barycentrics reproduce the hit point
        const auto& t = mesh.triangles[h->prim_id];
        const glm::vec3 at = (1 - h->u - h->v) * mesh.positions[t[0]] + h->u * mesh.positions[t[1]] + h->v * mesh.positions[t[2]];
        EXPECT_LT(glm::length(at - (origin + h->t * (target - origin))), 1e-5f);
        ++checked;
    }
    EXPECT_EQ(checked, 500);
}

TEST(Embree, OccludedAgreesWithIntersect) {
    const e::device dev;
    e::scene s(dev);
    s.add_mesh(g::make_hollow_cube({0, 0, 0}, 2.0f, 1.0f));
    s.commit();
    EXPECT_TRUE(s.occluded({0, 0, 5}, {0, 0, -1}, 0.0f, inf));
    EXPECT_TRUE(s.occluded({0, 0, 5}, {0, 0, -1}, 0.0f, 4.1f));
    EXPECT_FALSE(s.occluded({0, 0, 5}, {0, 0, -1}, 0.0f, 3.9f));
    EXPECT_FALSE(s.occluded({0, 0, 5}, {0, 0, 1}, 0.0f, inf));
    EXPECT_FALSE(s.occluded({0, 0, 0}, {0, 0, 1}, 0.0f, 0.49f));  // inside the cavity
    EXPECT_TRUE(s.occluded({0, 0, 0}, {0, 0, 1}, 0.0f, 0.51f));
    // the cavity's wall, seen from inside the cavity, faces the ray's origin
    const auto h = s.intersect({0, 0, 0}, {0, 0, 1}, 0.0f, inf);
    ASSERT_TRUE(h.has_value());
    EXPECT_FLOAT_EQ(h->t, 0.5f);
    EXPECT_LT(h->geometric_normal.z, 0.0f);
}

TEST(Embree, InvalidRaysAndUncommittedScenesReportNoHit) {
    const e::device dev;
    e::scene s(dev);
    s.add_mesh(g::make_cube({0, 0, 0}, 2.0f));
    EXPECT_FALSE(s.intersect({0, 0, 5}, {0, 0, -1}, 0.0f, inf).has_value());  // not committed yet
    s.commit();
    EXPECT_TRUE(s.intersect({0, 0, 5}, {0, 0, -1}, 0.0f, inf).has_value());
    const float nan = std::nanf("");
    EXPECT_FALSE(s.intersect({0, 0, nan}, {0, 0, -1}, 0.0f, inf).has_value());
    EXPECT_FALSE(s.intersect({0, 0, 5}, {0, inf, -1}, 0.0f, inf).has_value());
    EXPECT_FALSE(s.intersect({0, 0, 5}, {0, 0, -1}, -1.0f, inf).has_value());
    EXPECT_FALSE(s.intersect({0, 0, 5}, {0, 0, -1}, 2.0f, 1.0f).has_value());
    EXPECT_FALSE(s.occluded({0, 0, 5}, {0, 0, -1}, 2.0f, 1.0f));
    EXPECT_FALSE(s.occluded({0, 0, 5}, {0, 0, -1}, nan, inf));
    s.add_mesh(g::make_cube({0, 0, 10}, 1.0f));  // a change: no hits until the next commit
    EXPECT_FALSE(s.occluded({0, 0, 5}, {0, 0, -1}, 0.0f, inf));
    s.commit();
    EXPECT_EQ(s.intersect({0, 0, 5}, {0, 0, 1}, 0.0f, inf)->geom_id, 1u);
}

TEST(Embree, MovesTransferOwnershipAndScenesOutliveTheirDevice) {
    std::optional<e::scene> kept;
    {
        e::device dev;
        e::device moved(std::move(dev));
        EXPECT_EQ(dev.handle(), nullptr);  // NOLINT(bugprone-use-after-move): documented state
        EXPECT_NE(moved.handle(), nullptr);
        EXPECT_THROW(e::scene{dev}, e::error);
        e::scene s(moved);
        s.add_mesh(g::make_cube({0, 0, 0}, 1.0f));
        s.commit();
        kept.emplace(std::move(s));
        EXPECT_EQ(s.handle(), nullptr);  // NOLINT(bugprone-use-after-move)
        EXPECT_FALSE(s.intersect({0, 0, 5}, {0, 0, -1}, 0.0f, inf).has_value());
        EXPECT_THROW(s.add_mesh(g::make_cube({0, 0, 0}, 1.0f)), e::error);
        EXPECT_THROW(s.commit(), e::error);
    }  // the device wrappers are gone; the scene keeps Embree's device alive
    ASSERT_TRUE(kept.has_value());
    EXPECT_FLOAT_EQ(kept->intersect({0, 0, 5}, {0, 0, -1}, 0.0f, inf)->t, 4.5f);
    e::device other;
    e::scene target(other);
    target = std::move(*kept);
    EXPECT_FLOAT_EQ(target.intersect({0, 0, 5}, {0, 0, -1}, 0.0f, inf)->t, 4.5f);
}

TEST(Embree, EmbreeErrorsBecomeOneExceptionType) {
    // rtcNewDevice rejects a malformed configuration: no device, an error code.
    try {
        const e::device bad("threads=abc");
        ADD_FAILURE() << "no error for a malformed configuration";
    } catch (const e::error& err) {
        EXPECT_NE(std::string(err.what()).find("threads=abc"), std::string::npos) << err.what();
    }
    // An error reported through the device's callback (here from a native call through
    // the handle) is thrown by the next check, with Embree's message.
    const e::device dev;
    EXPECT_NO_THROW(dev.check());
    EXPECT_EQ(rtcNewGeometry(dev.handle(), static_cast<RTCGeometryType>(99)), nullptr);
    try {
        dev.check("rtcNewGeometry");
        ADD_FAILURE() << "the callback's error was not thrown";
    } catch (const e::error& err) {
        EXPECT_NE(std::string(err.what()).find("invalid geometry type"), std::string::npos) << err.what();
    }
    EXPECT_NO_THROW(dev.check());  // reported once
    // Meshes Embree would trace wrongly are refused at the boundary.
    e::scene s(dev);
    g::triangle_mesh broken;
    broken.positions = {{0, 0, 0}, {1, 0, 0}};
    broken.triangles = {{0, 1, 2}};
    EXPECT_THROW(s.add_mesh(broken), e::error);
    EXPECT_THROW(s.add_mesh(g::triangle_mesh{}), e::error);
    auto nan = g::make_cube({0, 0, 0}, 1.0f);
    nan.positions[0].x = std::nanf("");
    EXPECT_THROW(s.add_mesh(nan), e::error);
    auto normals = g::make_cube({0, 0, 0}, 1.0f);  // shading normals and uvs: none or one per vertex, finite
    normals.normals.assign(normals.positions.size() - 1, glm::vec3(0, 0, 1));
    EXPECT_THROW(s.add_mesh(normals), e::error);
    normals.normals.assign(normals.positions.size(), glm::vec3(0, 0, 1));
    normals.normals[3].y = std::nanf("");
    EXPECT_THROW(s.add_mesh(normals), e::error);
    auto uvs = g::make_cube({0, 0, 0}, 1.0f);
    uvs.uvs.assign(uvs.positions.size() + 1, glm::vec2(0.5f));
    EXPECT_THROW(s.add_mesh(uvs), e::error);
    uvs.uvs.assign(uvs.positions.size(), glm::vec2(0.5f));
    uvs.uvs[0].x = std::numeric_limits<float>::infinity();
    EXPECT_THROW(s.add_mesh(uvs), e::error);
    EXPECT_EQ(s.add_mesh(g::make_cube({0, 0, 0}, 1.0f)), 0u);  // refusals take no id
}

TEST(Embree, NoRayFromInsideAClosedMeshEscapes) {
    // Robust mode: rays from inside leave through faces, edges and vertices alike. Rays
    // aimed exactly at the vertices and edge midpoints of the (rotated) cube are the
    // adversarial cases; random directions fill in.
    const auto mesh = g::transformed(g::make_cube({0, 0, 0}, 1.0f), g::make_transform({0.1f, 0, 0}, {30, 45, 10}, {1, 1, 1}));
    const e::device dev;
    e::scene s(dev);
    s.add_mesh(mesh);
    s.add_mesh(g::make_hollow_cube({5, 5, 5}, 2.0f, 1.0f));
    s.commit();
    const glm::vec3 o(0.1f, 0, 0);
    std::vector<glm::vec3> targets(mesh.positions);
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) targets.push_back(0.5f * (mesh.positions[t[k]] + mesh.positions[t[(k + 1) % 3]]));
    for (const auto& t : targets) EXPECT_TRUE(s.occluded(o, t - o, 0.0f, inf));
    std::mt19937 rng(3);
    std::normal_distribution<float> n;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 d(n(rng), n(rng), n(rng));
        EXPECT_TRUE(s.intersect(o, d, 0.0f, inf).has_value()) << i;
        const auto h = s.intersect({5, 5, 5}, glm::normalize(d), 0.0f, inf);  // from the cavity
        ASSERT_TRUE(h.has_value());
        EXPECT_EQ(h->geom_id, 1u);
        EXPECT_LE(h->t, 0.8661f);  // the inner wall: between 1/2 and √3/2 away
        EXPECT_GE(h->t, 0.4999f);
    }
}

TEST(Embree, ConcurrentQueriesMatchSerialOnes) {
    const e::device dev;
    e::scene s(dev);
    s.add_mesh(g::make_sphere({0, 0, 0}, 1.0f, 3));
    s.add_mesh(g::make_hollow_cube({2, 0, 0}, 1.0f, 0.5f));
    s.commit();
    constexpr int n = 20000;
    std::vector<glm::vec3> origins(n), directions(n);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < n; ++i) {  // from around the objects towards them: about half hit
        const glm::vec3 o(3.0f * u(rng), 3.0f * u(rng), 3.0f * u(rng));
        origins[static_cast<std::size_t>(i)] = o;
        directions[static_cast<std::size_t>(i)] = glm::vec3(1.0f + 2.0f * u(rng), u(rng), u(rng)) - o;
    }
    struct result {
        std::optional<e::hit> hit;
        bool occluded = false;
    };
    const auto run = [&](int first, int step, std::vector<result>& out) {
        for (int i = first; i < n; i += step) {
            const auto k = static_cast<std::size_t>(i);
            out[k] = {s.intersect(origins[k], directions[k], 0.0f, inf), s.occluded(origins[k], directions[k], 0.0f, inf)};
        }
    };
    std::vector<result> serial(n), parallel(n);
    run(0, 1, serial);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t) threads.emplace_back(run, t, 4, std::ref(parallel));
    for (auto& t : threads) t.join();
    int hits = 0;
    for (std::size_t i = 0; i < serial.size(); ++i) {
        const auto &a = serial[i], &b = parallel[i];
        ASSERT_EQ(a.hit.has_value(), b.hit.has_value()) << i;
        ASSERT_EQ(a.occluded, a.hit.has_value()) << i;
        ASSERT_EQ(b.occluded, b.hit.has_value()) << i;
        if (!a.hit) continue;
        ++hits;
        ASSERT_EQ(a.hit->t, b.hit->t) << i;
        ASSERT_EQ(a.hit->geom_id, b.hit->geom_id) << i;
        ASSERT_EQ(a.hit->prim_id, b.hit->prim_id) << i;
    }
    EXPECT_GT(hits, n / 4);
    EXPECT_NO_THROW(dev.check());
}

}  // namespace
