// iris-render — render a scene progressively with a sampling preset.
//
//   iris-render SCENE|FILE --preset NAME --spp N -o OUT.exr
//       [--threads T=all] [--seed S=1] [--nthold N=512] [--width W --height H (scene's)]
//       [--png OUT.png] [--stats OUT.json] [--every K=0 (spp)] [--every-seconds T=0]
//       [--half] [--max-depth D=32] [--sampler independent|sobol|zsobol]
//       [--estimator nee-mis|bdpt|light|bsdf-only] [--strategy S,T] [--unweighted] [--paths all|camera-only|rest]
//       [--resume] [--checkpoint-seconds T=600] [--keep-checkpoint]
//   mpirun -np N iris-render …   (the passes shared between N processes)
//   iris-render --list-presets | --list-scenes
//
// The image is rewritten atomically every K samples / T seconds and at the end, so a
// viewer that reloads it (e.g. tev) shows it converge. Every rewrite also writes the
// checkpoint OUT.exr.ckpt (the exact film; iris/renderer/checkpoint.hpp), as does every
// T seconds of --checkpoint-seconds; `--resume` goes on from it to the bytes an
// uninterrupted render writes. Ctrl-C (SIGINT) or SIGTERM stops after the current pass,
// writes the last complete image (with its true spp in the metadata) and its checkpoint,
// and exits 130 (143 for SIGTERM). A complete render removes its checkpoint.
//
// Under mpirun, rank r renders the passes i ≡ r (mod N); rank 0 sums the ranks' films
// exactly (iris::mpi) and writes everything. The image is the single process's, bit for
// bit, for any N, and a checkpoint made with one N resumes with another — for the fading
// presets too (paper-fade, paper-auto-fade: their film's fade layer is in both).
// Bad arguments, checkpoints of another render or corrupt ones: one line on stderr,
// exit 2, nothing written.
#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>

#include <unistd.h>

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <iris/exr/exr.hpp>
#include <iris/renderer/renderer.hpp>
#include <iris/scene/scene.hpp>
#include <iris/renderer/checkpoint.hpp>
#include <iris/renderer/spectral_output.hpp>
#include <iris/version.hpp>
#if IRIS_HAVE_MPI
#include <iris/mpi/mpi.hpp>
#endif
#if IRIS_HAVE_TEV
#include <iris/tev/tev.hpp>
#endif

#include "cli.hpp"
#include "tev_option.hpp"

