#pragma once
// The progressive loop of the light tracer (internal to iris::renderer): the passes of
// for_each_pass (render_loop.hpp) — ranks, cancellation, hooks, statistics — but each pixel's
// sample launches one light subpath, whose splats land anywhere on the film; a pass's
// splats are gathered per thread and added at its end with film::add_pass, which sums
// them exactly, so no image depends on the thread count, the tiling or the rank count. A
// thread hands its list to the pass whenever it reaches film::splat_chunk splats (under a
// lock; the sums are exact, so when it does changes nothing): memory per thread is bounded
// whatever the image size.
// Compiled for the baseline instruction set only (docs/performance.md: what a copy costs
// in build time, the light tracer does not yet repay).
#include <cstdint>
#include <mutex>
#include <type_traits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "iris/render/camera.hpp"
#include "iris/render/film.hpp"
#include "iris/render/random.hpp"
#include "iris/renderer/renderer.hpp"
#include "render_loop.hpp"

namespace iris::renderer::detail {

template <class Integrator, class Tracer, class DistributionFor>
void run_light_passes(const Integrator& integ, const Tracer& tracer, const options& opt,
                      DistributionFor&& distribution_for, film& f, status& st, const hooks& h) {
    const int w = f.width(), rows = f.height();
    const sampler_setup sampler = make_sampler(opt);
    const double paths = static_cast<double>(w) * static_cast<double>(rows);  // one light subpath per pixel per pass
    std::vector<std::uint64_t> row_rays(static_cast<std::size_t>(rows));
    tbb::enumerable_thread_specific<std::vector<splat>> splats;
    std::mutex film_lock;
    const auto flush_if_full = [&](std::vector<splat>& out) {  // a thread's list stays under film::splat_chunk
        if (out.size() < film::splat_chunk) return;
        const std::lock_guard<std::mutex> hold(film_lock);
        f.add_splats(out);
        out.clear();
    };
    using distribution = std::remove_cvref_t<decltype(distribution_for(0).second)>;
    for_each_pass(opt, distribution_for, f, st, h,
                  [&](int i, float alpha, const distribution& dist, tbb::task_arena& arena, const auto& enter) {
                      for (auto& list : splats) list.clear();
                      f.begin_pass();
                      arena.execute([&] {
                          tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& r) {
                              enter();
                              std::vector<splat>& out = splats.local();
                              for (int y = r.begin(); y != r.end(); ++y) {
                                  std::uint64_t rays = 0;
                                  for (int x = 0; x < w; ++x) {
                                      const auto pixel = static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(w) +
                                                         static_cast<std::uint64_t>(x);
                                      sample_stream rng(sampler, static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y),
                                                        pixel, static_cast<std::uint64_t>(i));
                                      rays += integ.trace(tracer, dist, alpha, rng, paths, out);
                                      flush_if_full(out);
                                  }
                                  row_rays[static_cast<std::size_t>(y)] = rays;
                              }
                          });
                      });
                      for (const auto& list : splats) f.add_splats(list);
                      f.end_pass(static_cast<std::uint64_t>(i));
                      std::uint64_t rays = 0;
                      for (auto r : row_rays) rays += r;  // fixed reduction order
                      return rays;
                  });
}

/// \brief The light subpaths' sampler of a bidirectional render: the same kind, its own
/// seed, so a pixel's light subpath numbers are a second stream of that pixel and sample
/// (stratified within itself for the Sobol' samplers), independent of the camera's.
inline sampler_setup light_stream_setup(sampler_setup s) noexcept {
    s.seed = iris::detail::counter_hash(s.seed ^ 0x6c69676874ull);  // "light"
    return s;
}

/// \brief The progressive loop of bidirectional path tracing: each pixel's sample is a camera
/// subpath (jittered in the pixel, the pixel's stream) and a light subpath (the pixel's
/// second stream, `light_stream_setup`); everything it adds — its own pixel's value and the
/// t = 1 splats — goes through the per-thread splat lists and film::add_pass, as the light
/// tracer's.
template <class Integrator, class Tracer, class DistributionFor>
void run_bdpt_passes(const Integrator& integ, const Tracer& tracer, const camera_rays& cam, const options& opt,
                     DistributionFor&& distribution_for, film& f, status& st, const hooks& h) {
    const int w = f.width(), rows = f.height();
    const sampler_setup sampler = make_sampler(opt);
    const sampler_setup light_sampler = light_stream_setup(sampler);
    std::vector<std::uint64_t> row_rays(static_cast<std::size_t>(rows));
    tbb::enumerable_thread_specific<std::vector<splat>> splats;
    std::mutex film_lock;
    const auto flush_if_full = [&](std::vector<splat>& out) {  // a thread's list stays under film::splat_chunk
        if (out.size() < film::splat_chunk) return;
        const std::lock_guard<std::mutex> hold(film_lock);
        f.add_splats(out);
        out.clear();
    };
    tbb::enumerable_thread_specific<typename Integrator::workspace> spaces;
    using distribution = std::remove_cvref_t<decltype(distribution_for(0).second)>;
    for_each_pass(opt, distribution_for, f, st, h,
                  [&](int i, float alpha, const distribution& dist, tbb::task_arena& arena, const auto& enter) {
                      for (auto& list : splats) list.clear();
                      f.begin_pass();
                      arena.execute([&] {
                          tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& r) {
                              enter();
                              std::vector<splat>& out = splats.local();
                              auto& ws = spaces.local();
                              for (int y = r.begin(); y != r.end(); ++y) {
                                  std::uint64_t rays = 0;
                                  for (int x = 0; x < w; ++x) {
                                      const auto pixel = static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(w) +
                                                         static_cast<std::uint64_t>(x);
                                      const auto ux = static_cast<std::uint32_t>(x), uy = static_cast<std::uint32_t>(y);
                                      const auto sample = static_cast<std::uint64_t>(i);
                                      sample_stream rng(sampler, ux, uy, pixel, sample);
                                      sample_stream lrng(light_sampler, ux, uy, pixel, sample);
                                      const glm::vec3 d = cam.direction(x, y, rng.next2());
                                      rays += integ.trace(tracer, static_cast<std::uint32_t>(pixel), d, dist, alpha, rng,
                                                          lrng, ws, out);
                                      flush_if_full(out);
                                  }
                                  row_rays[static_cast<std::size_t>(y)] = rays;
                              }
                          });
                      });
                      for (const auto& list : splats) f.add_splats(list);
                      f.end_pass(static_cast<std::uint64_t>(i));
                      std::uint64_t rays = 0;
                      for (auto r : row_rays) rays += r;  // fixed reduction order
                      return rays;
                  });
}

}  // namespace iris::renderer::detail
