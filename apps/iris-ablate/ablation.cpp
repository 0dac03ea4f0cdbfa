#include "ablation.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>

#include <unistd.h>

#include <fmt/core.h>

#include <iris/exr/exr.hpp>
#include <iris/hash.hpp>
#include <iris/metrics/flip.hpp>
#include <iris/metrics/metrics.hpp>
#include <iris/renderer/renderer.hpp>
#include <iris/scene/scene.hpp>
#include <iris/version.hpp>

#include "cli.hpp"

namespace iris::app {
namespace {

namespace fs = std::filesystem;

/// \brief Seed of the reference render: far from the evaluated seeds 1..K, so the
/// reference's noise is independent of every evaluated image's.
constexpr std::uint64_t reference_seed = 0x5eed0f0ddull;

std::string file_safe(std::string s) {
    for (char& c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_')) c = '_';
    return s;
}

/// \brief Every byte of a file into `h` (nothing if it cannot be read).
void add_file(fnv1a& h, const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<char> buf(1 << 16);
    while (in.read(buf.data(), static_cast<std::streamsize>(buf.size())) || in.gcount() > 0)
        h.add(buf.data(), static_cast<std::size_t>(in.gcount()));
}

/// \brief What the cached reference depends on besides size, spp and seed: the scene's
/// content (its JSON text and every triangle, so an edited file or mesh is a new scene)
/// and the code that renders it (this executable's bytes: any change to iris gives a new
/// key, where a version string would go stale between releases).
std::uint64_t reference_key(const scene_desc& scene, const std::string& name_or_path) {
    fnv1a f;
    if (const auto text = iris::scene::builtin_scene_text(name_or_path))
        f.add(*text);
    else
        add_file(f, name_or_path);
    for (const auto& sh : scene.shapes) {
        f.add(sh.mesh.positions.data(), sh.mesh.positions.size() * sizeof(sh.mesh.positions[0]));
        f.add(sh.mesh.triangles.data(), sh.mesh.triangles.size() * sizeof(sh.mesh.triangles[0]));
    }
    add_file(f, "/proc/self/exe");
    return f.value();
}

/// \brief Progress over the whole run (all references and renders), with ETA.
class progress {
public:
    explicit progress(double total_passes) : m_total(total_passes), m_tty(::isatty(STDERR_FILENO) != 0) {}
    void step(const std::string& what, int spp, double pass_weight = 1.0) {
        m_done += pass_weight;
        if (!m_tty) return;
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
        const double frac = std::min(1.0, m_done / m_total);
        const double eta = frac > 0 ? elapsed / frac * (1.0 - frac) : 0.0;
        fmt::print(stderr, "\r{:<32} {:>6} spp   overall {:5.1f} %   ETA {:.0f} s      ", what, spp, 100.0 * frac, eta);
    }
    void line(const std::string& msg) {
        if (m_tty) fmt::print(stderr, "\r{:<90}\r", "");
        fmt::print(stderr, "{}\n", msg);
    }

private:
    double m_total, m_done = 0.0;
    bool m_tty;
    std::chrono::steady_clock::time_point m_start = std::chrono::steady_clock::now();
};

/// \brief A reference rendered elsewhere (`--reference FILE.exr`, e.g. on a cluster): it must
/// have the run's size and, if it says which scene it is (iris:scene), be of this scene.
/// \throws usage_error naming the file and the mismatch
image external_reference(const scene_desc& scene, const ablation_options& opt, int w, int h, std::string& source) {
    exr::loaded ref;
    try {
        ref = exr::read(opt.reference_file);
    } catch (const exr::error& e) {
        throw usage_error(fmt::format("--reference: {}", e.what()));
    }
    const auto& px = ref.pixels;
    if (px.width() != w || px.height() != h)
        throw usage_error(fmt::format("--reference {}: the image is {}x{}, the run is {}x{} (--width/--height)",
                                      opt.reference_file.string(), px.width(), px.height(), w, h));
    const auto attr = [&](const char* key) {
        const auto it = ref.meta.find(key);
        return it == ref.meta.end() ? std::string() : it->second;
    };
    if (const auto s = attr("iris:scene"); !s.empty() && s != scene.name)
        throw usage_error(fmt::format("--reference {}: rendered from scene '{}', the run is of '{}'",
                                      opt.reference_file.string(), s, scene.name));
    const auto or_unknown = [](const std::string& v) { return v.empty() ? std::string("unknown") : v; };
    source = fmt::format("`{}` (given with --reference; its header: preset {}, {} spp, sampler {}, seed {}, iris {})",
                         opt.reference_file.string(), or_unknown(attr("iris:preset")), or_unknown(attr("iris:spp")),
                         or_unknown(attr("iris:sampler")), or_unknown(attr("iris:seed")), or_unknown(attr("iris:version")));
    return px;
}

image reference_image(const scene_desc& scene, const ablation_options& opt, int w, int h, progress& prog) {
    // (the path tracer's keys are as before the estimator became a choice, so old caches stay valid)
    const std::string est = opt.ref_estimator() == "nee-mis" ? std::string() : "-" + opt.ref_estimator();
    const std::string key = fmt::format("{}-{:016x}-{}x{}-ref{}-{}{}-seed{:x}-v{}", file_safe(scene.name),
                                        reference_key(scene, opt.scene), w, h, opt.reference_spp, opt.ref_sampler(), est,
                                        reference_seed, iris::version);
    const fs::path cached = opt.cache / (key + ".exr");
    if (fs::exists(cached)) {
        try {
            auto img = exr::read(cached).pixels;
            if (img.width() == w && img.height() == h) {
                prog.step("reference (cached)", opt.reference_spp, opt.reference_spp);
                prog.line(fmt::format("reference: {} (cached)", cached.string()));
                return img;
            }
        } catch (const exr::error&) {
            // unreadable cache entry: render it again
        }
    }
    renderer::options ro;
    ro.preset = "hwss";
    ro.spp = opt.reference_spp;
    ro.seed = reference_seed;
    ro.threads = opt.threads;
    ro.width = w;
    ro.height = h;
    ro.nthold = opt.nthold;
    ro.sampler = opt.ref_sampler();
    ro.estimator = opt.ref_estimator();
    film f(w, h);
    renderer::hooks hk;
    hk.on_pass = [&](const film&, const renderer::status& st) {
        prog.step("reference hwss", st.spp_done);
        return true;
    };
    const auto st = renderer::render(scene, ro, f, hk);
    image img = f.to_image();
    std::error_code ec;
    fs::create_directories(opt.cache, ec);
    if (!ec) {
        exr::write(cached, img,
                   {{"iris:scene", scene.name}, {"iris:preset", "hwss"}, {"iris:sampler", opt.ref_sampler()},
                    {"iris:estimator", opt.ref_estimator()},
                    {"iris:spp", std::to_string(st.spp_done)},
                    {"iris:seed", std::to_string(reference_seed)}, {"iris:version", std::string(iris::version)}});
        prog.line(fmt::format("reference: {} spp in {:.1f} s, cached as {}", st.spp_done, st.seconds, cached.string()));
    }
    return img;
}

}  // namespace

ablation_result run_ablation(const ablation_options& opt) {
    for (const auto& p : opt.presets) {
        try {
            (void)renderer::config_name(p);
        } catch (const std::invalid_argument& e) {
            throw usage_error(e.what());
        }
    }
    scene_desc scene;
    try {
        scene = scene::load_scene(opt.scene);
    } catch (const std::exception& e) {
        throw usage_error(e.what());
    }
    const int w = opt.width > 0 ? opt.width : scene.camera.width;
    const int h = opt.height > 0 ? opt.height : scene.camera.height;
    // SSIM (results.csv, the plots) needs one whole window; below it the SSIM plots have
    // no defined point and gnuplot fails after the whole run
    if (w < ssim_window || h < ssim_window)
        throw usage_error(fmt::format("the image must be at least {0}x{0} pixels (one SSIM window), got {1}x{2}",
                                      ssim_window, w, h));
    (void)crop_rectangle(opt.crop, w, h);  // a bad --crop fails now, not after the renders
    ablation_result result;
    if (!opt.reference_file.empty()) {  // and so does a bad --reference
        result.reference = external_reference(scene, opt, w, h, result.reference_source);
        fmt::print(stderr, "reference: {} (given)\n", opt.reference_file.string());
    }
    std::error_code ec;
    fs::create_directories(opt.out / "snapshots", ec);
    if (ec) throw usage_error(fmt::format("cannot create output directory '{}': {}", opt.out.string(), ec.message()));
    const int max_spp = opt.spp.back();

    // work estimate in passes (time-equal renders count their largest budget's passes as they go)
    progress prog((opt.reference_file.empty() ? static_cast<double>(opt.reference_spp) : 0.0) +
                  static_cast<double>(opt.presets.size()) * opt.seeds * max_spp);
    if (opt.reference_file.empty()) {
        result.reference = reference_image(scene, opt, w, h, prog);
        result.reference_source =
            fmt::format("`hwss`, {} spp, sampler `{}`, estimator `{}`", opt.reference_spp, opt.ref_sampler(), opt.ref_estimator());
    }
    // HDR-ꟻLIP takes its exposures from the reference; one whose median pixel is black has none
    bool flip_exposures_ok = true;
    try {
        (void)flip_exposure_range(result.reference);
    } catch (const std::invalid_argument& e) {
        flip_exposures_ok = false;
        fmt::print(stderr, "iris-ablate: note: no FLIP column: {}\n", e.what());
    }

    for (const auto& preset : opt.presets) {
        for (int seed = 1; seed <= opt.seeds; ++seed) {
            renderer::options ro;
            ro.preset = preset;
            ro.seed = static_cast<std::uint64_t>(seed);
            ro.threads = opt.threads;
            ro.nthold = opt.nthold;
            ro.width = w;
            ro.height = h;
            ro.sampler = opt.sampler;
            ro.estimator = opt.estimator;
            ro.spp = opt.budgets.empty() ? max_spp : 10'000'000;  // time-equal: stop by budget
            std::size_t next_spp = 0, next_budget = 0;
            film f(w, h);
            renderer::hooks hk;
            hk.on_pass = [&](const film& film_now, const renderer::status& st) {
                prog.step(fmt::format("{} seed {}", preset, seed), st.spp_done, st.spp_done <= max_spp ? 1.0 : 0.0);
                auto row = [&](double budget) {
                    const image img = film_now.to_image();
                    const auto m = compare(img, result.reference);
                    double flip = std::numeric_limits<double>::quiet_NaN();
                    if (flip_exposures_ok) flip = flip_hdr(img, result.reference);
                    return std::pair{ablation_row{scene.name, preset, opt.sampler, seed, st.spp_done, st.seconds, m.mse, m.relmse,
                                                  m.ssim, budget, flip},
                                     img};
                };
                if (next_spp < opt.spp.size() && st.spp_done == opt.spp[next_spp]) {
                    auto [r, img] = row(0.0);
                    result.spp_rows.push_back(r);
                    exr::write(opt.out / "snapshots" / fmt::format("{}-seed{}-{}spp.exr", file_safe(preset), seed, st.spp_done),
                               img, {{"iris:scene", scene.name}, {"iris:preset", preset}, {"iris:sampler", opt.sampler},
                                     {"iris:spp", std::to_string(st.spp_done)}, {"iris:seed", std::to_string(seed)},
                                     {"iris:seconds", fmt::format("{:.3f}", st.seconds)}});
                    if (next_spp == 0 && seed == 1) result.first_snapshots.emplace_back(preset, img);
                    ++next_spp;
                }
                while (next_budget < opt.budgets.size() && st.seconds >= opt.budgets[next_budget]) {
                    result.time_rows.push_back(row(opt.budgets[next_budget]).first);
                    ++next_budget;
                }
                return next_spp < opt.spp.size() || next_budget < opt.budgets.size();
            };
            const auto st = renderer::render(scene, ro, f, hk);
            prog.line(fmt::format("{} seed {}: {} spp in {:.2f} s ({} NaN/Inf dropped)", preset, seed, st.spp_done,
                                  st.seconds, st.nan_inf));
        }
    }
    return result;
}

}  // namespace iris::app
