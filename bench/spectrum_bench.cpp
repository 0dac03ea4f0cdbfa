// Costs of the spectral core's building blocks, the floor under every sample.
#include <benchmark/benchmark.h>

#include <iris/spectrum/color.hpp>
#include <iris/spectrum/named.hpp>

namespace {

void BM_tabulated_eval(benchmark::State& state) {
    const auto d65 = iris::find_illuminant("D65")->spectrum();
    double l = 380.0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(d65(l));
        l = l >= 780.0 ? 380.0 : l + 0.731;
    }
}
BENCHMARK(BM_tabulated_eval);

void BM_sellmeier_n(benchmark::State& state) {
    const auto g = iris::find_glass("N-SF11")->sellmeier;
    double l = 380.0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(g.n(l));
        l = l >= 780.0 ? 380.0 : l + 0.731;
    }
}
BENCHMARK(BM_sellmeier_n);

void BM_sampled_to_xyz_c4(benchmark::State& state) {
    const iris::sampled_wavelengths<4> wl({450.f, 530.f, 610.f, 690.f}, {0.0025f, 0.0025f, 0.0025f, 0.0025f});
    const iris::sampled_spectrum<4> s(1.0f);
    for (auto _ : state) benchmark::DoNotOptimize(iris::sampled_to_xyz(s, wl));
}
BENCHMARK(BM_sampled_to_xyz_c4);

}  // namespace
