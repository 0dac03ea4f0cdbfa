// Ray throughput of iris::embree on a Cornell-box-like scene (5 walls, 2 rotated boxes, a
// light: 36 triangles): incoherent rays (origins uniform in the room, directions uniform
// on the sphere), closest hit and any hit, 1 and 2 threads, through the wrapper and
// through raw rtcIntersect1/rtcOccluded1 on the same scene (the wrapper's overhead).
// Compiles to nothing when iris::embree is not built (bench/CMakeLists.txt links it then).
#if __has_include(<iris/embree/embree.hpp>)
#include <benchmark/benchmark.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <embree3/rtcore.h>

#include <iris/embree/embree.hpp>
#include <iris/geometry/triangle_mesh.hpp>

namespace {

namespace g = iris::geometry;

constexpr float inf = std::numeric_limits<float>::infinity();

// The room [0, 5.5]^3 (open towards +z), a tall and a short box, a light under the ceiling.
void add_cornell(iris::embree::scene& scene) {
    const float s = 5.5f;
    scene.add_mesh(g::make_quad({s / 2, 0, s / 2}, {0, 0, s}, {s, 0, 0}));  // floor, facing +y
    scene.add_mesh(g::make_quad({s / 2, s, s / 2}, {s, 0, 0}, {0, 0, s}));  // ceiling, facing −y
    scene.add_mesh(g::make_quad({s / 2, s / 2, 0}, {s, 0, 0}, {0, s, 0}));  // back, facing +z
    scene.add_mesh(g::make_quad({0, s / 2, s / 2}, {0, s, 0}, {0, 0, s}));  // left, facing +x
    scene.add_mesh(g::make_quad({s, s / 2, s / 2}, {0, 0, s}, {0, s, 0}));  // right, facing −x
    scene.add_mesh(g::transformed(g::make_box({-0.8f, 0, -0.8f}, {0.8f, 3.3f, 0.8f}), g::make_transform({1.9f, 0, 2.0f}, {0, 17, 0}, {1, 1, 1})));
    scene.add_mesh(g::transformed(g::make_cube({0, 0.8f, 0}, 1.6f), g::make_transform({3.7f, 0, 3.4f}, {0, -18, 0}, {1, 1, 1})));
    scene.add_mesh(g::make_quad({s / 2, s - 0.01f, s / 2}, {1.3f, 0, 0}, {0, 0, 1.1f}));  // light, facing −y
    scene.commit();
}

struct cornell {
    iris::embree::device device{};
    iris::embree::scene scene{device};
    std::vector<glm::vec3> origins, directions;  // 2^16 incoherent rays, cycled through

    cornell() {
        add_cornell(scene);
        std::mt19937 rng(1);
        std::uniform_real_distribution<float> u(0.0f, 5.5f);
        std::normal_distribution<float> n;
        for (int i = 0; i < (1 << 16); ++i) {
            origins.emplace_back(u(rng), u(rng), u(rng));
            directions.emplace_back(n(rng), n(rng), n(rng));
        }
    }
};

const cornell& scene() {
    static const cornell c;  // built once, shared read-only by all benchmark threads
    return c;
}

void BM_embree_intersect(benchmark::State& state) {
    const cornell& c = scene();
    std::size_t i = static_cast<std::size_t>(state.thread_index()) * 4099u;
    for (auto _ : state) {
        const std::size_t k = i++ & (c.origins.size() - 1);
        benchmark::DoNotOptimize(c.scene.intersect(c.origins[k], c.directions[k], 0.0f, inf));
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_embree_intersect)->Threads(1)->Threads(2)->UseRealTime();

void BM_embree_occluded(benchmark::State& state) {
    const cornell& c = scene();
    std::size_t i = static_cast<std::size_t>(state.thread_index()) * 4099u;
    for (auto _ : state) {
        const std::size_t k = i++ & (c.origins.size() - 1);
        benchmark::DoNotOptimize(c.scene.occluded(c.origins[k], c.directions[k], 0.0f, inf));
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_embree_occluded)->Threads(1)->Threads(2)->UseRealTime();

// The same queries straight through Embree's C API, for the wrapper's overhead.
void BM_embree_raw_intersect(benchmark::State& state) {
    const cornell& c = scene();
    std::size_t i = static_cast<std::size_t>(state.thread_index()) * 4099u;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (auto _ : state) {
        const std::size_t k = i++ & (c.origins.size() - 1);
        RTCRayHit rh;
        rh.ray = {c.origins[k].x, c.origins[k].y, c.origins[k].z, 0.0f, c.directions[k].x, c.directions[k].y, c.directions[k].z,
                  0.0f, inf, ~0u, 0u, 0u};
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(c.scene.handle(), &context, &rh);
        benchmark::DoNotOptimize(rh.hit.geomID);
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_embree_raw_intersect)->Threads(1)->Threads(2)->UseRealTime();

void BM_embree_raw_occluded(benchmark::State& state) {
    const cornell& c = scene();
    std::size_t i = static_cast<std::size_t>(state.thread_index()) * 4099u;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (auto _ : state) {
        const std::size_t k = i++ & (c.origins.size() - 1);
        RTCRay r{c.origins[k].x, c.origins[k].y, c.origins[k].z, 0.0f, c.directions[k].x, c.directions[k].y, c.directions[k].z,
                 0.0f, inf, ~0u, 0u, 0u};
        rtcOccluded1(c.scene.handle(), &context, &r);
        benchmark::DoNotOptimize(r.tfar);
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_embree_raw_occluded)->Threads(1)->Threads(2)->UseRealTime();

// Building the scene (robust, high-quality BVH) from scratch: what a render pays once.
void BM_embree_build_cornell(benchmark::State& state) {
    const iris::embree::device device;
    for (auto _ : state) {
        iris::embree::scene s(device);
        add_cornell(s);
        benchmark::DoNotOptimize(s.handle());
    }
}
BENCHMARK(BM_embree_build_cornell)->Unit(benchmark::kMicrosecond);

}  // namespace
#endif