namespace {

std::atomic<int> g_signal{0};  ///< SIGINT or SIGTERM once received
extern "C" void on_signal(int sig) { g_signal.store(sig); }

#if IRIS_HAVE_MPI
using ranks_session = iris::mpi::session;
#else
/// \brief One process: what iris::mpi::session does without a launcher.
struct ranks_session {
    ranks_session(int&, char**&) {}
    int rank() const noexcept { return 0; }
    int size() const noexcept { return 1; }
    bool active() const noexcept { return false; }
    iris::film reduce(const iris::film& f) const { return f; }
    int max(int v) const { return v; }
    double max(double v) const { return v; }
    double sum(double v) const { return v; }
    std::uint64_t sum(std::uint64_t v) const { return v; }
    double broadcast(double v) const { return v; }
    void abort(int) const {}
};
#endif

/// \brief Set once the ranks have started working together: an error after that must end
/// every rank (MPI_Abort), where one before it is met by every rank alike.
bool g_collective = false;

namespace fs = std::filesystem;

struct args {
    std::string scene, preset = "hwss", out, png, stats, isa = "auto", estimator = "nee-mis",
                sampler = "sobol", strategy;
    bool unweighted = false;
    std::string paths = "all";
    int spp = 16, threads = 0, nthold = 512, width = 0, height = 0, every = 0, max_depth = 32;
    int spectral = 0;  ///< spectral bands in the EXR (0: none)
    double every_seconds = 0.0, checkpoint_seconds = 600.0, tev_seconds = 0.25;
    std::string tev;      ///< tev address ("" with --tev alone: the default)
    bool tev_on = false;
    std::uint64_t seed = 1;
    bool half = false, list_presets = false, list_scenes = false, resume = false, keep_checkpoint = false;
    bool strict = false;                                 ///< a pbrt-v4 scene's approximations are errors
    bool spp_given = false, max_depth_given = false;     ///< else the scene file's suggestion, if any
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

iris::exr::metadata metadata(const iris::scene_desc& s, const iris::renderer::options& opt, const iris::renderer::status& st) {
    return iris::renderer::image_metadata(s.name, opt, st);
}

/// \brief The image (a pure function of the render's key and spp: no time or machine in
/// its header, so a resumed or distributed render writes the same bytes; timing is in
/// --stats) and the PNG.
void write_outputs(const iris::scene_desc& s, const args& a, const iris::renderer::options& opt, const iris::film& f,
                   const iris::renderer::status& st) {
    const iris::image img = f.to_image();
    auto meta = metadata(s, opt, st);
    iris::renderer::add_spectral_metadata(f, meta);
    const iris::exr::spectral_image spectral = iris::renderer::spectral_channels(f);
    iris::exr::write(a.out, img, meta, a.half ? iris::exr::pixel_type::half : iris::exr::pixel_type::float32,
                     spectral.count() > 0 ? &spectral : nullptr);
    if (!a.png.empty()) iris::exr::write_png(a.png, img);
}

std::string checkpoint_path(const args& a) { return a.out + ".ckpt"; }

#if IRIS_HAVE_TEV
/// \brief The running image as a tev frame: linear sRGB, named after the output file.
iris::tev::frame tev_frame(const args& a, const iris::film& f) {
    const iris::image img = f.to_image();
    iris::tev::frame fr{fs::path(a.out).filename().string(), img.width(), img.height(), {"R", "G", "B"}, {}};
    fr.data.reserve(img.pixel_count() * 3);
    for (const auto& p : img.pixels()) {
        fr.data.push_back(p.r);
        fr.data.push_back(p.g);
        fr.data.push_back(p.b);
    }
    return fr;
}
#endif

iris::renderer::checkpoint_key key_of(const iris::scene_desc& s, const args& a, int width, int height) {
    // a bidirectional render's strategy choice is part of what its film holds
    std::string estimator = a.estimator;
    if (!a.strategy.empty()) estimator += " strategy " + a.strategy;
    if (a.unweighted) estimator += " unweighted";
    if (a.paths != "all") estimator += " paths " + a.paths;
    return {std::string(iris::version), s.name, iris::scene::fingerprint(s), a.preset, estimator, a.sampler, a.seed,
            a.nthold, a.max_depth, a.spp, width, height, a.spectral};
}

/// \brief This run's totals over every rank (samples, rays, dropped samples; rank 0's time).
struct run_totals {
    std::uint64_t samples = 0, rays = 0;
    double seconds = 0.0;
    int ranks = 1, resumed_from = 0;
    int gathers = 0;              ///< reductions of the ranks' films to rank 0
    double gather_seconds = 0.0;  ///< their wall-clock time on rank 0 (with the wait for the slowest rank)
    std::uint64_t gather_bytes = 0;  ///< film bytes each rank sends per gather
    double busy_max = 0.0, busy_mean = 0.0;  ///< seconds the ranks spent in their passes: the balance
    double write_seconds = 0.0;  ///< rank 0's time writing images and checkpoints
};

void write_stats(const iris::scene_desc& s, const args& a, iris::renderer::status st, const run_totals& t) {
    if (a.stats.empty()) return;
    st.samples = t.samples;
    st.rays = t.rays;
    st.seconds = t.seconds;
    nlohmann::json j = {{"scene", s.name},
                        {"preset", a.preset},
                        {"config", st.config_name},
                        {"windows", st.windows},
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
                        {"ranks", t.ranks},
                        {"resumed_from_spp", t.resumed_from},
                        {"gathers", t.gathers},
                        {"gather_seconds", t.gather_seconds},
                        {"gather_bytes", t.gather_bytes},
                        {"rank_busy_seconds_max", t.busy_max},
                        {"rank_busy_seconds_mean", t.busy_mean},
                        {"write_seconds", t.write_seconds},
                        {"version", std::string(iris::version)}};
    iris::exr::write_atomically(a.stats, [&](const fs::path& tmp) {
        std::ofstream o(tmp);
        o << j.dump(2) << "\n";
        if (!o) throw std::runtime_error("cannot write stats '" + a.stats + "'");
    });
}

int run_render(args a, const ranks_session& mpi) {
    if (a.spp <= 0) throw iris::app::usage_error(fmt::format("--spp must be > 0, got {}", a.spp));
    if (a.nthold < 1) throw iris::app::usage_error(fmt::format("--nthold must be >= 1, got {}", a.nthold));
    if (a.threads < 0) throw iris::app::usage_error(fmt::format("--threads must be >= 0, got {}", a.threads));
    if ((a.width != 0) != (a.height != 0) || a.width < 0 || a.height < 0 || a.width > 16384 || a.height > 16384)
        throw iris::app::usage_error("--width and --height go together and must be in 1..16384");
    if (a.every < 0 || a.every_seconds < 0 || a.checkpoint_seconds < 0)
        throw iris::app::usage_error("--every, --every-seconds and --checkpoint-seconds must be >= 0");
    if (a.max_depth < 1 || a.max_depth > 10000) throw iris::app::usage_error("--max-depth must be in 1..10000");
    if (a.out.empty()) throw iris::app::usage_error("an output image is required: -o OUT.exr");
    if (a.tev_seconds < 0) throw iris::app::usage_error("--tev-seconds must be >= 0");
#if IRIS_HAVE_TEV
    iris::tev::address tev_address;
    if (a.tev_on) tev_address = iris::app::tev_option(a.tev);
#else
    if (a.tev_on) iris::app::tev_option(a.tev);
#endif
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
        scene = iris::scene::load_scene(a.scene, {.strict = a.strict});
    } catch (const std::exception& e) {
        throw iris::app::usage_error(e.what());
    }
    for (const auto& m : iris::scene::approximations(scene)) fmt::print(stderr, "iris-render: warning: {}\n", m);
    // a pbrt-v4 file's Sampler and Integrator suggest them; the command line decides
    if (!a.spp_given && scene.default_spp > 0) a.spp = scene.default_spp;
    if (!a.max_depth_given && scene.default_max_depth > 0) a.max_depth = std::min(scene.default_max_depth, 10000);

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
    if (!a.strategy.empty()) {
        int s = -1, t = -1;
        char comma = 0, extra = 0;
        if (std::sscanf(a.strategy.c_str(), "%d%c%d%c", &s, &comma, &t, &extra) != 3 || comma != ',' || s < 0 || t < 1 ||
            (s == 1 && t == 1))
            throw iris::app::usage_error(fmt::format(
                "--strategy expects S,T with S >= 0 light vertices and T >= 1 camera vertices, not (1,1), got '{}'",
                a.strategy));
        opt.bdpt.only_s = s;
        opt.bdpt.only_t = t;
    }
    opt.bdpt.mis = !a.unweighted;
    if ((!a.strategy.empty() || a.unweighted || a.paths != "all") && a.estimator != "bdpt")
        throw iris::app::usage_error("--strategy, --unweighted and --paths need --estimator bdpt");
    if (a.unweighted && a.paths != "all")
        throw iris::app::usage_error("--paths needs the weighted render (which strategies can make a path decides "
                                     "which are camera-only), not --unweighted");
    opt.bdpt.keep = a.paths == "camera-only" ? iris::bdpt_settings::paths::camera_only
                    : a.paths == "rest"      ? iris::bdpt_settings::paths::rest
                                             : iris::bdpt_settings::paths::all;
    opt.sampler = a.sampler;
    opt.spectral_bins = a.spectral;
    opt.rank = mpi.rank();
    opt.ranks = mpi.size();
    try {
        iris::renderer::check(opt);  // every option the renderer refuses, before anything is read or written
    } catch (const std::invalid_argument& e) {
        throw iris::app::usage_error(fmt::format("{}{}", a.spectral != 0 && std::string_view(e.what()).find("spectral") !=
                                                                                 std::string_view::npos ? "--spectral: " : "",
                                                 e.what()));
    }
    const int width = a.width > 0 ? a.width : scene.camera.width;
    const int height = a.height > 0 ? a.height : scene.camera.height;
    const bool root = mpi.rank() == 0;

