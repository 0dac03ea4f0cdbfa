// iris-compare — two or more presets converging side by side, at the same render time: the
// comparison of the paper's Figure 1, live in tev.
//
//   iris-compare SCENE [--presets hwss,paper,hwss:bdpt] [--seconds T=10 | --spp N] [--tev[=HOST:PORT]]
//       [--tev-seconds 0.25] [--reference FILE.exr] [-o DIR] [--width W --height H (scene's)]
//       [--threads T=all] [--seed S=1] [--sampler S=sobol] [--nthold N=512]
//
// The presets render in lockstep: one at a time, each pass with every thread, and the next
// pass always goes to the preset that has had the least render time so far (with --spp: the
// fewest samples). So at any moment their render times differ by at most one pass, and each
// renders at its own full speed, as it would alone. Their images go to tev together (one tev
// image per preset, "SCENE-PRESET", and one of all of them left to right, in the order of
// --presets, "SCENE-side-by-side"), at most every --tev-seconds of wall-clock time; the
// scheduling and the streaming are not counted as render time. Every preset's pixels are
// those `iris-render` gives for the same seed, sampler and spp (with --spp N; with --seconds
// the sampler is set up for an open-ended render, as iris-ablate's time budgets are).
//
// At the end: a table (preset, spp, render seconds, samples/s, and with --reference MSE,
// relMSE and SSIM against it) on stdout; with -o DIR, DIR/PRESET.exr, DIR/side-by-side.png and
// DIR/compare.csv. Ctrl-C stops after the current pass and writes what is complete (exit 130).
// Bad arguments: one line on stderr, exit 2.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <tuple>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <thread>

#include <unistd.h>

#include <fmt/core.h>

#include <iris/exr/exr.hpp>
#include <iris/metrics/metrics.hpp>
#include <iris/renderer/renderer.hpp>
#include <iris/scene/scene.hpp>
#include <iris/version.hpp>
#if IRIS_HAVE_TEV
#include <iris/tev/tev.hpp>
#endif

#include "cli.hpp"
#include "tev_option.hpp"

namespace {

namespace fs = std::filesystem;

std::atomic<int> g_signal{0};  ///< SIGINT or SIGTERM once received
extern "C" void on_signal(int sig) { g_signal.store(sig); }

struct args {
    std::string scene, presets = "hwss,paper", sampler = "sobol", reference, out, tev;
    double seconds = 10.0, tev_seconds = 0.25;
    int spp = 0, threads = 0, nthold = 512, width = 0, height = 0;
    std::uint64_t seed = 1;
    bool tev_on = false;
};

/// \brief One preset's render: its film, where it is, and its thread.
struct lane {
    lane(std::string p, int w, int h) : preset(std::move(p)), film(w, h) {}
    std::string preset;
    iris::film film;
    iris::renderer::status st;
    double max_pass = 0.0;  ///< the longest pass so far (s)
    bool started = false, done = false;
    std::string error;
};

/// \brief The lockstep: which lane renders next. Pure, so its rule is stated in one place:
/// among the lanes that are running, the one with the least render time (equal_spp: the fewest
/// passes), ties to the fewer passes, then to the earlier preset. -1 if none is running.
int next_turn(const std::vector<std::unique_ptr<lane>>& lanes, bool equal_spp) {
    int best = -1;
    for (int i = 0; i < static_cast<int>(lanes.size()); ++i) {
        const lane& l = *lanes[static_cast<std::size_t>(i)];
        if (!l.started || l.done) continue;
        if (best < 0) {
            best = i;
            continue;
        }
        const lane& b = *lanes[static_cast<std::size_t>(best)];
        const bool better = equal_spp ? l.st.spp_done < b.st.spp_done
                                      : (l.st.seconds < b.st.seconds ||
                                         (l.st.seconds == b.st.seconds && l.st.spp_done < b.st.spp_done));
        if (better) best = i;
    }
    return best;
}

/// \brief The presets' images left to right, in order, 4 black pixels apart.
iris::image side_by_side(const std::vector<iris::image>& images) {
    constexpr int gap = 4;
    const int w = images.front().width(), h = images.front().height();
    const int n = static_cast<int>(images.size());
    iris::image out(n * w + (n - 1) * gap, h);
    for (int k = 0; k < n; ++k)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) out(k * (w + gap) + x, y) = images[static_cast<std::size_t>(k)](x, y);
    return out;
}

