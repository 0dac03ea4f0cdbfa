// What the bias fade (accumulation::fade, film.hpp's fade layer) costs: film::add with and
// without the layer (per sample: the running mean's three fixed-point sums, plus the
// layer's squares), and film::to_image with and without it (per image written: the blend
// over a 5 × 5 neighbourhood against the running mean). Films of 160×120 (the results'
// size), 1280×720 and 1920×1080, 8 synthetic samples per pixel (4 early, 4 late).
// Run: build/release/bench/iris-bench --benchmark_filter=Fade
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include <iris/render/film.hpp>

namespace {

/// \brief A w × h film with 8 samples per pixel (a fade layer split at 4 if `fade`).
iris::film make_film(int w, int h, bool fade) {
    iris::film f(w, h);
    if (fade) f.enable_fade(4);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 2.0);
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    for (std::uint64_t s = 0; s < 8; ++s)
        for (std::size_t i = 0; i < n; ++i) f.add(i, {u(rng), u(rng), u(rng)}, s);
    return f;
}

void BM_FadeAdd(benchmark::State& state) {
    const bool fade = state.range(0) != 0;
    constexpr int w = 160, h = 120;
    std::vector<iris::xyz> values(4096);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 2.0);
    for (auto& v : values) v = {u(rng), u(rng), u(rng)};
    iris::film f(w, h);
    if (fade) f.enable_fade(1u << 30);  // every sample early: the layer's longer branch
    std::size_t k = 0;
    std::uint64_t sample = 0;
    for (auto _ : state) {
        const std::size_t i = k % (w * h);
        f.add(i, values[k % values.size()], sample);
        if (i == w * h - 1) ++sample;
        ++k;
    }
    benchmark::DoNotOptimize(f.sum(0));
    state.SetItemsProcessed(static_cast<std::int64_t>(k));
}
BENCHMARK(BM_FadeAdd)->Arg(0)->Arg(1)->ArgName("fade");

void BM_FadeToImage(benchmark::State& state) {
    const bool fade = state.range(2) != 0;
    const iris::film f = make_film(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), fade);
    for (auto _ : state) {
        auto img = f.to_image();
        benchmark::DoNotOptimize(img.pixels().data());
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0) * state.range(1));
}
BENCHMARK(BM_FadeToImage)
    ->ArgNames({"w", "h", "fade"})
    ->Args({160, 120, 0})
    ->Args({160, 120, 1})
    ->Args({1280, 720, 0})
    ->Args({1280, 720, 1})
    ->Args({1920, 1080, 0})
    ->Args({1920, 1080, 1})
    ->Unit(benchmark::kMillisecond);

}  // namespace
