// render(): options checked, then one function chosen from the dispatch table (find_render)
// and run. The integrators themselves are compiled elsewhere (dispatch.hpp).
#include "iris/renderer/renderer.hpp"

#include <algorithm>
#include <variant>
#include <array>
#include <chrono>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "iris/sampling/presets.hpp"
#include "iris/version.hpp"
#include "iris/embree/intersector.hpp"
#include "cores.hpp"
#include "dispatch.hpp"
#include "windows.hpp"

namespace iris::renderer {
namespace {

static_assert(iris::presets::size == IRIS_PRESET_COUNT,
              "the preset list changed: set IRIS_PRESET_COUNT in modules/renderer/CMakeLists.txt to its length, "
              "so that every preset is instantiated");

/// \brief Is preset P's shape among the shared instantiations this build compiles?
template <class P>
constexpr bool core_compiled() noexcept {
    for (const auto& k : detail::compiled_cores)
        if (k.c == P::wavelength_count && k.bins == iris::detail::bins_of<P>() && k.propagates == P::bias_type::propagates)
            return true;
    return false;
}
static_assert([]<class... P>(type_list<P...>) { return (core_compiled<P>() && ...); }(iris::presets{}),
              "a preset's shape (C, B-term bins, propagates) is not compiled: add it to IRIS_RENDERER_CORES in "
              "modules/renderer/CMakeLists.txt");

using detail::isa;
using detail::render_fn;

/// \brief I's copy where this build has one, else the baseline loop.
constexpr isa compiled(isa i) noexcept { return IRIS_ISA_DISPATCH ? i : isa::baseline; }

/// \brief A preset's functions, indexed by instruction set.
template <class P>
constexpr std::array<render_fn, 2> functions_of() noexcept {
    using detail::render_preset;
    return {&render_preset<P, compiled(isa::baseline)>, &render_preset<P, compiled(isa::avx2)>};
}

/// \brief The dispatch table: every preset's functions, in preset-list order.
constexpr auto preset_table = []<class... P>(type_list<P...>) {
    return std::array<std::array<render_fn, 2>, sizeof...(P)>{functions_of<P>()...};
}(iris::presets{});

/// \brief Every preset's bidirectional path tracer (one loop, whatever the instruction set), in preset-list order.
constexpr auto bdpt_table = []<class... P>(type_list<P...>) {
    return std::array<render_fn, sizeof...(P)>{&detail::render_bdpt<P>...};
}(iris::presets{});

/// \brief Every preset's light tracer (one loop, whatever the instruction set), in preset-list order.
constexpr auto light_table = []<class... P>(type_list<P...>) {
    return std::array<render_fn, sizeof...(P)>{&detail::render_light<P>...};
}(iris::presets{});

constexpr std::array<render_fn, 2> bsdf_only_table{&detail::render_bsdf_only<compiled(isa::baseline)>,
                                                   &detail::render_bsdf_only<compiled(isa::avx2)>};

/// \brief The one place where a render's runtime choices become a compiled function.
/// \throws std::invalid_argument for an unknown preset.
render_fn find_render(const std::string& estimator, const std::string& preset, isa i) {
    const auto column = static_cast<std::size_t>(i);
    if (estimator == "bsdf-only") return bsdf_only_table[column];
    const std::size_t index = dispatch_preset(preset, []<class P>() { return preset_index<P>(); });
    if (estimator == "light") return light_table[index];
    if (estimator == "bdpt") return bdpt_table[index];
    return preset_table[index][column];
}

/// \brief The instruction sets' names, in `isa`'s order.
constexpr std::array<const char*, 2> isa_names{detail::isa_name(isa::baseline), detail::isa_name(isa::avx2)};

/// \brief The instruction set a render runs with: `requested` ("auto": the best this CPU and
/// build have), checked against this CPU.
/// \throws std::invalid_argument for an unknown or unsupported one.
isa choose_isa(const std::string& requested) {
    const auto available = instruction_sets();
    const std::string& name = requested == "auto" ? available.back() : requested;
    for (std::size_t i = 0; i < isa_names.size(); ++i) {
        if (name != isa_names[i]) continue;
        if (std::find(available.begin(), available.end(), name) == available.end())
            throw std::invalid_argument(fmt::format("instruction set '{}' is not supported by this CPU or build (available: auto, {})",
                                                    requested, fmt::join(available, ", ")));
        return static_cast<isa>(i);
    }
    if (requested == "avx512")
        throw std::invalid_argument("instruction set 'avx512' is no longer compiled: its copy of the hot loop was no faster "
                                    "than the AVX2 one in whole renders (docs/performance.md); use auto, baseline or avx2");
    throw std::invalid_argument(fmt::format("unknown instruction set '{}' (expected auto, baseline or avx2)", requested));
}

void validate(const options& o) {
    if (o.spp <= 0) throw std::invalid_argument(fmt::format("spp must be > 0, got {}", o.spp));
    if (o.nthold < 1) throw std::invalid_argument(fmt::format("nthold must be >= 1, got {}", o.nthold));
    if (o.threads < 0) throw std::invalid_argument(fmt::format("threads must be >= 0, got {}", o.threads));
    if (o.width < 0 || o.height < 0 || (o.width == 0) != (o.height == 0))
        throw std::invalid_argument(fmt::format("width and height must both be positive (or both 0 for the scene's), got {}x{}",
                                                o.width, o.height));
    if (o.path.max_depth < 1) throw std::invalid_argument("max depth must be >= 1");
    if (o.estimator != "nee-mis" && o.estimator != "bsdf-only" && o.estimator != "light" && o.estimator != "bdpt")
        throw std::invalid_argument(
            fmt::format("unknown estimator '{}' (expected nee-mis, bdpt, light or bsdf-only)", o.estimator));
    if (o.estimator != "bdpt" && (o.bdpt.only_s >= 0 || o.bdpt.only_t >= 0 || !o.bdpt.mis ||
                                  o.bdpt.keep != bdpt_settings::paths::all))
        throw std::invalid_argument(
            "bidirectional strategy settings (a single (s, t), unweighted, camera-only paths or the rest) need the bdpt estimator");
    if (!o.bdpt.mis && o.bdpt.keep != bdpt_settings::paths::all)
        throw std::invalid_argument(
            "camera-only paths are those no other strategy can make, which the weighted render decides: keeping them "
            "(or the rest) needs the MIS weights, not unweighted strategies");
    if (o.bdpt.only_t == 0) throw std::invalid_argument("strategy t = 0 does not exist (the pinhole cannot be hit): t >= 1");
    if (o.bdpt.only_s == 1 && o.bdpt.only_t == 1)
        throw std::invalid_argument("strategy (s, t) = (1, 1) is not used: a light seen directly is (0, 2)");
    if (!parse_sampler(o.sampler))
        throw std::invalid_argument(fmt::format("unknown sampler '{}' (expected independent, sobol or zsobol)", o.sampler));
    if (o.start_spp < 0 || o.start_spp > o.spp)
        throw std::invalid_argument(fmt::format("start spp must be in 0..spp ({}), got {}", o.spp, o.start_spp));
    if (o.planned_spp < 0 || (o.planned_spp > 0 && o.planned_spp < o.spp))
        throw std::invalid_argument(fmt::format("planned spp must be 0 (spp) or at least spp ({}), got {}: the sampler's "
                                                "sequence is laid out for it", o.spp, o.planned_spp));
    if (o.spectral_bins < 0 || o.spectral_bins > max_spectral_bins)
        throw std::invalid_argument(fmt::format("spectral bins must be 0 (no spectral output) or 1..{}, got {}",
                                                max_spectral_bins, o.spectral_bins));
    if (o.spectral_bins > 0 && (o.estimator == "bdpt" || o.estimator == "light"))
        throw std::invalid_argument(fmt::format("spectral output is written by the nee-mis and bsdf-only estimators; the {} "
                                                "estimator splats onto other pixels, which the spectral film does not take",
                                                o.estimator));
    if (o.ranks < 1 || o.rank < 0 || o.rank >= o.ranks)
        throw std::invalid_argument(fmt::format("rank {} of {} ranks is not in 0..ranks-1", o.rank, o.ranks));
}

}  // namespace

struct prepared_scene::parts {
    explicit parts(std::shared_ptr<const scene_desc> s) : scene(std::move(s)), tracer(*scene), lights(*scene) {}
    std::shared_ptr<const scene_desc> scene;
    embree::intersector tracer;
    light_sampler lights;
    double seconds = 0.0;  ///< building tracer and lights
};

prepared_scene::prepared_scene(std::shared_ptr<const scene_desc> scene) {
    const auto start = std::chrono::steady_clock::now();
    auto p = std::make_shared<parts>(std::move(scene));
    p->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    m_parts = std::move(p);
}
prepared_scene::prepared_scene(scene_desc scene) : prepared_scene(std::make_shared<const scene_desc>(std::move(scene))) {}
prepared_scene prepared_scene::borrow(const scene_desc& scene) {
    return prepared_scene(std::shared_ptr<const scene_desc>(std::shared_ptr<const scene_desc>(), &scene));  // aliasing, no owner
}
const scene_desc& prepared_scene::desc() const noexcept { return *m_parts->scene; }
double prepared_scene::build_seconds() const noexcept { return m_parts->seconds; }

void check(const options& opt) {
    validate(opt);
    config_name(opt.preset);
    choose_isa(opt.isa);
}

std::map<std::string, std::string> image_metadata(const std::string& scene_name, const options& opt, const status& st) {
    std::map<std::string, std::string> m{{"iris:scene", scene_name},
                                         {"iris:preset", opt.preset},
                                         {"iris:config", st.config_name},
                                         {"iris:estimator", st.estimator},
                                         {"iris:sampler", st.sampler},
                                         {"iris:spp", std::to_string(st.spp_done)},
                                         {"iris:seed", std::to_string(opt.seed)},
                                         {"iris:nthold", std::to_string(opt.nthold)},
                                         {"iris:nan_inf", std::to_string(st.nan_inf)},
                                         {"iris:version", std::string(iris::version)}};
    if (!st.windows.empty()) m["iris:windows"] = st.windows;
    if (opt.spectral_bins > 0) m["iris:spectral_bins"] = std::to_string(opt.spectral_bins);  // centre:width (nm) of each restriction window
    return m;
}

status render(const scene_desc& scene, const options& opt, film& out, const hooks& h) {
    check(opt);  // before the ray tracer is built
    return render(prepared_scene::borrow(scene), opt, out, h);
}

status render(const prepared_scene& prepared, const options& opt, film& out, const hooks& h) {
    const scene_desc& scene = prepared.desc();
    validate(opt);
    const std::string config = config_name(opt.preset);  // throws for an unknown preset
    const isa chosen = choose_isa(opt.isa);
    const int w = opt.width > 0 ? opt.width : scene.camera.width;
    const int ht = opt.height > 0 ? opt.height : scene.camera.height;
    if (w <= 0 || ht <= 0) throw std::invalid_argument(fmt::format("image size must be positive, got {}x{}", w, ht));
    if (opt.estimator == "light" || opt.estimator == "bdpt") {
        const bool absorbs = std::any_of(scene.materials.begin(), scene.materials.end(), [](const material_desc& m) {
            const auto* d = std::get_if<material::dielectric>(&m);
            return d && d->absorption;
        });
        const bool scatters = std::any_of(scene.materials.begin(), scene.materials.end(), [](const material_desc& m) {
            const auto* d = std::get_if<material::dielectric>(&m);
            return d && d->scattering;
        });
        if (scatters || scene.medium)
            throw std::invalid_argument(fmt::format("the {} estimator does not render participating media yet; use nee-mis "
                                                    "(or bsdf-only) for a scene with 'scattering' or a scene 'medium'",
                                                    opt.estimator));
        if (absorbs)
            throw std::invalid_argument(fmt::format("the {} estimator does not render absorbing dielectrics yet; use nee-mis "
                                                    "(or bsdf-only) for a scene with an 'absorption'",
                                                    opt.estimator));
    }
    if (opt.start_spp > 0 && (out.width() != w || out.height() != ht))
        throw std::invalid_argument(fmt::format("the film to resume is {}x{}, the render {}x{}", out.width(), out.height(), w, ht));
    const spectral_bands bands{opt.spectral_bins, scene.lambda_min, scene.lambda_max};
    const bool fades = opt.estimator != "bsdf-only" &&
                       dispatch_preset(opt.preset, []<class P>() { return P::accumulation_type::fades; });
    if (opt.start_spp > 0) {
        // the film to go on from: a fading preset's has (or, still empty — another rank's
        // share of a resumed render — gets) a fade layer split at N_thold; another's has none
        bool empty = true;
        for (std::size_t i = 0; i < out.sums().size(); ++i) empty = empty && out.samples(i) == 0;
        if (fades && !out.fades() && empty) out.enable_fade(static_cast<std::uint32_t>(opt.nthold));
        if (fades != out.fades())
            throw std::invalid_argument(fmt::format("preset '{}' {} a fade layer, the film to resume {}", opt.preset,
                                                    fades ? "needs" : "has no use for", out.fades() ? "has one" : "has none"));
        if (fades && out.fade_state()->split != static_cast<std::uint32_t>(opt.nthold))
            throw std::invalid_argument(fmt::format("the film to resume fades at sample {}, the render's nthold is {}",
                                                    out.fade_state()->split, opt.nthold));
        if (opt.spectral_bins > 0 && !out.spectral_state() && empty) out.enable_spectral(bands);
        const int has = out.spectral_state() ? out.spectral_state()->bands.count : 0;
        if (has != opt.spectral_bins || (has > 0 && !(out.spectral_state()->bands == bands)))
            throw std::invalid_argument(fmt::format("the film to resume has {} spectral bands, the render asks for {}{}", has,
                                                    opt.spectral_bins, has == opt.spectral_bins ? " over another range" : ""));
    }
    if (opt.start_spp == 0) try {
        out = film(w, ht);
        if (fades) out.enable_fade(static_cast<std::uint32_t>(opt.nthold));
        if (opt.spectral_bins > 0) out.enable_spectral(bands);
    } catch (const std::bad_alloc&) {
        const std::size_t per_pixel = film::bytes_per_pixel + (fades ? film::fade_bytes_per_pixel : 0) +
                                      film::spectral_bytes_per_band * static_cast<std::size_t>(opt.spectral_bins);
        const double bytes = static_cast<double>(w) * static_cast<double>(ht) * static_cast<double>(per_pixel);
        throw std::runtime_error(fmt::format("not enough memory for a {}x{} film ({:.2f} GiB at {} bytes per pixel)", w, ht,
                                             bytes / (1024.0 * 1024.0 * 1024.0), per_pixel));
    }
    status st;
    st.config_name = opt.estimator == "bsdf-only" ? std::string("bsdf-only") : config;
    st.estimator = opt.estimator;
    st.width = w;
    st.height = ht;
    st.spp_total = opt.spp;
    st.spp_done = opt.start_spp;
    st.isa = isa_names[static_cast<std::size_t>(opt.estimator == "light" || opt.estimator == "bdpt" ? isa::baseline : chosen)];  // the loop run (set again by a preset without a copy)
    st.sampler = opt.sampler;
    const render_fn fn = find_render(opt.estimator, opt.preset, chosen);
    fn(detail::render_job{scene, prepared.get().tracer, prepared.get().lights, opt, out, st, h});
    return st;
}

std::vector<std::string> instruction_sets() {
    std::vector<std::string> v{"baseline"};
#if IRIS_ISA_DISPATCH
    __builtin_cpu_init();
    if (__builtin_cpu_supports("x86-64-v3")) v.emplace_back("avx2");
#endif
    return v;
}

std::vector<preset_info> presets() {
    std::vector<preset_info> v;
    for_each_preset([&]<class P>() {
        constexpr bool unrestricted = std::is_same_v<typename P::kernel_type, restriction::unrestricted>;
        v.push_back({std::string(P::cli_name), std::string(P::name), P::wavelength_count,
                     unrestricted || P::bias_type::propagates, P::accumulation_type::fades,
                     IRIS_ISA_DISPATCH && detail::has_isa_copy<P>});
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

std::string windows(const scene_desc& scene, const std::string& preset) {
    return dispatch_preset(preset, [&]<class P>() {
        typename P::parameters params;
        params.domain = {scene.lambda_min, scene.lambda_max};
        return detail::resolve_windows<P>(params, scene);
    });
}

}  // namespace iris::renderer
