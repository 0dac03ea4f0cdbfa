// The preset × feature dispatch: every preset of the type list is instantiated here,
// once with and once without the dispersive path-pdf bookkeeping.
#include "iris/renderer/renderer.hpp"

#include <new>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "iris/render/bsdf_only.hpp"
#include "iris/render/camera.hpp"
#include "iris/render/lights.hpp"
#include "iris/sampling/presets.hpp"
#include "iris/renderer/embree_tracer.hpp"
#include "render_loop.hpp"

namespace iris::renderer {
namespace {

template <class Preset, bool Dispersive>
void run(const scene_desc& scene, const embree_tracer& tracer, const options& opt, film& f, status& st,
         const hooks& h) {
    typename Preset::parameters params;
    params.n_thold = static_cast<std::uint32_t>(opt.nthold);
    params.domain = {scene.lambda_min, scene.lambda_max};
    const Preset cfg(params);
    const light_sampler lights(scene);
    const path_integrator<Preset, Dispersive> integ(scene, lights, opt.path);
    const camera_rays cam(scene.camera, f.width(), f.height());
    // α changes every pass until N_thold and then stays 1: build p_α only when it changes
    float built_alpha = -1.0f;
    std::optional<typename Preset::distribution_type> dist;
    detail::run_passes(integ, tracer, cam, opt,
                       [&](int i) {
                           const float a = cfg.alpha(static_cast<std::uint64_t>(i));
                           if (a != built_alpha) {
                               dist.emplace(cfg.distribution(a));
                               built_alpha = a;
                           }
                           return std::pair<float, const typename Preset::distribution_type&>(a, *dist);
                       },
                       f, st, h);
}

/// \brief The independent estimator: one instantiation, no wavelength policy (its loop's
/// distribution is an empty placeholder).
void run_bsdf_only(const scene_desc& scene, const embree_tracer& tracer, const options& opt, film& f, status& st,
                   const hooks& h) {
    struct no_distribution {};
    static constexpr no_distribution none{};
    const bsdf_only_integrator integ(scene, opt.path);
    const camera_rays cam(scene.camera, f.width(), f.height());
    detail::run_passes(integ, tracer, cam, opt,
                       [&](int) { return std::pair<float, const no_distribution&>(1.0f, none); }, f, st, h);
}

/// \brief The instruction set a render runs with: `requested`, checked against this CPU.
std::string choose_isa(const std::string& requested) {
    const auto available = instruction_sets();
    if (requested == "auto") return available.back();
    for (const auto& a : available)
        if (a == requested) return a;
    for (const char* known : {"baseline", "avx2", "avx512"})
        if (requested == known)
            throw std::invalid_argument(fmt::format("instruction set '{}' is not supported by this CPU or build (available: auto, {})",
                                                    requested, fmt::join(available, ", ")));
    throw std::invalid_argument(fmt::format("unknown instruction set '{}' (expected auto, baseline, avx2 or avx512)", requested));
}

void validate(const options& o) {
    if (o.spp <= 0) throw std::invalid_argument(fmt::format("spp must be > 0, got {}", o.spp));
    if (o.nthold < 1) throw std::invalid_argument(fmt::format("nthold must be >= 1, got {}", o.nthold));
    if (o.threads < 0) throw std::invalid_argument(fmt::format("threads must be >= 0, got {}", o.threads));
    if (o.width < 0 || o.height < 0 || (o.width == 0) != (o.height == 0))
        throw std::invalid_argument(fmt::format("width and height must both be positive (or both 0 for the scene's), got {}x{}",
                                                o.width, o.height));
    if (o.path.max_depth < 1) throw std::invalid_argument("max depth must be >= 1");
    if (o.estimator != "nee-mis" && o.estimator != "bsdf-only")
        throw std::invalid_argument(fmt::format("unknown estimator '{}' (expected nee-mis or bsdf-only)", o.estimator));
}

}  // namespace

status render(const scene_desc& scene, const options& opt, film& out, const hooks& h) {
    validate(opt);
    const std::string config = config_name(opt.preset);  // throws for an unknown preset
    const std::string isa = choose_isa(opt.isa);          // throws for an unknown or unsupported one
    const int w = opt.width > 0 ? opt.width : scene.camera.width;
    const int ht = opt.height > 0 ? opt.height : scene.camera.height;
    if (w <= 0 || ht <= 0) throw std::invalid_argument(fmt::format("image size must be positive, got {}x{}", w, ht));
    const embree_tracer tracer(scene);
    try {
        out = film(w, ht);
    } catch (const std::bad_alloc&) {
        const double bytes = static_cast<double>(w) * static_cast<double>(ht) * static_cast<double>(film::bytes_per_pixel);
        throw std::runtime_error(fmt::format("not enough memory for a {}x{} film ({:.2f} GiB at {} bytes per pixel)", w, ht,
                                             bytes / (1024.0 * 1024.0 * 1024.0), film::bytes_per_pixel));
    }
    status st;
    st.config_name = opt.estimator == "bsdf-only" ? std::string("bsdf-only") : config;
    st.estimator = opt.estimator;
    st.width = w;
    st.height = ht;
    st.spp_total = opt.spp;
    st.dispersive_instantiation = opt.force_dispersive || scene.features().dispersive();
    st.isa = isa;
    if (opt.estimator == "bsdf-only") {
        st.dispersive_instantiation = false;  // one wavelength: nothing to track
        run_bsdf_only(scene, tracer, opt, out, st, h);
        return st;
    }
    dispatch_preset(opt.preset, [&]<class Preset>() {
        if (st.dispersive_instantiation) run<Preset, true>(scene, tracer, opt, out, st, h);
        else run<Preset, false>(scene, tracer, opt, out, st, h);
    });
    return st;
}

std::vector<std::string> instruction_sets() {
    std::vector<std::string> v{"baseline"};
#if IRIS_ISA_DISPATCH
    __builtin_cpu_init();
    if (__builtin_cpu_supports("x86-64-v3")) v.emplace_back("avx2");
    if (__builtin_cpu_supports("x86-64-v4")) v.emplace_back("avx512");
#endif
    return v;
}

std::vector<preset_info> presets() {
    std::vector<preset_info> v;
    for_each_preset([&]<class P>() {
        constexpr bool unrestricted = std::is_same_v<typename P::kernel_type, restriction::unrestricted>;
        v.push_back({std::string(P::cli_name), std::string(P::name), P::wavelength_count,
                     unrestricted || P::bias_type::propagates});
    });
    return v;
}

std::vector<std::string> preset_names() {
    std::vector<std::string> v;
    for (const auto& p : presets()) v.push_back(p.name);
    return v;
}

std::string config_name(const std::string& preset) {
    return dispatch_preset(preset, [&]<class P>() { return std::string(P::name); });
}

}  // namespace iris::renderer
