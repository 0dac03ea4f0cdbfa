// The B term's hot loop alone: its weight at a smooth-glass vertex (Fresnel at every bin,
// from the bins' η² and 1/η² tables) times the path throughput, per vertex, for 80 bins
// (`paper`) and 8 (`paper-fast`), compiled as the renderer compiles its hot loop: for the
// baseline x86-64 and, where the CPU has them, AVX2 and AVX-512 (GCC's target attribute;
// this file gets the renderer's -fno-trapping-math -ffp-contract=off, bench/CMakeLists.txt).
// Run: build/release/bench/iris-bench --benchmark_filter=BTerm
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include <iris/render/bins.hpp>
#include <iris/render/bsdf.hpp>

namespace {

template <std::size_t B>
struct glass_tables {
    iris::bin_lattice<B> lattice{380.0f, 780.0f};
    iris::binned_spectrum<B> eta2, inv_eta2;
    glass_tables() {
        const iris::sellmeier_ior bk7{1.03961212, 0.231792344, 1.01046945, 0.00600069867, 0.0200179144, 103.560653};
        eta2 = iris::binned_spectrum<B>(lattice, [&](double l) { return std::pow(iris::refractive_index(bk7, l), 2.0); });
        inv_eta2 = iris::binned_spectrum<B>(lattice, [&](double l) { return std::pow(iris::refractive_index(bk7, l), -2.0); });
    }
};

/// \brief η² and 1/η² of the glass at one sample's bins, as the integrator reads them.
template <std::size_t B>
struct table_spectra {
    const glass_tables<B>& t;
    iris::bin_position bp;
    std::array<float, B>& s1;
    std::array<float, B>& s2;
    auto eta2() const { return t.eta2.at(bp, s1); }
    auto inv_eta2() const { return t.inv_eta2.at(bp, s2); }
};

/// \brief `count` glass vertices at varying angles, sides, lobes and bin jitters.
template <std::size_t B>
inline float glass_vertices(const glass_tables<B>& t, int count) {
    const iris::material::dielectric glass{iris::constant_ior{1.5}, 0.0f};
    iris::sampled_spectrum<B> tb(1.0f);
    std::array<float, B> s1, s2;
    float acc = 0.0f;
    for (int i = 0; i < count; ++i) {
        const float c = 0.05f + 0.9f * static_cast<float>(i & 1023) / 1024.0f;
        const glm::vec3 wo(std::sqrt(1.0f - c * c), 0.0f, (i & 1024) ? c : -c);
        const iris::bin_position bp = t.lattice.position(static_cast<float>(i & 255) / 256.0f);
        const table_spectra<B> spectra{t, bp, s1, s2};
        const auto w = iris::smooth_dielectric{glass}.follow<B>(
            wo, wo, (i & 2048) ? iris::lobe::reflection : iris::lobe::transmission, spectra);
        for (std::size_t b = 0; b < B; ++b) tb[b] *= w[b] * 1.5f;
        acc += tb[static_cast<std::size_t>(i) % B];
        if (!(tb[0] > 1e-20f && tb[0] < 1e20f)) tb = iris::sampled_spectrum<B>(1.0f);
    }
    return acc;
}

template <std::size_t B>
[[gnu::flatten, gnu::noinline]] float run_baseline(const glass_tables<B>& t, int n) { return glass_vertices(t, n); }
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
template <std::size_t B>
[[gnu::target("arch=x86-64-v3"), gnu::flatten, gnu::noinline]] float run_avx2(const glass_tables<B>& t, int n) {
    return glass_vertices(t, n);
}
template <std::size_t B>
[[gnu::target("arch=x86-64-v4"), gnu::flatten, gnu::noinline]] float run_avx512(const glass_tables<B>& t, int n) {
    return glass_vertices(t, n);
}
#endif

template <std::size_t B>
void glass_vertex(benchmark::State& state, float (*run)(const glass_tables<B>&, int)) {
    static const glass_tables<B> tables;
    constexpr int per_iteration = 4096;
    for (auto _ : state) benchmark::DoNotOptimize(run(tables, per_iteration));
    state.SetItemsProcessed(state.iterations() * per_iteration);  // items/s = glass vertices per second
}

template <std::size_t B>
void register_bins() {
    const std::string name = "BTerm/glass_vertex/bins:" + std::to_string(B) + "/isa:";
    benchmark::RegisterBenchmark((name + "baseline").c_str(), [](benchmark::State& s) { glass_vertex<B>(s, &run_baseline<B>); });
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("x86-64-v3"))
        benchmark::RegisterBenchmark((name + "avx2").c_str(), [](benchmark::State& s) { glass_vertex<B>(s, &run_avx2<B>); });
    if (__builtin_cpu_supports("x86-64-v4"))
        benchmark::RegisterBenchmark((name + "avx512").c_str(), [](benchmark::State& s) { glass_vertex<B>(s, &run_avx512<B>); });
#endif
}

const bool registered = (register_bins<80>(), register_bins<8>(), true);

}  // namespace
