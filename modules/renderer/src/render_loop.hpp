#pragma once
// The progressive loop shared by every instantiation (internal to iris::renderer).
#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "iris/render/camera.hpp"
#include "iris/render/film.hpp"
#include "iris/render/random.hpp"
#include "iris/renderer/renderer.hpp"
#include "dispatch.hpp"

namespace iris::renderer::detail {

/// \brief One tile of one pass: which pixels, which sample.
struct tile_job {
    int x0, y0, x1, y1;  ///< pixels [x0, x1) × [y0, y1)
    int width;           ///< of the image (pixel index = y · width + x)
    sampler_setup sampler;
    std::uint64_t sample;
};

/// \brief Trace one sample in every pixel of a tile into the film; returns the rays traced.
/// The hot loop of a render: compiled once per instruction set below.
template <class Integrator, class Tracer, class Distribution>
inline std::uint64_t tile_body(const Integrator& integ, const Tracer& tracer, const camera_rays& cam,
                               const tile_job& job, const Distribution& dist, float alpha, film& f) {
    std::uint64_t rays = 0;
    // the spectral film's row (film.hpp): one per tile call, filled by each sample and
    // cleared by the film as it sums it
    const film::spectral_parts* spectral = f.spectral_state();
    std::vector<double> values(spectral ? static_cast<std::size_t>(spectral->bands.count) : 0, 0.0);
    std::optional<spectral_row> row;
    if (spectral) row.emplace(spectral->bands, values.data());
    for (int y = job.y0; y < job.y1; ++y)
        for (int x = job.x0; x < job.x1; ++x) {
            const auto pixel = static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(job.width) +
                               static_cast<std::uint64_t>(x);
            sample_stream rng(job.sampler, static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y), pixel, job.sample);
            const glm::vec3 d = cam.direction(x, y, rng.next2());
            // one call for both (the integrator is inlined here once: its spectral steps are branches)
            const path_sample s = integ.trace(tracer, cam.origin(), d, dist, alpha, rng, row ? &*row : nullptr);
            if (row) f.add(static_cast<std::size_t>(pixel), s.value, job.sample, values.data());
            else f.add(static_cast<std::size_t>(pixel), s.value, job.sample);
            rays += s.rays;
        }
    return rays;
}

// The same loop for wider instruction sets. `flatten` inlines the whole integrator into
// each copy, so all of it is compiled for that target (the B term's 80-wide spectra are
// 10 AVX registers instead of 20 SSE ones); calls that leave the translation unit
// (Embree, libm) stay as they are. The renderer is compiled with -ffp-contract=off: no
// copy fuses a multiply and an add, no loop reassociates a sum (the B term's XYZ sums run
// in lanes fixed by the code, path_integrator::trace), and division and square root are correctly
// rounded at any width — so every copy computes bit-identical images.
//
// A build without the copies (IRIS_ISA_COPIES=OFF: the `asan` preset) does not flatten its
// one loop: nothing needs compiling for another target, and under -g GCC 12 overruns its
// variable-tracking limit on the flattened function and compiles it a second time without
// (one preset under ASan: 109 s flattened, 47 s not; docs/performance.md).
#if IRIS_ISA_DISPATCH
#define IRIS_TILE_FLATTEN [[gnu::flatten]]
#else
#define IRIS_TILE_FLATTEN
#endif
template <class Integrator, class Tracer, class Distribution>
IRIS_TILE_FLATTEN std::uint64_t tile_baseline(const Integrator& integ, const Tracer& tracer, const camera_rays& cam,
                                             const tile_job& job, const Distribution& dist, float alpha, film& f) {
    return tile_body(integ, tracer, cam, job, dist, alpha, f);
}
#if IRIS_ISA_DISPATCH
template <class Integrator, class Tracer, class Distribution>
[[gnu::target("arch=x86-64-v3"), gnu::flatten]] std::uint64_t tile_avx2(const Integrator& integ, const Tracer& tracer,
                                                                        const camera_rays& cam, const tile_job& job,
                                                                        const Distribution& dist, float alpha, film& f) {
    return tile_body(integ, tracer, cam, job, dist, alpha, f);
}
#endif

/// \brief The tile function of instruction set I (baseline where the build has no copies).
template <isa I, class Integrator, class Tracer, class Distribution>
constexpr auto tile_function() {
#if IRIS_ISA_DISPATCH
    if constexpr (I == isa::avx2) return &tile_avx2<Integrator, Tracer, Distribution>;
    else return &tile_baseline<Integrator, Tracer, Distribution>;
#else
    return &tile_baseline<Integrator, Tracer, Distribution>;
#endif
}

