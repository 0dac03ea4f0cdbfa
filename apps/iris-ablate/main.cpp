// iris-ablate — how fast does each preset become perceptually acceptable?
//
//   iris-ablate SCENE --presets hwss,paper,... --spp 16,32,64,128,256,512
//       [--reference-spp N=16384] [--time-budgets 1,2,4,8s] [--seeds K=1]
//       [--width W --height H (scene's)] [--threads T=all] [--nthold N=512]
//       [--cache DIR=~/.cache/iris] [--crop x,y,w,h (centre)]
//       [--sampler independent|sobol|zsobol] [--reference-sampler S (--sampler)]
//       [--estimator nee-mis|bdpt|light] [--reference-estimator E (--estimator)]
//       [--reference FILE.exr (instead of rendering one)] -o DIR
//
// Renders (or loads from the cache, keyed by scene content, size, seed, reference spp, sampler and code
// — this executable's bytes) an unbiased `hwss` reference, or takes one rendered elsewhere (--reference: of
// the run's size and, per its iris:scene attribute, of its scene; summary.md records its file and header), renders each preset progressively once per seed
// with snapshots at the requested spp (and wall-clock budgets), and writes DIR/results.csv
// (scene,preset,sampler,seed,spp,seconds,mse,relmse,ssim,flip), DIR/results_time.csv, the snapshot
// EXRs, SSIM/MSE plots against spp and seconds, crops at the smallest spp side by side,
// and DIR/summary.md. Bad arguments: one line on stderr, exit 2.
#include <algorithm>
#include <cstdlib>

#include <fmt/core.h>

#include <iris/version.hpp>

#include "ablation.hpp"
#include "cli.hpp"

namespace {

std::filesystem::path default_cache() {
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::filesystem::path(x) / "iris";
    if (const char* h = std::getenv("HOME"); h && *h) return std::filesystem::path(h) / ".cache" / "iris";
    return std::filesystem::temp_directory_path() / "iris-cache";
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"iris-ablate: compare sampling presets against a converged reference (SSIM, MSE vs spp and time)",
                 "iris-ablate"};
    app.set_version_flag("--version", std::string(iris::version));
    iris::app::ablation_options o;
    std::string presets = "hwss,paper", spp = "16,32,64,128,256,512", budgets, out, cache, reference;
    app.add_option("SCENE", o.scene, "built-in scene name or scene JSON file")->required();
    app.add_option("--presets", presets, "comma-separated presets (iris-render --list-presets)")->capture_default_str();
    app.add_option("--spp", spp, "comma-separated spp snapshots")->capture_default_str();
    auto* ref_spp = app.add_option("--reference-spp", o.reference_spp, "spp of the hwss reference")->capture_default_str();
    app.add_option("--time-budgets", budgets, "comma-separated wall-clock budgets, e.g. 1,2,4,8s (time-equal mode)");
    app.add_option("--seeds", o.seeds, "independent runs per preset (mean ± std)")->capture_default_str();
    app.add_option("--width", o.width, "image width (default: the scene's)");
    app.add_option("--height", o.height, "image height (default: the scene's)");
    app.add_option("--threads", o.threads, "worker threads (0: all)")->capture_default_str();
    app.add_option("--nthold", o.nthold, "relaxation length N_thold")->capture_default_str();
    app.add_option("--sampler", o.sampler, "sampler of every preset's renders: independent, sobol or zsobol")
        ->check(CLI::IsMember({"independent", "sobol", "zsobol"}))
        ->capture_default_str();
    auto* ref_sampler = app.add_option("--reference-sampler", o.reference_sampler,
                   "sampler of the reference (default: --sampler; give the same one to compare runs with different "
                   "--sampler against one reference)")
        ->check(CLI::IsMember({"independent", "sobol", "zsobol"}));
    app.add_option("--estimator", o.estimator,
                   "estimator of every preset's renders: nee-mis (path tracing), bdpt (bidirectional) or light "
                   "(light tracing)")
        ->check(CLI::IsMember({"nee-mis", "bdpt", "light"}))
        ->capture_default_str();
    auto* ref_estimator = app.add_option("--reference-estimator", o.reference_estimator,
                                         "estimator of the reference (default: --estimator)")
                              ->check(CLI::IsMember({"nee-mis", "bdpt", "light"}));
    app.add_option("--reference", reference,
                   "an EXR to use as the reference instead of rendering one (e.g. rendered on a cluster): the run's "
                   "size, and of its scene if its header names one")
        ->excludes(ref_spp)
        ->excludes(ref_sampler)
        ->excludes(ref_estimator);
    app.add_option("--cache", cache, "reference cache directory (default ~/.cache/iris)");
    app.add_option("--crop", o.crop, "crop rectangle x,y,w,h for the side-by-side PNG (default: the centre)");
    app.add_option("-o,--output", out, "output directory")->required();
    app.callback([&] {
        o.presets = iris::app::split_list(presets);
        if (o.presets.empty()) throw iris::app::usage_error("--presets is empty");
        o.spp.clear();
        for (const auto& s : iris::app::split_list(spp)) {
            const double v = iris::app::parse_number(s, "--spp entry");
            if (v < 1 || v > 1e7 || v != static_cast<int>(v))
                throw iris::app::usage_error(fmt::format("--spp entries must be integers in 1..1e7, got '{}'", s));
            o.spp.push_back(static_cast<int>(v));
        }
        if (o.spp.empty()) throw iris::app::usage_error("--spp is empty");
        std::sort(o.spp.begin(), o.spp.end());
        o.spp.erase(std::unique(o.spp.begin(), o.spp.end()), o.spp.end());
        for (auto b : iris::app::split_list(budgets)) {
            if (!b.empty() && b.back() == 's') b.pop_back();
            const double v = iris::app::parse_number(b, "--time-budgets entry");
            if (!(v > 0 && v <= 86400)) throw iris::app::usage_error(fmt::format("time budgets must be in (0, 86400] s, got '{}'", b));
            o.budgets.push_back(v);
        }
        std::sort(o.budgets.begin(), o.budgets.end());
        if (o.reference_spp < 1) throw iris::app::usage_error("--reference-spp must be >= 1");
        if (o.seeds < 1 || o.seeds > 1000) throw iris::app::usage_error("--seeds must be in 1..1000");
        if (o.nthold < 1) throw iris::app::usage_error("--nthold must be >= 1");
        if (o.threads < 0) throw iris::app::usage_error("--threads must be >= 0");
        if ((o.width != 0) != (o.height != 0) || o.width < 0 || o.height < 0)
            throw iris::app::usage_error("--width and --height go together and must be positive");
        o.out = out;
        o.reference_file = reference;
        o.cache = cache.empty() ? default_cache() : std::filesystem::path(cache);
        const auto result = iris::app::run_ablation(o);
        iris::app::write_report(o, result);
    });
    return iris::app::run(app, argc, argv);
}
