#pragma once
/// \file
/// \brief iris::renderer — progressive rendering of a scene with a named preset: one
/// pass = one sample per pixel, tiles in parallel over TBB, identical pixels for a given
/// seed whatever the thread count (per-pixel, per-sample random streams; each pixel's
/// samples are accumulated in sample order by whichever thread owns its tile).
///
/// The preset name and the instruction set are mapped once, here, onto one compile-time
/// instantiation `path_integrator<Config>` with its hot loop compiled for that instruction
/// set; nothing below branches on the policy at run time.

#include <array>
#include <atomic>
#include <cstdio>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "iris/render/film.hpp"
#include "iris/render/integrator.hpp"
#include "iris/render/scene.hpp"

namespace iris::renderer {

struct options {
    std::string preset = "hwss";
    int spp = 16;
    int threads = 0;  ///< 0: every hardware thread
    std::uint64_t seed = 1;
    int nthold = 512;  ///< relaxation length N_thold (samples per pixel)
    int width = 0;     ///< 0: the scene camera's resolution
    int height = 0;
    path_settings path{};
    int tile_size = 16;
    /// \brief Instruction set of the integrator's hot loop: "auto" (the widest this CPU
    /// runs), or one of `instruction_sets()` ("baseline", "avx2"). Every choice gives
    /// bit-identical images; only the speed differs (docs/performance.md). Only the presets
    /// with `preset_info::isa_copy` have an AVX2 loop; the others, the light tracer and the
    /// BSDF-only estimator run their baseline loop (`status::isa` says which ran).
    std::string isa = "auto";
    /// \brief "nee-mis" (the preset's `path_integrator`: next-event estimation, MIS),
    /// "bdpt" (the preset's `bdpt_integrator`, iris/render/bdpt.hpp: bidirectional path
    /// tracing, every (s, t) strategy weighted over strategies × wavelengths; t = 1 splatted;
    /// baseline loop only),
    /// "light" (the preset's `light_integrator`, iris/render/light_tracer.hpp: light tracing,
    /// one light subpath per pixel per pass splatted onto the film; baseline loop only, so
    /// `isa` does not apply) or "bsdf-only" (`bsdf_only_integrator`,
    /// iris/render/bsdf_only.hpp: pure BSDF sampling at one uniform wavelength, the
    /// independent check; the preset is then not used).
    std::string estimator = "nee-mis";
    /// \brief Bidirectional strategies kept and their weighting (bdpt only): one (s, t)
    /// alone, or each unweighted over strategies — the pieces docs/method.md §3 sums.
    bdpt_settings bdpt{};
    /// \brief Where a pixel's random numbers come from: "sobol" (the default: SSIM at 16 spp
    /// +22–29 % over independent sampling on the paper's scenes, as good as "zsobol" and
    /// cheaper; docs/results.md#samplers), "zsobol" or "independent" (iris/render/random.hpp:
    /// the samplers and their dimension layout).
    std::string sampler = "sobol";
    /// \brief Resume: the film passed to `render` already holds the samples of passes
    /// [0, start_spp) (a checkpoint's film, iris/renderer/checkpoint.hpp); the render adds
    /// passes [start_spp, spp) to it. 0: a new film. Every pixel's sums are exact
    /// (film.hpp), so the result is the same film an uninterrupted render gives.
    int start_spp = 0;
    /// \brief The sample count the sampler's sequence is laid out for: 0 means `spp`. Only
    /// `zsobol` depends on it (its Morton scale, ⌈log₂⌉ of it); a caller that adds passes
    /// a few at a time without knowing the last (the Python `Renderer.step`) sets it once,
    /// and a zsobol image then equals the one-call render with `spp` = planned_spp.
    int planned_spp = 0;
    /// \brief Share the passes between `ranks` processes (MPI): this one renders the passes
    /// i with i mod ranks = rank, one per round of `ranks` passes, into its own film; the
    /// films' exact sum (film::merge) is the single-process film. The hooks' `on_pass`
    /// runs after every round on every rank, even a rank without a pass in the last one.
    int rank = 0;
    int ranks = 1;
    /// \brief Spectral output: 0 (none), or the film's spectral layer with this many equal
    /// bands over the scene's spectral domain (film.hpp, iris/render/spectral_bands.hpp;
    /// 1..max_spectral_bins). The nee-mis and bsdf-only estimators only: bdpt and light
    /// splat onto other pixels, which a spectral layer does not take. Costs
    /// film::spectral_bytes_per_band (16) bytes per band per pixel; the XYZ film is the same
    /// bit for bit with or without it.
    int spectral_bins = 0;
};

/// \brief The most bands `options::spectral_bins` accepts (0.4 nm on 380–780 nm).
inline constexpr int max_spectral_bins = 1000;

/// \brief Where a render is: passed to the hooks and returned at the end.
struct status {
    std::string config_name;       ///< e.g. "multibox3/linear/C4/propagate"; "bsdf-only" for that estimator
    std::string estimator;         ///< "nee-mis", "bdpt", "light" or "bsdf-only"
    std::string isa;               ///< instruction set the hot loop ran with
    std::string sampler;           ///< "independent", "sobol" or "zsobol"
    int width = 0, height = 0;
    int threads = 0;               ///< worker threads the render may use (its arena's size)
    int threads_used = 0;          ///< of those, how many rendered at least one tile
    float alpha = 1.0f;            ///< α of the last pass this rank rendered (sample index spp_done − 1 for one rank)
    int spp_done = 0;              ///< complete passes over all ranks (every pixel has this many samples
                                   ///< once the ranks' films are merged), counting a resumed film's
    int spp_total = 0;
    double seconds = 0.0;          ///< wall-clock time spent in passes (by this call)
    std::uint64_t samples = 0;     ///< taken by this call (this rank; not a resumed film's)
    std::uint64_t rays = 0;        ///< traced by this call (this rank)
    std::uint64_t nan_inf = 0;     ///< samples this call dropped from the film (non-finite, out of range)
    bool interrupted = false;
    /// \brief The restriction windows the render used, "centre:width" in nm, comma-separated
    /// ("464:20,549:20,611:20" for `paper`; placed from the scene's emitters for the `-auto`
    /// presets, iris/sampling/placement.hpp); empty for kernels without windows.
    std::string windows;
};

/// \brief A scene made ready to render: its ray tracer (Embree's BVH) and light sampler
/// built once, then shared read-only by every render on it — in sequence (a progressive
/// caller, a parameter sweep) or at once from several threads. Cheap to copy (shared
/// ownership); the render on a `scene_desc` builds one for the call.
class prepared_scene {
public:
    /// \throws std::runtime_error if the ray tracer cannot be built.
    explicit prepared_scene(scene_desc scene);
    const scene_desc& desc() const noexcept;
    /// \brief The seconds spent building the ray tracer and the light sampler.
    double build_seconds() const noexcept;
    struct parts;  ///< (defined in renderer.cpp)
    const parts& get() const noexcept { return *m_parts; }
    /// \brief One over a scene it does not own (no copy): `scene` must outlive it and every copy.
    static prepared_scene borrow(const scene_desc& scene);

private:
    explicit prepared_scene(std::shared_ptr<const scene_desc> scene);
    std::shared_ptr<const parts> m_parts;
};

/// \brief "464:20,549:20,611:20": windows as `status::windows` writes them.
template <std::size_t N>
std::string format_windows(const std::array<float, N>& centres_nm, const std::array<float, N>& widths_nm) {
    std::string s;
    for (std::size_t k = 0; k < N; ++k) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%s%g:%g", k ? "," : "", static_cast<double>(centres_nm[k]),
                      static_cast<double>(widths_nm[k]));
        s += buf;
    }
    return s;
}