/// \brief The progressive loop every estimator shares: rounds of `ranks` passes from
/// start_spp on, this rank rendering pass round + rank; cancellation, the hooks and the
/// status are kept here. `render_pass(i, alpha, dist, arena, enter)` renders pass i (with
/// {α_i, p_α} from `distribution_for(i)`, built once per pass and shared read-only by all
/// threads) in `arena`, calls `enter()` at the start of each parallel chunk, and returns
/// the rays traced.
template <class DistributionFor, class RenderPass>
void for_each_pass(const options& opt, DistributionFor&& distribution_for, film& f, status& st, const hooks& h,
                   RenderPass&& render_pass) {
    std::atomic<std::uint64_t> used{0};  // arena slots that rendered a chunk (slots ≥ 64 share bit 63)
    tbb::task_arena arena(opt.threads > 0 ? opt.threads : tbb::info::default_concurrency());
    st.threads = arena.max_concurrency();
    const auto enter = [&] {
        const int slot = tbb::this_task_arena::current_thread_index();
        used.fetch_or(std::uint64_t{1} << std::clamp(slot, 0, 63), std::memory_order_relaxed);
        if (h.on_tile) h.on_tile(slot);
    };
    if (h.on_start && !h.on_start(st)) return;
    // Rounds of `ranks` passes from start_spp on; this rank renders pass round + rank.
    for (int round = opt.start_spp; round < opt.spp; round += opt.ranks) {
        if (h.cancel && h.cancel->load()) {
            st.interrupted = true;
            break;
        }
        const int i = round + opt.rank;
        if (i < opt.spp) {
            const auto pass_start = std::chrono::steady_clock::now();  // time passes, not the hooks
            const auto [alpha, dist] = distribution_for(i);
            const std::uint64_t before = f.dropped();
            st.rays += render_pass(i, alpha, dist, arena, enter);
            st.alpha = alpha;
            st.threads_used = std::popcount(used.load(std::memory_order_relaxed));
            st.samples += static_cast<std::uint64_t>(f.width()) * static_cast<std::uint64_t>(f.height());
            st.nan_inf += f.dropped() - before;
            st.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - pass_start).count();
        }
        st.spp_done = std::min(round + opt.ranks, opt.spp);
        if (h.on_pass && !h.on_pass(f, st)) break;
    }
}

/// \brief Run passes [opt.start_spp, opt.spp) — this rank's share of them — of the path
/// tracer (or the BSDF-only estimator): one sample per pixel per pass, tile by tile, with
/// the hot loop compiled for instruction set I.
template <isa I, class Integrator, class Tracer, class DistributionFor>
void run_passes(const Integrator& integ, const Tracer& tracer, const camera_rays& cam, const options& opt,
                DistributionFor&& distribution_for, film& f, status& st, const hooks& h) {
    const int w = f.width(), ht = f.height();
    const int ts = std::max(1, opt.tile_size);
    const int tiles_x = (w + ts - 1) / ts, tiles_y = (ht + ts - 1) / ts;
    const int tiles = tiles_x * tiles_y;
    const sampler_setup sampler = make_sampler(opt);
    std::vector<std::uint64_t> tile_rays(static_cast<std::size_t>(tiles));
    using distribution = std::remove_cvref_t<decltype(distribution_for(0).second)>;
    constexpr auto tile = tile_function<I, Integrator, Tracer, distribution>();
    for_each_pass(opt, distribution_for, f, st, h,
                  [&](int i, float alpha, const distribution& dist, tbb::task_arena& arena, const auto& enter) {
                      arena.execute([&] {
                          tbb::parallel_for(tbb::blocked_range<int>(0, tiles), [&](const tbb::blocked_range<int>& r) {
                              enter();
                              for (int t = r.begin(); t != r.end(); ++t) {
                                  const int x0 = (t % tiles_x) * ts, y0 = (t / tiles_x) * ts;
                                  const tile_job job{x0, y0, std::min(x0 + ts, w), std::min(y0 + ts, ht), w, sampler,
                                                     static_cast<std::uint64_t>(i)};
                                  tile_rays[static_cast<std::size_t>(t)] = tile(integ, tracer, cam, job, dist, alpha, f);
                              }
                          });
                      });
                      std::uint64_t rays = 0;
                      for (auto r : tile_rays) rays += r;  // fixed reduction order
                      return rays;
                  });
}

}  // namespace iris::renderer::detail
