// iris-render — render a scene progressively with a sampling preset.
//
//   iris-render SCENE|FILE --preset NAME --spp N -o OUT.exr
//       [--threads T=all] [--seed S=1] [--nthold N=512] [--width W --height H (scene's)]
//       [--png OUT.png] [--stats OUT.json] [--every K=0 (spp)] [--every-seconds T=0]
//       [--half] [--max-depth D=32] [--sampler independent|sobol|zsobol]
//   iris-render --list-presets | --list-scenes
//
// The image is rewritten atomically every K samples / T seconds and at the end, so a
// viewer that reloads it (e.g. tev) shows it converge. Ctrl-C stops after the current
// pass, writes the last complete image (with its true spp in the metadata) and exits 130.
// Bad arguments: one line on stderr, exit 2, nothing written.
#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <unistd.h>

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <iris/exr/exr.hpp>
#include <iris/renderer/renderer.hpp>
#include <iris/scene/scene.hpp>
#include <iris/version.hpp>

#include "cli.hpp"

namespace {

std::atomic<bool> g_interrupted{false};
extern "C" void on_sigint(int) { g_interrupted.store(true); }

namespace fs = std::filesystem;

struct args {
    std::string scene, preset = "hwss", out, png, stats, isa = "auto", estimator = "nee-mis",
                sampler = "sobol";
    int spp = 16, threads = 0, nthold = 512, width = 0, height = 0, every = 0, max_depth = 32;
    double every_seconds = 0.0;
    std::uint64_t seed = 1;
    bool half = false, list_presets = false, list_scenes = false;
};

void check_writable(const std::string& path, const char* what) {
    if (path.empty()) return;
    const fs::path p(path);
    if (fs::is_directory(p))
        throw iris::app::usage_error(fmt::format("cannot write {} '{}': it is a directory", what, path));
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    if (!fs::is_directory(dir))
        throw iris::app::usage_error(fmt::format("cannot write {} '{}': directory '{}' does not exist", what, path,
                                                 dir.string()));
    if (::access(dir.c_str(), W_OK) != 0)
        throw iris::app::usage_error(fmt::format("cannot write {} '{}': directory is not writable", what, path));
}

/// \brief Refuse an output name whose extension says another format (an EXR called
/// out.png, or --png out.exr overwriting the EXR), as iris-image does.
void require_extension(const std::string& path, std::string_view ext, const char* option) {
    if (path.empty()) return;
    std::string e = fs::path(path).extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (e != ext) throw iris::app::usage_error(fmt::format("{} '{}' must end in {}", option, path, ext));
}

std::string eta(double seconds) {
    if (!(seconds >= 0.0) || seconds > 1e7) return "?";
    const auto s = static_cast<long>(seconds + 0.5);
    return s >= 3600 ? fmt::format("{}h{:02}m", s / 3600, (s / 60) % 60)
                     : s >= 60 ? fmt::format("{}m{:02}s", s / 60, s % 60) : fmt::format("{}s", s);
}

iris::exr::metadata metadata(const iris::scene_desc& s, const args& a, const iris::renderer::status& st) {
    return {{"iris:scene", s.name},
            {"iris:preset", a.preset},
            {"iris:config", st.config_name},
            {"iris:estimator", st.estimator},
            {"iris:sampler", st.sampler},
            {"iris:spp", std::to_string(st.spp_done)},
            {"iris:seconds", fmt::format("{:.3f}", st.seconds)},
            {"iris:seed", std::to_string(a.seed)},
            {"iris:nthold", std::to_string(a.nthold)},
            {"iris:nan_inf", std::to_string(st.nan_inf)},
            {"iris:version", std::string(iris::version)}};
}

void write_outputs(const iris::scene_desc& s, const args& a, const iris::film& f, const iris::renderer::status& st) {
    const iris::image img = f.to_image();
    iris::exr::write(a.out, img, metadata(s, a, st), a.half ? iris::exr::pixel_type::half : iris::exr::pixel_type::float32);
    if (!a.png.empty()) iris::exr::write_png(a.png, img);
}

void write_stats(const iris::scene_desc& s, const args& a, const iris::renderer::status& st) {
    if (a.stats.empty()) return;
    nlohmann::json j = {{"scene", s.name},
                        {"preset", a.preset},
                        {"config", st.config_name},
                        {"estimator", st.estimator},
                        {"spp", st.spp_done},
                        {"width", st.width},
                        {"height", st.height},
                        {"threads", st.threads},
                        {"threads_used", st.threads_used},
                        {"isa", st.isa},
                        {"sampler", st.sampler},
                        {"seed", a.seed},
                        {"nthold", a.nthold},
                        {"seconds", st.seconds},
                        {"samples_per_second", st.seconds > 0 ? static_cast<double>(st.samples) / st.seconds : 0.0},
                        {"rays_per_second", st.seconds > 0 ? static_cast<double>(st.rays) / st.seconds : 0.0},
                        {"samples", st.samples},
                        {"rays", st.rays},
                        {"nan_inf_count", st.nan_inf},
                        {"interrupted", st.interrupted},
                        {"version", std::string(iris::version)}};
    iris::exr::write_atomically(a.stats, [&](const fs::path& tmp) {
        std::ofstream o(tmp);
        o << j.dump(2) << "\n";
        if (!o) throw std::runtime_error("cannot write stats '" + a.stats + "'");
    });
}

int run_render(const args& a) {
    if (a.spp <= 0) throw iris::app::usage_error(fmt::format("--spp must be > 0, got {}", a.spp));
    if (a.nthold < 1) throw iris::app::usage_error(fmt::format("--nthold must be >= 1, got {}", a.nthold));
    if (a.threads < 0) throw iris::app::usage_error(fmt::format("--threads must be >= 0, got {}", a.threads));
    if ((a.width != 0) != (a.height != 0) || a.width < 0 || a.height < 0 || a.width > 16384 || a.height > 16384)
        throw iris::app::usage_error("--width and --height go together and must be in 1..16384");
    if (a.every < 0 || a.every_seconds < 0) throw iris::app::usage_error("--every and --every-seconds must be >= 0");
    if (a.max_depth < 1 || a.max_depth > 10000) throw iris::app::usage_error("--max-depth must be in 1..10000");
    if (a.out.empty()) throw iris::app::usage_error("an output image is required: -o OUT.exr");
    try {
        (void)iris::renderer::config_name(a.preset);
    } catch (const std::invalid_argument& e) {
        throw iris::app::usage_error(e.what());
    }
    require_extension(a.out, ".exr", "-o");
    require_extension(a.png, ".png", "--png");
    const auto same_file = [](const std::string& x, const std::string& y) {
        return !x.empty() && !y.empty() && fs::absolute(x).lexically_normal() == fs::absolute(y).lexically_normal();
    };
    if (same_file(a.stats, a.out) || same_file(a.stats, a.png))
        throw iris::app::usage_error(fmt::format("--stats '{}' would overwrite an output image", a.stats));
    check_writable(a.out, "image");
    check_writable(a.png, "PNG");
    check_writable(a.stats, "stats");

    iris::scene_desc scene;
    try {
        scene = iris::scene::load_scene(a.scene);
    } catch (const std::exception& e) {
        throw iris::app::usage_error(e.what());
    }

    iris::renderer::options opt;
    opt.preset = a.preset;
    opt.spp = a.spp;
    opt.threads = a.threads;
    opt.seed = a.seed;
    opt.nthold = a.nthold;
    opt.width = a.width;
    opt.height = a.height;
    opt.path.max_depth = a.max_depth;
    opt.isa = a.isa;
    opt.estimator = a.estimator;
    opt.sampler = a.sampler;

    std::signal(SIGINT, on_sigint);
    const bool tty = ::isatty(STDERR_FILENO) != 0;
    auto last_write = std::chrono::steady_clock::now();
    int last_written_spp = 0;

    iris::renderer::hooks h;
    h.cancel = &g_interrupted;
    h.on_pass = [&](const iris::film& f, const iris::renderer::status& st) {
        const auto now = std::chrono::steady_clock::now();
        const bool by_count = a.every > 0 && st.spp_done % a.every == 0;
        const bool by_time = a.every_seconds > 0 && std::chrono::duration<double>(now - last_write).count() >= a.every_seconds;
        if ((by_count || by_time) && st.spp_done < st.spp_total) {
            write_outputs(scene, a, f, st);
            last_write = now;
            last_written_spp = st.spp_done;
        }
        if (tty) {
            const double sps = st.seconds > 0 ? static_cast<double>(st.samples) / st.seconds : 0.0;
            const double left = st.spp_done > 0 ? st.seconds / st.spp_done * (st.spp_total - st.spp_done) : -1.0;
            const int width = 30;
            const int filled = st.spp_total > 0 ? width * st.spp_done / st.spp_total : 0;
            fmt::print(stderr, "\r[{:<{}}] {}/{} spp  {:.2f} Msamples/s  ETA {}   ", std::string(static_cast<std::size_t>(filled), '#'),
                       width, st.spp_done, st.spp_total, sps * 1e-6, eta(left));
        }
        return true;
    };
    (void)last_written_spp;

    iris::film f(1, 1);
    iris::renderer::status st;
    try {
        st = iris::renderer::render(scene, opt, f, h);
    } catch (const std::invalid_argument& e) {
        throw iris::app::usage_error(e.what());
    }
    if (tty) fmt::print(stderr, "\n");
    if (st.spp_done > 0) write_outputs(scene, a, f, st);
    write_stats(scene, a, st);
    if (st.spp_done == 0) {  // interrupted during the first pass: there is no image to write
        fmt::print("{}: not written, interrupted before the first pass completed\n", a.out);
        return 130;
    }
    fmt::print("{}: {} with {} ({}), {}x{}, {} spp in {:.2f} s: {:.3f} Msamples/s, {:.2f} Mrays/s, {} NaN/Inf samples dropped{}\n",
               a.out, scene.name, a.estimator == "bsdf-only" ? std::string("the bsdf-only estimator") : a.preset,
               a.estimator == "bsdf-only" ? std::string("no preset") : st.config_name, st.width, st.height, st.spp_done, st.seconds,
               st.seconds > 0 ? static_cast<double>(st.samples) / st.seconds * 1e-6 : 0.0,
               st.seconds > 0 ? static_cast<double>(st.rays) / st.seconds * 1e-6 : 0.0, st.nan_inf,
               st.interrupted ? " (interrupted)" : "");
    return st.interrupted ? 130 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"iris-render: progressive spectral rendering of a scene with a sampling preset", "iris-render"};
    app.set_version_flag("--version", std::string(iris::version));
    args a;
    app.add_option("SCENE", a.scene, "built-in scene name (--list-scenes) or scene JSON file");
    app.add_option("--preset", a.preset, "sampling preset (--list-presets)")->capture_default_str();
    app.add_option("--spp", a.spp, "samples per pixel")->capture_default_str();
    app.add_option("--threads", a.threads, "worker threads (0: all)")->capture_default_str();
    app.add_option("--seed", a.seed, "random seed")->capture_default_str();
    app.add_option("--nthold", a.nthold, "relaxation length N_thold in samples per pixel")->capture_default_str();
    app.add_option("--width", a.width, "image width (default: the scene's)");
    app.add_option("--height", a.height, "image height (default: the scene's)");
    app.add_option("-o,--output", a.out, "output EXR (linear sRGB, metadata in the header)");
    app.add_option("--png", a.png, "also write an sRGB PNG preview");
    app.add_option("--stats", a.stats, "write run statistics as JSON");
    app.add_option("--every", a.every, "rewrite the image every K samples per pixel (0: only at the end)")->capture_default_str();
    app.add_option("--every-seconds", a.every_seconds, "rewrite the image every T seconds (0: off)")->capture_default_str();
    app.add_option("--max-depth", a.max_depth, "maximum number of scattering events")->capture_default_str();
    app.add_option("--isa", a.isa,
                   fmt::format("instruction set of the integrator's hot loop: auto (the widest this CPU runs) or one of "
                               "{} (the images are bit-identical; only the speed differs)",
                               fmt::join(iris::renderer::instruction_sets(), ", ")))
        ->check(CLI::IsMember({"auto", "baseline", "avx2", "avx512"}))
        ->capture_default_str();
    app.add_option("--estimator", a.estimator,
                   "nee-mis (the preset's path tracer: next-event estimation with MIS) or bsdf-only (pure BSDF "
                   "sampling at one uniform wavelength, no light sampling: the independent check of nee-mis; the "
                   "preset is not used)")
        ->check(CLI::IsMember({"nee-mis", "bsdf-only"}))
        ->capture_default_str();
    app.add_option("--sampler", a.sampler,
                   "where each pixel's random numbers come from: independent (a hash per number), sobol "
                   "(Owen-scrambled Sobol' points, per pixel) or zsobol (the same, Morton-ordered over the image: "
                   "blue-noise error)")
        ->check(CLI::IsMember({"independent", "sobol", "zsobol"}))
        ->capture_default_str();
    app.add_flag("--half", a.half, "write half-float EXR (default float)");
    app.add_flag("--list-presets", a.list_presets, "list the sampling presets and exit");
    app.add_flag("--list-scenes", a.list_scenes, "list the built-in scenes and exit");
    int status = 0;
    app.callback([&] {
        if (a.list_presets) {
            for (const auto& p : iris::renderer::preset_names())
                fmt::print("{:<16} {}\n", p, iris::renderer::config_name(p));
            return;
        }
        if (a.list_scenes) {
            for (const auto& s : iris::scene::builtin_scenes()) fmt::print("{:<18} {}\n", s.name, s.description);
            return;
        }
        if (a.scene.empty()) throw iris::app::usage_error("a scene is required (see --list-scenes)");
        status = run_render(a);
    });
    const int rc = iris::app::run(app, argc, argv);
    return rc != 0 ? rc : status;
}