#if IRIS_HAVE_TEV
iris::tev::frame tev_frame(std::string name, const iris::image& img) {
    iris::tev::frame fr{std::move(name), img.width(), img.height(), {"R", "G", "B"}, {}};
    fr.data.reserve(img.pixel_count() * 3);
    for (const auto& p : img.pixels()) {
        fr.data.push_back(p.r);
        fr.data.push_back(p.g);
        fr.data.push_back(p.b);
    }
    return fr;
}
#endif

std::string file_safe(std::string s) {
    for (char& c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_')) c = '_';
    return s;
}

/// \brief A --presets entry: PRESET, or PRESET:ESTIMATOR (nee-mis, bdpt or light; default nee-mis).
std::pair<std::string, std::string> preset_and_estimator(const std::string& entry) {
    const auto colon = entry.find(':');
    if (colon == std::string::npos) return {entry, "nee-mis"};
    std::string est = entry.substr(colon + 1);
    if (est != "nee-mis" && est != "bdpt" && est != "light")
        throw iris::app::usage_error(
            fmt::format("--presets entry '{}': unknown estimator '{}' (expected nee-mis, bdpt or light)", entry, est));
    return {entry.substr(0, colon), est};
}

int compare_presets(const args& a) {
    const auto presets = iris::app::split_list(a.presets);
    if (presets.size() < 2) throw iris::app::usage_error(fmt::format("--presets needs two or more presets, got '{}'", a.presets));
    if (std::set<std::string>(presets.begin(), presets.end()).size() != presets.size())
        throw iris::app::usage_error(fmt::format("--presets names a preset twice: '{}'", a.presets));
    for (const auto& p : presets) try {
            (void)iris::renderer::config_name(preset_and_estimator(p).first);
        } catch (const std::invalid_argument& e) {
            throw iris::app::usage_error(e.what());
        }
    if (a.spp < 0 || a.spp > 10'000'000) throw iris::app::usage_error(fmt::format("--spp must be in 1..1e7, got {}", a.spp));
    if (!(a.seconds > 0 && a.seconds <= 7 * 86400.0))
        throw iris::app::usage_error(fmt::format("--seconds must be in (0, 604800], got {}", a.seconds));
    if (a.tev_seconds < 0) throw iris::app::usage_error("--tev-seconds must be >= 0");
    if (a.threads < 0) throw iris::app::usage_error("--threads must be >= 0");
    if (a.nthold < 1) throw iris::app::usage_error("--nthold must be >= 1");
    if ((a.width != 0) != (a.height != 0) || a.width < 0 || a.height < 0 || a.width > 16384 || a.height > 16384)
        throw iris::app::usage_error("--width and --height go together and must be in 1..16384");
#if IRIS_HAVE_TEV
    iris::tev::address tev_address;
    if (a.tev_on) tev_address = iris::app::tev_option(a.tev);
#else
    if (a.tev_on) iris::app::tev_option(a.tev);
#endif
    iris::scene_desc scene;
    try {
        scene = iris::scene::load_scene(a.scene);
    } catch (const std::exception& e) {
        throw iris::app::usage_error(e.what());
    }
    const int w = a.width > 0 ? a.width : scene.camera.width;
    const int h = a.height > 0 ? a.height : scene.camera.height;
    std::optional<iris::image> reference;
    if (!a.reference.empty()) {
        try {
            reference = iris::exr::read(a.reference).pixels;
        } catch (const iris::exr::error& e) {
            throw iris::app::usage_error(fmt::format("--reference: {}", e.what()));
        }
        if (reference->width() != w || reference->height() != h)
            throw iris::app::usage_error(fmt::format("--reference {}: the image is {}x{}, the run is {}x{}", a.reference,
                                                     reference->width(), reference->height(), w, h));
    }
    if (!a.out.empty()) {
        std::error_code ec;
        fs::create_directories(a.out, ec);
        if (ec) throw iris::app::usage_error(fmt::format("-o: cannot create directory '{}': {}", a.out, ec.message()));
    }
    const bool equal_spp = a.spp > 0;

    std::vector<std::unique_ptr<lane>> lanes;
    for (const auto& p : presets) {
        lanes.push_back(std::make_unique<lane>(p, w, h));
    }
    const auto images = [&] {
        std::vector<iris::image> out;
        for (const auto& l : lanes) out.push_back(l->film.to_image());
        return out;
    };

#if IRIS_HAVE_TEV
    std::unique_ptr<iris::tev::client> tev;
    if (a.tev_on)
        tev = std::make_unique<iris::tev::client>(tev_address, [](const std::string& m) {
            fmt::print(stderr, "iris-compare: warning: {}\n", m);
        });
#endif
    // All presets' images together, one frame each and the side-by-side one. Called with the
    // baton held: no lane is rendering, every film is between passes.
    auto last_post = std::chrono::steady_clock::now();
    double post_cost = 0.0;
    const auto post = [&] {
#if IRIS_HAVE_TEV
        const auto t0 = std::chrono::steady_clock::now();
        const auto imgs = images();
        for (std::size_t i = 0; i < lanes.size(); ++i)
            tev->post(tev_frame(fmt::format("{}-{}", scene.name, lanes[i]->preset), imgs[i]));
        tev->post(tev_frame(fmt::format("{}-side-by-side", scene.name), side_by_side(imgs)));
        last_post = std::chrono::steady_clock::now();
        post_cost = std::chrono::duration<double>(last_post - t0).count();
#endif
    };

    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    const bool tty = ::isatty(STDERR_FILENO) != 0;
    const auto start = std::chrono::steady_clock::now();
    std::mutex m;
    std::condition_variable cv;
    int turn = -1;
    bool stop = false;
    double largest_gap = 0.0;  // the largest render-time gap between two presets after any pass
    const auto progress = [&] {  // with m held
        if (!tty) return;
        std::string line;
        double frac = 1.0;
        for (const auto& l : lanes) {
            line += fmt::format("{} {} spp {:.1f} s   ", l->preset, l->st.spp_done, l->st.seconds);
            frac = std::min(frac, equal_spp ? static_cast<double>(l->st.spp_done) / a.spp : l->st.seconds / a.seconds);
        }
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        fmt::print(stderr, "\r{}{:5.1f} %  ETA {:.0f} s    ", line, 100.0 * frac,
                   frac > 0 ? wall / frac * (1.0 - frac) : 0.0);
    };
    // Hand the baton on and wait for it (with m held); false when this lane is to stop.
    const auto pass_on = [&](std::unique_lock<std::mutex>& lock, int i) {
        turn = next_turn(lanes, equal_spp);
        cv.notify_all();
        cv.wait(lock, [&] { return stop || turn == i; });
        return !stop;
    };

    std::vector<std::thread> threads;
    for (int i = 0; i < static_cast<int>(lanes.size()); ++i) {
        threads.emplace_back([&, i] {
            lane& me = *lanes[static_cast<std::size_t>(i)];
            iris::renderer::options ro;
            std::tie(ro.preset, ro.estimator) = preset_and_estimator(me.preset);
            ro.spp = equal_spp ? a.spp : 10'000'000;
            ro.threads = a.threads;
            ro.seed = a.seed;
            ro.nthold = a.nthold;
            ro.width = w;
            ro.height = h;
            ro.sampler = a.sampler;
            iris::renderer::hooks hk;
            hk.on_start = [&](const iris::renderer::status& st) {
                std::unique_lock lock(m);
                me.st = st;
                me.started = true;
                // the first pass waits until every preset is set up
                if (std::all_of(lanes.begin(), lanes.end(), [](const auto& l) { return l->started || l->done; }))
                    turn = next_turn(lanes, equal_spp);
                cv.notify_all();
                cv.wait(lock, [&] { return stop || turn == i; });
                return !stop;
            };
            hk.on_pass = [&](const iris::film&, const iris::renderer::status& st) {
                std::unique_lock lock(m);
                me.max_pass = std::max(me.max_pass, st.seconds - me.st.seconds);
                me.st = st;
                double lo = me.st.seconds, hi = me.st.seconds;
                for (const auto& l : lanes) {
                    lo = std::min(lo, l->st.seconds);
                    hi = std::max(hi, l->st.seconds);
                }
                largest_gap = std::max(largest_gap, hi - lo);
                if (g_signal.load() != 0) stop = true;
                if (equal_spp ? st.spp_done >= a.spp : st.seconds >= a.seconds) me.done = true;
                progress();
#if IRIS_HAVE_TEV
                const auto now = std::chrono::steady_clock::now();
                if (tev && std::chrono::duration<double>(now - last_post).count() >= std::max(a.tev_seconds, 50.0 * post_cost))
                    post();
#endif
                if (me.done) {  // hand the baton on without waiting for it
                    turn = next_turn(lanes, equal_spp);
                    cv.notify_all();
                    return false;
                }
                return pass_on(lock, i);
            };
            try {
                iris::renderer::render(scene, ro, me.film, hk);
            } catch (const std::exception& e) {
                std::lock_guard lock(m);
                me.error = e.what();
                stop = true;  // one failed preset ends the comparison
            }
            std::lock_guard lock(m);
            me.done = true;
            turn = next_turn(lanes, equal_spp);
            cv.notify_all();
        });
    }
    for (auto& t : threads) t.join();
    if (tty) fmt::print(stderr, "\r{:<100}\r", "");
    for (const auto& l : lanes)
        if (!l->error.empty()) throw std::runtime_error(fmt::format("{}: {}", l->preset, l->error));

    const auto imgs = images();
#if IRIS_HAVE_TEV
    if (tev) {
        post();
        if (!tev->flush(5.0)) fmt::print(stderr, "iris-compare: warning: the last images did not reach tev within 5 s\n");
    }
#endif
    // the table, and with -o the images and the CSV
    std::string csv = "scene,preset,sampler,seed,spp,seconds,max_pass_seconds,samples_per_second,nan_inf,mse,relmse,ssim\n";
    fmt::print("{} at {}x{}, {}, sampler {}, seed {}:\n", scene.name, w, h,
               equal_spp ? fmt::format("equal spp ({})", a.spp) : fmt::format("equal render time ({} s)", a.seconds),
               a.sampler, a.seed);
    fmt::print("{:<16} {:>8} {:>9} {:>10} {:>12}{}\n", "preset", "spp", "seconds", "max pass", "samples/s",
               reference ? fmt::format(" {:>11} {:>11} {:>8}", "MSE", "relMSE", "SSIM") : std::string());
    for (std::size_t i = 0; i < lanes.size(); ++i) {
        const lane& l = *lanes[i];
        const double rate = l.st.seconds > 0 ? static_cast<double>(l.st.samples) / l.st.seconds : 0.0;
        std::string metrics_txt, metrics_csv = ",,";
        if (reference) {
            const auto mt = iris::compare(imgs[i], *reference);
            metrics_txt = fmt::format(" {:>11.4e} {:>11.4e} {:>8.4f}", mt.mse, mt.relmse, mt.ssim);
            metrics_csv = fmt::format("{:.6e},{:.6e},{:.6f}", mt.mse, mt.relmse, mt.ssim);
        }
        fmt::print("{:<16} {:>8} {:>9.3f} {:>10.3f} {:>12.4g}{}\n", l.preset, l.st.spp_done, l.st.seconds, l.max_pass, rate,
                   metrics_txt);
        csv += fmt::format("{},{},{},{},{},{:.4f},{:.4f},{:.6g},{},{}\n", scene.name, l.preset, a.sampler, a.seed,
                           l.st.spp_done, l.st.seconds, l.max_pass, rate, l.st.nan_inf, metrics_csv);
        if (l.st.nan_inf > 0)
            fmt::print(stderr, "iris-compare: {}: {} NaN/Inf samples dropped from the film\n", l.preset, l.st.nan_inf);
        if (!a.out.empty()) {
            iris::exr::metadata meta{{"iris:scene", scene.name}, {"iris:preset", l.preset}, {"iris:sampler", a.sampler},
                                     {"iris:spp", std::to_string(l.st.spp_done)}, {"iris:seed", std::to_string(a.seed)},
                                     {"iris:seconds", fmt::format("{:.3f}", l.st.seconds)},
                                     {"iris:version", std::string(iris::version)}};
            if (!l.st.windows.empty()) meta["iris:windows"] = l.st.windows;
            iris::exr::write(fs::path(a.out) / (file_safe(l.preset) + ".exr"), imgs[i], meta);
        }
    }
    double longest_pass = 0.0;
    for (const auto& l : lanes) longest_pass = std::max(longest_pass, l->max_pass);
    if (!equal_spp)
        fmt::print("largest render-time gap between presets after any pass: {:.4f} s (longest pass: {:.4f} s)\n",
                   largest_gap, longest_pass);
    fmt::print("wall-clock: {:.3f} s (setup, scheduling and streaming included)\n",
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (!a.out.empty()) {
        iris::exr::write_png(fs::path(a.out) / "side-by-side.png", side_by_side(imgs));
        const fs::path path = fs::path(a.out) / "compare.csv", tmp = path.string() + ".tmp";
        {
            std::ofstream f(tmp);
            f << csv;
            if (!f) throw std::runtime_error(fmt::format("cannot write {}", tmp.string()));
        }
        fs::rename(tmp, path);
    }
    if (const int sig = g_signal.load(); sig != 0) {
        fmt::print(stderr, "iris-compare: interrupted; wrote what was complete\n");
        return 128 + sig;
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"iris-compare: two or more presets converging side by side at the same render time (or spp), "
                 "streamed live to tev",
                 "iris-compare"};
    app.set_version_flag("--version", std::string(iris::version));
    args a;
    int status = 0;
    app.add_option("SCENE", a.scene, "built-in scene name or scene JSON file")->required();
    app.add_option("--presets", a.presets,
                   "comma-separated presets, left to right (iris-render --list-presets), each optionally with its "
                   "estimator: PRESET:bdpt, PRESET:light (default PRESET:nee-mis), e.g. hwss,hwss:bdpt")
        ->capture_default_str();
    auto* sec = app.add_option("--seconds", a.seconds, "render time per preset (equal-time comparison)")->capture_default_str();
    app.add_option("--spp", a.spp, "samples per pixel per preset (equal-spp comparison, instead of --seconds)")->excludes(sec);
    auto* tev_option = app.add_option("--tev", a.tev,
                                      "stream the images to the tev viewer at HOST:PORT (default 127.0.0.1:14158; "
                                      "write --tev=HOST:PORT before the scene, or put --tev after it)")
                           ->expected(0, 1);
    app.add_option("--tev-seconds", a.tev_seconds, "at most one tev update every T seconds")->capture_default_str();
    app.add_option("--reference", a.reference, "an EXR to measure the final images against (MSE, relMSE, SSIM)");
    app.add_option("-o,--output", a.out, "directory for PRESET.exr, side-by-side.png and compare.csv");
    app.add_option("--width", a.width, "image width (default: the scene's)");
    app.add_option("--height", a.height, "image height (default: the scene's)");
    app.add_option("--threads", a.threads, "worker threads of each pass (0: all)")->capture_default_str();
    app.add_option("--seed", a.seed, "seed of every preset's render")->capture_default_str();
    app.add_option("--sampler", a.sampler, "independent, sobol or zsobol")
        ->check(CLI::IsMember({"independent", "sobol", "zsobol"}))
        ->capture_default_str();
    app.add_option("--nthold", a.nthold, "relaxation length N_thold")->capture_default_str();
    app.callback([&] {
        a.tev_on = tev_option->count() > 0;
        status = compare_presets(a);
    });
    const int rc = iris::app::run(app, argc, argv);
    return rc != 0 ? rc : status;
}