    // The checkpoint: read and checked by rank 0 before anything is written; every rank
    // learns how it went (spp done, or -1: rank 0 stops with the reason, the others exit 2).
    const std::string ckpt = checkpoint_path(a);
    const iris::renderer::checkpoint_key key = key_of(scene, a, width, height);
    iris::renderer::checkpoint resumed;
    double start_spp = 0;
    std::string refusal;
    if (root) {
        if (a.resume) {
            try {
                resumed = iris::renderer::read_checkpoint(ckpt);
                if (const auto m = iris::renderer::key_mismatch(resumed.key, key))
                    refusal = fmt::format("checkpoint '{}' belongs to another render: {}; nothing written", ckpt, *m);
                start_spp = resumed.spp_done;
            } catch (const iris::renderer::checkpoint_error& e) {
                refusal = e.what();
            }
        } else if (fs::exists(ckpt)) {
            refusal = fmt::format("checkpoint '{}' of an unfinished render exists: --resume continues it (or delete it to "
                                  "start again); nothing written", ckpt);
        }
        if (!refusal.empty()) start_spp = -1;
    }
    start_spp = mpi.broadcast(start_spp);
    if (start_spp < 0) throw iris::app::usage_error(root ? refusal : std::string("rank 0 could not resume (see its message)"));
    opt.start_spp = static_cast<int>(start_spp);
    g_collective = mpi.active();

    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    const bool tty = root && ::isatty(STDERR_FILENO) != 0;
    const auto run_start = std::chrono::steady_clock::now();
    auto last_image = run_start, last_checkpoint = run_start;
    bool stopped = false;

#if IRIS_HAVE_TEV
    // Live view: rank 0 posts the running image to a sender thread (never blocking); one
    // process posts between passes at most every --tev-seconds, and never more often than
    // 50 times the conversion's cost (so streaming costs at most 2 % of the render); under
    // MPI only the images it writes (the ranks' films summed).
    std::unique_ptr<iris::tev::client> tev;
    if (a.tev_on && root)
        tev = std::make_unique<iris::tev::client>(tev_address, [](const std::string& m) {
            fmt::print(stderr, "iris-render: warning: {}\n", m);
        });
    auto last_post = std::chrono::steady_clock::now();
    double post_cost = 0.0;
    const auto post = [&](const iris::film& film) {
        const auto t0 = std::chrono::steady_clock::now();
        tev->post(tev_frame(a, film));
        last_post = std::chrono::steady_clock::now();
        post_cost = std::chrono::duration<double>(last_post - t0).count();
    };
#endif

