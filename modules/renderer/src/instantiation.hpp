#pragma once
// The definitions of the functions dispatch.hpp declares (internal to iris::renderer):
// included by the translation units that instantiate them (presets.cpp.in, bsdf_only.cpp).
#include <cstdint>
#include <optional>
#include <utility>

#include "iris/render/bsdf_only.hpp"
#include "iris/render/camera.hpp"
#include "iris/render/integrator.hpp"
#include "iris/render/lights.hpp"
#include "iris/sampling/presets.hpp"
#include "dispatch.hpp"
#include "render_loop.hpp"
#include "windows.hpp"

namespace iris::renderer::detail {

template <class Preset, isa I>
void render_preset(const render_job& job) {
    typename Preset::parameters params;
    params.n_thold = static_cast<std::uint32_t>(job.opt.nthold);
    params.domain = {job.scene.lambda_min, job.scene.lambda_max};
    job.st.windows = resolve_windows<Preset>(params, job.scene);
    const Preset cfg(params);
    const light_sampler lights(job.scene);
    const path_integrator<Preset> integ(job.scene, lights, job.opt.path);
    const camera_rays cam(job.scene.camera, job.out.width(), job.out.height());
    // α changes every pass until N_thold and then stays 1: build p_α only when it changes
    float built_alpha = -1.0f;
    std::optional<typename Preset::distribution_type> dist;
    run_passes<I>(integ, job.tracer, cam, job.opt,
                  [&](int i) {
                      const float a = cfg.alpha(static_cast<std::uint64_t>(i));
                      if (a != built_alpha) {
                          dist.emplace(cfg.distribution(a));
                          built_alpha = a;
                      }
                      return std::pair<float, const typename Preset::distribution_type&>(a, *dist);
                  },
                  job.out, job.st, job.h);
}

/// The independent estimator: no wavelength policy (its loop's distribution is an empty
/// placeholder).
template <isa I>
void render_bsdf_only(const render_job& job) {
    struct no_distribution {};
    static constexpr no_distribution none{};
    const bsdf_only_integrator integ(job.scene, job.opt.path);
    const camera_rays cam(job.scene.camera, job.out.width(), job.out.height());
    run_passes<I>(integ, job.tracer, cam, job.opt,
                  [&](int) { return std::pair<float, const no_distribution&>(1.0f, none); }, job.out, job.st, job.h);
}

}  // namespace iris::renderer::detail