/// \brief The windows `render` would use for `scene` with `preset` (status::windows), without
/// rendering. \throws std::invalid_argument for an unknown preset.
std::string windows(const scene_desc& scene, const std::string& preset);

struct hooks {
    /// \brief Once, after the setup (scene, ray tracer, threads) and before the first pass,
    /// on the thread that called render; not timed. Return false to render no pass. (For
    /// callers that schedule several renders, e.g. iris-compare's lockstep.)
    std::function<bool(const status&)> on_start;
    /// \brief After every complete pass (with ranks > 1: after every round, on every rank).
    /// Return false to stop after this pass.
    std::function<bool(const film&, const status&)> on_pass;
    /// \brief Checked between passes; a set flag stops the render after the current pass.
    const std::atomic<bool>* cancel = nullptr;
    /// \brief Before every chunk of tiles a thread takes, with that thread's arena slot (0 is
    /// the thread that called render). For tests that must see tiles spread over threads;
    /// it runs on the rendering threads, so it must be thread-safe.
    std::function<void(int slot)> on_tile;
};

/// \brief Render `scene` progressively into a new film (`opt.start_spp` = 0) or on into
/// `out` (resume). \throws std::invalid_argument for an unknown preset or bad options
/// (spp ≤ 0, nthold < 1, size ≤ 0, a resumed film of another size, rank ∉ [0, ranks)),
/// with a message that lists what is accepted; std::runtime_error if the ray tracer cannot
/// be built.
status render(const scene_desc& scene, const options& opt, film& out, const hooks& h = {});

