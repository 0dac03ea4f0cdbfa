#pragma once
// The definitions of the functions dispatch.hpp declares (internal to iris::renderer):
// included by the translation units that instantiate them (presets.cpp.in, bsdf_only.cpp).
#include <cstdint>
#include <optional>
#include <utility>

#include "iris/render/bdpt.hpp"
#include "iris/render/bsdf_only.hpp"
#include "iris/render/camera.hpp"
#include "iris/render/integrator.hpp"
#include "iris/render/light_tracer.hpp"
#include "iris/render/lights.hpp"
#include "iris/sampling/presets.hpp"
#include "dispatch.hpp"
#include "light_loop.hpp"
#include "render_loop.hpp"
#include "windows.hpp"

namespace iris::renderer::detail {

/// \brief A preset's configuration for one render, and p_α for pass i — rebuilt only when α
/// changes (every pass until N_thold, then never).
template <class Preset>
class preset_passes {
public:
    explicit preset_passes(const render_job& job) : m_cfg(parameters(job)) {}
    std::pair<float, const typename Preset::distribution_type&> operator()(int i) {
        const float a = m_cfg.alpha(static_cast<std::uint64_t>(i));
        if (a != m_alpha) {
            m_dist.emplace(m_cfg.distribution(a));
            m_alpha = a;
        }
        return {a, *m_dist};
    }

private:
    /// The preset's parameters for this render, its windows resolved for the scene
    /// (and reported in the status).
    static typename Preset::parameters parameters(const render_job& job) {
        typename Preset::parameters params;
        params.n_thold = static_cast<std::uint32_t>(job.opt.nthold);
        params.domain = {job.scene.lambda_min, job.scene.lambda_max};
        job.st.windows = resolve_windows<Preset>(params, job.scene);
        return params;
    }
    const Preset m_cfg;
    float m_alpha = -1.0f;
    std::optional<typename Preset::distribution_type> m_dist;
};

template <class Preset, isa I>
void render_preset(const render_job& job) {
    if constexpr (I != isa::baseline && !has_isa_copy<Preset>) {
        job.st.isa = isa_name(isa::baseline);  // no copy of this preset's loop (dispatch.hpp)
        render_preset<Preset, isa::baseline>(job);
        return;
    } else {
    preset_passes<Preset> passes(job);
    const light_sampler& lights = job.lights;
    const path_integrator<Preset> integ(job.scene, lights, job.opt.path);
    const camera_rays cam(job.scene.camera, job.out.width(), job.out.height());
    run_passes<I>(integ, job.tracer, cam, job.opt, passes, job.out, job.st, job.h);
    }
}

template <class Preset>
void render_light(const render_job& job) {
    preset_passes<Preset> passes(job);
    const light_sampler& lights = job.lights;
    const camera_rays cam(job.scene.camera, job.out.width(), job.out.height());
    const light_integrator<Preset> integ(job.scene, lights, cam, job.opt.path);
    run_light_passes(integ, job.tracer, job.opt, passes, job.out, job.st, job.h);
}

template <class Preset>
void render_bdpt(const render_job& job) {
    preset_passes<Preset> passes(job);
    const light_sampler& lights = job.lights;
    const camera_rays cam(job.scene.camera, job.out.width(), job.out.height());
    const bdpt_integrator<Preset> integ(job.scene, lights, cam, job.opt.path, job.opt.bdpt);
    run_bdpt_passes(integ, job.tracer, cam, job.opt, passes, job.out, job.st, job.h);
}

/// The independent estimator: no wavelength policy (its loop's distribution is an empty
/// placeholder).
template <isa I>
void render_bsdf_only(const render_job& job) {
    job.st.isa = isa_name(isa::baseline);  // one loop: the check need not be fast
    struct no_distribution {};
    static constexpr no_distribution none{};
    const bsdf_only_integrator integ(job.scene, job.opt.path);
    const camera_rays cam(job.scene.camera, job.out.width(), job.out.height());
    run_passes<isa::baseline>(integ, job.tracer, cam, job.opt,
                              [&](int) { return std::pair<float, const no_distribution&>(1.0f, none); }, job.out, job.st,
                              job.h);
}

}  // namespace iris::renderer::detail
