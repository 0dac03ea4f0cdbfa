#pragma once
// The definitions of the shared instantiations dispatch.hpp declares (internal to
// iris::renderer): each estimator for one `core_config<C, Bins, Propagates>`, reading the
// preset's wavelength policy through `pass_source` and `sample_policy`
// (iris/render/sample_policy.hpp). Included by the units core.cpp.in generates and by
// bsdf_only.cpp.
#include <cstddef>
#include <utility>

#include "iris/render/bdpt.hpp"
#include "iris/render/bsdf_only.hpp"
#include "iris/render/camera.hpp"
#include "iris/render/integrator.hpp"
#include "iris/render/light_tracer.hpp"
#include "iris/render/lights.hpp"
#include "iris/render/sample_policy.hpp"
#include "dispatch.hpp"
#include "light_loop.hpp"
#include "render_loop.hpp"

namespace iris::renderer::detail {

template <isa I, std::size_t C, std::size_t Bins, bool Propagates>
void render_path_core(const render_job& job, pass_source<C, Bins>& passes) {
    const path_integrator<core_config<C, Bins, Propagates>> integ(job.scene, job.lights, job.opt.path);
    const camera_rays cam(job.scene.camera, job.out.width(), job.out.height());
    run_passes<I>(integ, job.tracer, cam, job.opt, [&](int i) { return passes(i); }, job.out, job.st, job.h);
}

template <std::size_t C, std::size_t Bins, bool Propagates>
void render_light_core(const render_job& job, pass_source<C, Bins>& passes) {
    const camera_rays cam(job.scene.camera, job.out.width(), job.out.height());
    const light_integrator<core_config<C, Bins, Propagates>> integ(job.scene, job.lights, cam, job.opt.path);
    run_light_passes(integ, job.tracer, job.opt, [&](int i) { return passes(i); }, job.out, job.st, job.h);
}

template <std::size_t C, std::size_t Bins, bool Propagates>
void render_bdpt_core(const render_job& job, pass_source<C, Bins>& passes) {
    const camera_rays cam(job.scene.camera, job.out.width(), job.out.height());
    const bdpt_integrator<core_config<C, Bins, Propagates>> integ(job.scene, job.lights, cam, job.opt.path,
                                                                 job.opt.bdpt);
    run_bdpt_passes(integ, job.tracer, cam, job.opt, [&](int i) { return passes(i); }, job.out, job.st, job.h);
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
