// Costs of the sampling policies (targets in docs/performance.md, "Wavelength sampling"):
//   BM_sample_wavelengths<preset>   one hero-rotated draw of C wavelengths with their pdfs,
//                                   at the preset's first sample (α_0: the most restricted)
//   BM_rebuild_distribution<kernel/base>   building p_α for a new α (once per pass)
//   BM_restriction<kernel>          one r_α(λ) (the B term evaluates it once per bin)
//   BM_mis_weight_c4                one HWSS MIS weight over 4 path pdfs
//   BM_sample_stream<sampler>       the numbers of one camera sample of a 4-bounce path with
//                                   next-event estimation (24 numbers in 15 slots, random.hpp)
//   BM_film_add                     one sample's XYZ added to the film (film.hpp)
// Targets: a 4-wavelength restricted draw ≤ 30 ns and ≤ 2× the unrestricted (`hwss`) draw
// of the same run; a rebuild ≤ 20 µs.
#include <benchmark/benchmark.h>

#include <array>
#include <string>

#include <iris/render/film.hpp>
#include <iris/render/random.hpp>
#include <iris/sampling/sampling.hpp>
#include <iris/spectrum/named.hpp>

namespace {

/// \brief 4096 uniforms, cycled, so the generator's cost stays out of the timings.
const std::array<float, 4096>& uniforms() {
    static const std::array<float, 4096> u = [] {
        std::array<float, 4096> a{};
        iris::counter_rng rng(2024);
        for (float& x : a) x = rng.next();
        return a;
    }();
    return u;
}

template <class P>
void sample_wavelengths(benchmark::State& state) {
    P cfg;
    const auto dist = cfg.distribution(cfg.alpha(0));
    const auto& u = uniforms();
    std::size_t i = 0;
    for (auto _ : state) {
        const auto wl = dist.template sample_wavelengths<P::wavelength_count>(u[i++ & 4095]);
        benchmark::DoNotOptimize(wl);
    }
    state.SetItemsProcessed(state.iterations());
}

template <class Kernel, class Base>
void rebuild(benchmark::State& state, Kernel kernel, Base base) {
    float alpha = 0.0f;
    for (auto _ : state) {
        const iris::restricted_distribution dist(base, kernel, alpha, iris::spectral_domain{});
        benchmark::DoNotOptimize(&dist);
        alpha = alpha >= 1.0f ? 0.0f : alpha + 1.0f / 512.0f;  // a new α every time, as a pass does
    }
}

template <class Kernel>
void restriction_eval(benchmark::State& state, Kernel kernel) {
    const auto r = kernel.bind(0.3f, iris::spectral_domain{});
    const auto& u = uniforms();
    std::size_t i = 0;
    for (auto _ : state) benchmark::DoNotOptimize(r(380.0f + 400.0f * u[i++ & 4095]));
}

void BM_mis_weight_c4(benchmark::State& state) {
    const iris::sampled_spectrum<4> path({0.7f, 1.3f, 0.2f, 2.9f});
    const auto& u = uniforms();
    std::size_t i = 0;
    for (auto _ : state) benchmark::DoNotOptimize(iris::hwss_mis_weight(0.001f + u[i++ & 4095], path));
}
BENCHMARK(BM_mis_weight_c4);

/// \brief What a sampler costs per camera sample, apart from the rest of the render: the
/// slots of a 4-bounce diffuse path with next-event estimation (pixel, hero u, then per
/// bounce light point, light choice, lobe, BSDF direction, roulette) for the pixels of a
/// 64 × 64 image, one sample index per pass.
void BM_sample_stream(benchmark::State& state) {
    const auto kind = static_cast<iris::sampler_kind>(state.range(0));
    const auto setup = iris::sampler_setup::make(kind, 7, 64);
    std::uint32_t x = 0, y = 0, sample = 0;
    for (auto _ : state) {
        iris::sample_stream s(setup, x, y, std::uint64_t{y} * 64 + x, sample);
        float acc = s.next2().x + s.next();
        for (int k = 0; k < 4; ++k) {
            s.start_bounce(k);
            const glm::vec2 p = s.next2();
            acc += p.x + p.y + s.next() + s.next();
            const glm::vec2 d = s.next2();
            acc += d.x + d.y + s.next();
        }
        benchmark::DoNotOptimize(acc);
        if (++x == 64) {
            x = 0;
            if (++y == 64) y = 0, ++sample;
        }
    }
    state.SetLabel(std::string(iris::sampler_name(kind)));
}
BENCHMARK(BM_sample_stream)->DenseRange(0, 2);

/// \brief The film's share of a camera sample: adding one XYZ (values over 10 orders of
/// magnitude) to a 256 × 256 film, pixel after pixel (issue 14: exact accumulation).
void BM_film_add(benchmark::State& state) {
    iris::film f(256, 256);
    const auto& u = uniforms();
    std::size_t k = 0, i = 0;
    for (auto _ : state) {
        f.add(i, {u[k & 4095] * 3.0, u[(k + 1) & 4095] * 1e4, u[(k + 2) & 4095] * 1e-6});
        k += 3;
        i = (i + 1) & 65535;
    }
    benchmark::DoNotOptimize(f.mean(7));
}
BENCHMARK(BM_film_add);

const int registered = [] {
    iris::for_each_preset([]<class P>() {
        benchmark::RegisterBenchmark(("BM_sample_wavelengths<" + std::string(P::cli_name) + ">").c_str(),
                                     sample_wavelengths<P>);
    });
    using namespace iris;
    const spectral_pdf::illuminant d65(find_illuminant("D65")->spectrum());
    auto kernels = [&](const auto& base, const std::string& base_name) {
        benchmark::RegisterBenchmark(("BM_rebuild_distribution<unrestricted/" + base_name + ">").c_str(),
                                     [=](benchmark::State& s) { rebuild(s, restriction::unrestricted{}, base); });
        benchmark::RegisterBenchmark(("BM_rebuild_distribution<box/" + base_name + ">").c_str(),
                                     [=](benchmark::State& s) { rebuild(s, restriction::box{}, base); });
        benchmark::RegisterBenchmark(("BM_rebuild_distribution<multibox3/" + base_name + ">").c_str(),
                                     [=](benchmark::State& s) { rebuild(s, restriction::multi_box<3>{}, base); });
        benchmark::RegisterBenchmark(("BM_rebuild_distribution<gaussian/" + base_name + ">").c_str(),
                                     [=](benchmark::State& s) { rebuild(s, restriction::gaussian{}, base); });
    };
    kernels(spectral_pdf::uniform{}, "uniform");
    kernels(spectral_pdf::visible{}, "visible");
    kernels(d65, "illuminant");
    benchmark::RegisterBenchmark("BM_restriction<box>", [](benchmark::State& s) { restriction_eval(s, restriction::box{}); });
    benchmark::RegisterBenchmark("BM_restriction<multibox3>",
                                 [](benchmark::State& s) { restriction_eval(s, restriction::multi_box<3>{}); });
    benchmark::RegisterBenchmark("BM_restriction<gaussian>",
                                 [](benchmark::State& s) { restriction_eval(s, restriction::gaussian{}); });
    return 0;
}();

}  // namespace
