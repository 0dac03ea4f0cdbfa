#pragma once
// The progressive loop shared by every instantiation (internal to iris::renderer).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "iris/render/camera.hpp"
#include "iris/render/film.hpp"
#include "iris/render/random.hpp"
#include "iris/renderer/renderer.hpp"

namespace iris::renderer::detail {

/// \brief Run `opt.spp` passes. `make_distribution(i)` returns {α_i, distribution} for
/// sample index i (built once per pass, shared read-only by all threads).
template <class Integrator, class Tracer, class DistributionFor>
void run_passes(const Integrator& integ, const Tracer& tracer, const camera_rays& cam, const options& opt,
                DistributionFor&& distribution_for, film& f, status& st, const hooks& h) {
    const int w = f.width(), ht = f.height();
    const int ts = std::max(1, opt.tile_size);
    const int tiles_x = (w + ts - 1) / ts, tiles_y = (ht + ts - 1) / ts;
    const int tiles = tiles_x * tiles_y;
    std::vector<std::uint64_t> tile_rays(static_cast<std::size_t>(tiles));
    tbb::task_arena arena(opt.threads > 0 ? opt.threads : tbb::info::default_concurrency());
    st.threads = arena.max_concurrency();

    for (int i = 0; i < opt.spp; ++i) {
        if (h.cancel && h.cancel->load()) {
            st.interrupted = true;
            break;
        }
        const auto pass_start = std::chrono::steady_clock::now();  // time passes, not the hooks
        const auto [alpha, dist] = distribution_for(i);
        const std::uint64_t before = f.dropped();
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<int>(0, tiles), [&](const tbb::blocked_range<int>& r) {
                for (int t = r.begin(); t != r.end(); ++t) {
                    const int x0 = (t % tiles_x) * ts, y0 = (t / tiles_x) * ts;
                    std::uint64_t rays = 0;
                    for (int y = y0; y < std::min(y0 + ts, ht); ++y)
                        for (int x = x0; x < std::min(x0 + ts, w); ++x) {
                            const auto pixel = static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(w) +
                                               static_cast<std::uint64_t>(x);
                            sample_stream rng(opt.seed, pixel, static_cast<std::uint64_t>(i));
                            const glm::vec3 d = cam.direction(x, y, rng.next2());
                            const path_sample s = integ.trace(tracer, cam.origin(), d, dist, alpha, rng);
                            f.add(static_cast<std::size_t>(pixel), s.value);
                            rays += s.rays;
                        }
                    tile_rays[static_cast<std::size_t>(t)] = rays;
                }
            });
        });
        for (auto r : tile_rays) st.rays += r;  // fixed reduction order
        st.spp_done = i + 1;
        st.samples += static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(ht);
        st.nan_inf += f.dropped() - before;
        st.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - pass_start).count();
        if (h.on_pass && !h.on_pass(f, st)) break;
    }
}

}  // namespace iris::renderer::detail
