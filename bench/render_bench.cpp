// Whole-renderer throughput (samples/s, rays/s) through iris::renderer on built-in scenes:
// presets side by side (what the B term of PropagateUnused costs per sample), 1 vs 2
// threads, and the hot loop compiled for each
// instruction set this CPU runs (baseline SSE2, AVX2, AVX-512). Compiles to nothing without
// iris::renderer and iris::scene (bench/CMakeLists.txt links them when they exist).
// Run: build/release/bench/iris-bench --benchmark_filter=Render
#if __has_include(<iris/renderer/renderer.hpp>) && __has_include(<iris/scene/scene.hpp>)
#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <variant>

#include <iris/renderer/renderer.hpp>
#include <iris/scene/scene.hpp>

namespace {

/// \brief The built-in scenes, built once.
const iris::scene_desc& scene(const std::string& name) {
    static std::map<std::string, iris::scene_desc> cache;
    if (auto it = cache.find(name); it != cache.end()) return it->second;
    return cache.emplace(name, iris::scene::builtin_scene(name)).first->second;
}

void render(benchmark::State& state, const std::string& scene_name, const std::string& preset, int threads,
            const std::string& isa = "auto", const std::string& sampler = "independent") {
    const auto& s = scene(scene_name);
    iris::renderer::options o;
    o.preset = preset;
    o.width = 128;
    o.height = 128;
    o.spp = 4;
    o.threads = threads;
    o.nthold = 1 << 20;  // α stays < 1: PropagateUnused evaluates its B term on every sample
    o.isa = isa;
    o.sampler = sampler;
    double samples = 0, rays = 0;
    for (auto _ : state) {
        iris::film f(1, 1);
        const auto st = iris::renderer::render(s, o, f);
        samples += static_cast<double>(st.samples);
        rays += static_cast<double>(st.rays);
        benchmark::DoNotOptimize(f.mean(0));
    }
    state.counters["samples/s"] = benchmark::Counter(samples, benchmark::Counter::kIsRate);
    state.counters["rays/s"] = benchmark::Counter(rays, benchmark::Counter::kIsRate);
}

/// \brief One short render (1 spp, 64 × 48) per iteration, on the scene description (the
/// ray tracer and light sampler built by every call) or on a prepared scene (built once):
/// the per-call cost a progressive or sweeping caller (the Python module) no longer pays.
void render_call(benchmark::State& state, const std::string& scene_name, bool prepared) {
    const auto& s = scene(scene_name);
    const iris::renderer::prepared_scene ready = iris::renderer::prepared_scene::borrow(s);
    iris::renderer::options o;
    o.width = 64;
    o.height = 48;
    o.spp = 1;
    o.threads = 1;
    for (auto _ : state) {
        iris::film f(1, 1);
        const auto st = prepared ? iris::renderer::render(ready, o, f) : iris::renderer::render(s, o, f);
        benchmark::DoNotOptimize(st.rays);
    }
}

void register_all() {
    for (const char* sc : {"cornell", "falling-cubes", "prism"})
        for (bool prepared : {false, true})
            benchmark::RegisterBenchmark(
                (std::string("RenderCall/") + sc + (prepared ? "/prepared" : "/scene_desc")).c_str(),
                [=](benchmark::State& st) { render_call(st, sc, prepared); })
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime()
                ->MinTime(1.0);
    for (const char* sc : {"cornell", "falling-cubes"})
        for (const char* p : {"hwss", "paper", "paper-fast", "restrict-only", "scaled-pdf", "hwss-c1", "hwss-c8"})
            for (int t : {1, 2})
                benchmark::RegisterBenchmark((std::string("Render/") + sc + "/" + p + "/threads:" + std::to_string(t)).c_str(),
                                             [=](benchmark::State& st) { render(st, sc, p, t); })
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime()
                    ->MinTime(1.0);
    // the samplers' cost per camera sample (issue 12's target: <= 5 % over independent)
    for (const char* sc : {"cornell", "falling-cubes"})
        for (const char* p : {"hwss", "paper"})
            for (const char* smp : {"independent", "sobol", "zsobol"})
                benchmark::RegisterBenchmark((std::string("Render/") + sc + "/" + p + "/sampler:" + smp).c_str(),
                                             [=](benchmark::State& st) { render(st, sc, p, 1, "auto", smp); })
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime()
                    ->MinTime(1.0);
    // the hot loop per instruction set (images are identical; renderer_core_test checks that)
    for (const auto& isa : iris::renderer::instruction_sets())
        for (const char* p : {"hwss", "paper", "paper-fast"})
            benchmark::RegisterBenchmark((std::string("Render/falling-cubes/") + p + "/isa:" + isa).c_str(),
                                         [=](benchmark::State& st) { render(st, "falling-cubes", p, 1, isa); })
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime()
                ->MinTime(1.0);
}

const bool registered = (register_all(), true);

}  // namespace
#endif