    run_totals totals;
    std::uint64_t dropped = 0;  // samples dropped over all ranks and runs (at the last save)
    totals.ranks = mpi.size();
    totals.resumed_from = opt.start_spp;
    // This run's totals over the ranks, added to the checkpoint's. Collective.
    const auto gather_totals = [&](const iris::renderer::status& st) {
        totals.samples = mpi.sum(st.samples);
        totals.rays = mpi.sum(st.rays);
        totals.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start).count();
        totals.busy_max = mpi.max(st.seconds);
        totals.busy_mean = mpi.sum(st.seconds) / mpi.size();
    };
    // Rank 0 writes the image (if asked) and the checkpoint of the film summed over the
    // ranks. Collective.
    const auto save = [&](const iris::film& local, iris::renderer::status st, bool image, bool checkpoint) {
        gather_totals(st);
        const auto gather_start = std::chrono::steady_clock::now();
        iris::film sum = mpi.reduce(local);
        ++totals.gathers;
        totals.gather_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - gather_start).count();
        totals.gather_bytes = local.sums().size() * (iris::film::bytes_per_pixel + iris::film::spectral_bytes_per_band *
                                                                         static_cast<std::size_t>(a.spectral));
        if (!root) return;
        const auto write_start = std::chrono::steady_clock::now();
        st.nan_inf = dropped = sum.dropped();
        if (image) write_outputs(scene, a, opt, sum, st);
#if IRIS_HAVE_TEV
        if (image && tev) post(sum);
#endif
        if (checkpoint)
            iris::renderer::write_checkpoint(ckpt, {key, st.spp_done, resumed.samples + totals.samples,
                                                    resumed.rays + totals.rays, resumed.seconds + totals.seconds,
                                                    std::move(sum)});
        totals.write_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - write_start).count();
    };


    iris::renderer::hooks h;
    int last_spp = opt.start_spp;
    h.on_pass = [&](const iris::film& f, const iris::renderer::status& st) {
        // One collective per round: bit 0 "write now" (rank 0's clocks decide), bit 1 "stop"
        // (a signal on any rank).
        const auto now = std::chrono::steady_clock::now();
        const auto since = [&](auto t) { return std::chrono::duration<double>(now - t).count(); };
        const bool by_count = a.every > 0 && st.spp_done / a.every != last_spp / a.every;
        const bool image_due = root && (by_count || (a.every_seconds > 0 && since(last_image) >= a.every_seconds));
        const bool checkpoint_due = root && a.checkpoint_seconds > 0 && since(last_checkpoint) >= a.checkpoint_seconds;
        const int flags = mpi.max((image_due ? 1 : 0) | (checkpoint_due ? 2 : 0) | (g_signal.load() != 0 ? 4 : 0));
        last_spp = st.spp_done;
        stopped = (flags & 4) != 0;
        if ((flags & 3) != 0 && !stopped && st.spp_done < st.spp_total) {
            save(f, st, (flags & 1) != 0, true);
            if (flags & 1) last_image = now;
            last_checkpoint = now;
        }
#if IRIS_HAVE_TEV
        if (tev && mpi.size() == 1 && !stopped && st.spp_done < st.spp_total &&
            std::chrono::duration<double>(now - last_post).count() >= std::max(a.tev_seconds, 50.0 * post_cost))
            post(f);
#endif
        if (tty) {
            const double sps = st.seconds > 0 ? static_cast<double>(st.samples) * mpi.size() / st.seconds : 0.0;
            const int done = st.spp_done - opt.start_spp;
            const double left = done > 0 ? st.seconds / done * (st.spp_total - st.spp_done) : -1.0;
            const int bar = 30;
            const int filled = st.spp_total > 0 ? bar * st.spp_done / st.spp_total : 0;
            fmt::print(stderr, "\r[{:<{}}] {}/{} spp  {:.2f} Msamples/s  ETA {}   ", std::string(static_cast<std::size_t>(filled), '#'),
                       bar, st.spp_done, st.spp_total, sps * 1e-6, eta(left));
        }
        return !stopped;
    };

    iris::film f(1, 1);
    if (root && opt.start_spp > 0) f = std::move(resumed.image);
    else if (opt.start_spp > 0) f = iris::film(width, height);
    iris::renderer::status st;
    try {
        st = iris::renderer::render(scene, opt, f, h);
    } catch (const std::invalid_argument& e) {
        throw iris::app::usage_error(e.what());
    }
    if (tty) fmt::print(stderr, "\n");
    st.interrupted = st.spp_done < st.spp_total;
    // the last complete image; the checkpoint too if the render is to go on
    const bool keep = st.interrupted || a.keep_checkpoint;
    save(f, st, true, keep);
    if (!root) return 0;