/// \brief The same on a prepared scene: no ray tracer or light sampler is built, so many
/// short renders (a pass at a time, a sweep over presets or seeds) pay for them once.
/// The result is the same film, bit for bit. Thread-safe for distinct films.
status render(const prepared_scene& scene, const options& opt, film& out, const hooks& h = {});

/// \brief The checks `render` makes on `opt` before it starts (preset, estimator, sampler,
/// instruction set, sizes, counts), without rendering. \throws std::invalid_argument
/// with the message `render` would give.
void check(const options& opt);

/// \brief The string attributes an image of this render carries (`iris:scene`, `iris:preset`,
/// `iris:spp`, …; docs/architecture.md): a pure function of the render's key and of the
/// passes done — no time or machine — so a resumed or distributed render writes the same bytes.
std::map<std::string, std::string> image_metadata(const std::string& scene_name, const options& opt, const status& st);

/// \brief The instruction sets of the hot loop this build and CPU can run, narrowest
/// first ("baseline" always; "avx2" = x86-64-v3 on x86-64 with GCC).
std::vector<std::string> instruction_sets();

/// \brief What the renderer knows about a preset.
struct preset_info {
    std::string name;    ///< CLI name, e.g. "paper"
    std::string config;  ///< config name, e.g. "multibox3/linear/C4/propagate"
    std::size_t wavelengths = 0;  ///< C
    /// \brief E[F] = I at every iteration in scenes without specular dispersion (docs/method.md §4, U1):
    /// true for an unrestricted kernel or the PropagateUnused bias; restriction-only and
    /// scaled-pdf are biased until N_thold.
    bool unbiased_before_nthold = false;
    /// \brief The film fades the early samples out (accumulation::fade): its image is the
    /// fade's blend, its mean the running mean.
    bool fades = false;
    /// \brief Its path tracer's hot loop has an AVX2 copy in this build (the presets whose
    /// B term runs 80 bins wide; docs/performance.md).
    bool isa_copy = false;
};

/// \brief Every preset, in the order of the preset list.
std::vector<preset_info> presets();

/// \brief The preset names `render` accepts, in the order of the preset list.
std::vector<std::string> preset_names();

/// \brief The config name (`multibox3/linear/C4/propagate`) of a preset. \throws std::invalid_argument
std::string config_name(const std::string& preset);

}  // namespace iris::renderer