#if IRIS_HAVE_TEV
    if (tev && !tev->flush(5.0))
        fmt::print(stderr, "iris-render: warning: the last image did not reach tev within 5 s\n");
#endif
    std::error_code ec;
    if (!keep) fs::remove(ckpt, ec);
    st.nan_inf = dropped;
    write_stats(scene, a, st, totals);
    const int sig = g_signal.load();
    fmt::print("{}: {} with {} ({}), {}x{}, {} spp in {:.2f} s: {:.3f} Msamples/s, {:.2f} Mrays/s, {} NaN/Inf samples dropped{}\n",
               a.out, scene.name, a.estimator == "bsdf-only" ? std::string("the bsdf-only estimator") : a.preset,
               a.estimator == "bsdf-only" ? std::string("no preset") : st.config_name, st.width, st.height, st.spp_done,
               totals.seconds, totals.seconds > 0 ? static_cast<double>(totals.samples) / totals.seconds * 1e-6 : 0.0,
               totals.seconds > 0 ? static_cast<double>(totals.rays) / totals.seconds * 1e-6 : 0.0, st.nan_inf,
               st.interrupted ? " (interrupted)" : "");
    return st.interrupted ? (sig == SIGTERM ? 143 : 130) : 0;
}

}  // namespace

int main(int argc, char** argv) {
    ranks_session mpi(argc, argv);
    CLI::App app{"iris-render: progressive spectral rendering of a scene with a sampling preset", "iris-render"};
    app.set_version_flag("--version", std::string(iris::version));
    args a;
    app.add_option("SCENE", a.scene, "built-in scene name (--list-scenes), scene JSON file or pbrt-v4 file (.pbrt)");
    app.add_option("--preset", a.preset, "sampling preset (--list-presets)")->capture_default_str();
    auto* spp_option = app.add_option("--spp", a.spp, "samples per pixel (default: a pbrt-v4 scene's pixelsamples, else 16)")
                           ->capture_default_str();
    app.add_option("--threads", a.threads, "worker threads (0: all)")->capture_default_str();
    app.add_option("--seed", a.seed, "random seed")->capture_default_str();
    app.add_option("--nthold", a.nthold, "relaxation length N_thold in samples per pixel")->capture_default_str();
    app.add_option("--width", a.width, "image width (default: the scene's)");
    app.add_option("--height", a.height, "image height (default: the scene's)");
    app.add_option("-o,--output", a.out, "output EXR (linear sRGB, metadata in the header)");
    app.add_option("--png", a.png, "also write an sRGB PNG preview");
    app.add_option("--spectral", a.spectral,
                   "also write the spectral radiance in the EXR: B equal bands over the scene's wavelength range, as "
                   "channels S0.<centre>nm (the spectral layout of Fichet et al. 2021), each the band's mean; exact like "
                   "the XYZ film, 16*B bytes more per pixel (nee-mis and bsdf-only estimators; 0: none)")
        ->capture_default_str();
    app.add_option("--stats", a.stats, "write run statistics as JSON");
    app.add_option("--every", a.every, "rewrite the image every K samples per pixel (0: only at the end)")->capture_default_str();
    app.add_option("--every-seconds", a.every_seconds, "rewrite the image every T seconds (0: off)")->capture_default_str();
    auto* depth_option = app.add_option("--max-depth", a.max_depth,
                                        "maximum number of scattering events (default: a pbrt-v4 scene's maxdepth, else 32)")
                             ->capture_default_str();
    app.add_flag("--strict", a.strict,
                 "a pbrt-v4 scene: refuse what the importer would approximate (docs/pbrt-import.md) instead of warning");
    app.add_option("--isa", a.isa,
                   fmt::format("instruction set of the integrator's hot loop: auto (the widest this CPU runs) or one of "
                               "{} (the images are bit-identical; only the speed differs)",
                               fmt::join(iris::renderer::instruction_sets(), ", ")))
        ->check(CLI::IsMember({"auto", "baseline", "avx2"}))
        ->capture_default_str();
    app.add_option("--estimator", a.estimator,
                   "nee-mis (the preset's path tracer: next-event estimation with MIS), bdpt (the preset's "
                   "bidirectional path tracer: light and camera subpaths, every (s, t) strategy weighted over "
                   "strategies x wavelengths — caustics; baseline instruction set), light (the preset's light "
                   "tracer: paths from the lights, each vertex connected to the camera — caustics; misses the "
                   "environment and delta lights seen directly and anything seen only in a mirror or through smooth "
                   "glass; baseline instruction set) or bsdf-only (pure BSDF sampling at one uniform wavelength, no "
                   "light sampling: the independent check of nee-mis; the preset is not used)")
        ->check(CLI::IsMember({"nee-mis", "bdpt", "light", "bsdf-only"}))
        ->capture_default_str();
    app.add_option("--strategy", a.strategy,
                   "bdpt: keep only strategy S,T (S light vertices, T camera vertices; e.g. 0,3 = a light hit after "
                   "one bounce, 2,1 = light tracing of one bounce) — still MIS-weighted unless --unweighted");
    app.add_flag("--unweighted", a.unweighted,
                 "bdpt: weight each strategy over the wavelengths alone, not against the other strategies (with "
                 "--strategy: that strategy's own unbiased estimate of the paths it can make)");
    app.add_option("--paths", a.paths,
                   "bdpt: keep all paths, only the camera-only ones (those no strategy but a camera path that hits "
                   "the light can make, through a non-delta vertex: a caustic seen through glass or in a mirror, "
                   "specular-diffuse-specular) or the rest; the two images sum to the whole — to measure how much "
                   "of the error the camera-only paths carry")
        ->check(CLI::IsMember({"all", "camera-only", "rest"}))
        ->capture_default_str();
    app.add_option("--sampler", a.sampler,
                   "where each pixel's random numbers come from: independent (a hash per number), sobol "
                   "(Owen-scrambled Sobol' points, per pixel) or zsobol (the same, Morton-ordered over the image: "
                   "blue-noise error)")
        ->check(CLI::IsMember({"independent", "sobol", "zsobol"}))
        ->capture_default_str();
    app.add_flag("--resume", a.resume,
                 "go on from the checkpoint OUT.exr.ckpt to the image an uninterrupted render writes (same bytes); it "
                 "must be this render's (scene, preset, estimator, sampler, seed, nthold, max depth, spp, size, iris "
                 "version), else exit 2 and nothing written");
    app.add_option("--checkpoint-seconds", a.checkpoint_seconds,
                   "also write the checkpoint every T seconds (0: only with the images of --every/--every-seconds "
                   "and when interrupted)")
        ->capture_default_str();
    app.add_flag("--keep-checkpoint", a.keep_checkpoint, "keep the checkpoint after a complete render (default: removed)");
    auto* tev_option = app.add_option("--tev", a.tev,
                   "stream the running image to the tev viewer at HOST:PORT (default 127.0.0.1:14158; write "
                   "--tev=HOST:PORT before the scene, or put --tev after it); if tev is not running the render goes "
                   "on and connects when it is")
        ->expected(0, 1);
    app.add_option("--tev-seconds", a.tev_seconds, "at most one tev update every T seconds")->capture_default_str();
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
        a.tev_on = tev_option->count() > 0;
        a.spp_given = spp_option->count() > 0;
        a.max_depth_given = depth_option->count() > 0;
        status = run_render(a, mpi);
    });
    const int rc = iris::app::run(app, argc, argv);
    // an error on one rank while the others work with it: end them all, with its status
    if (rc != 0 && g_collective && mpi.size() > 1) mpi.abort(rc);
    return rc != 0 ? rc : status;
}
