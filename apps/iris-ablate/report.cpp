#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <iris/exr/exr.hpp>

#include "ablation.hpp"
#include "cli.hpp"
#include "plot.hpp"

namespace iris::app {
namespace {

namespace fs = std::filesystem;

struct stat {
    double mean = 0, std = 0;
    int n = 0;
};

stat summarise(const std::vector<double>& v) {
    stat s;
    s.n = static_cast<int>(v.size());
    if (v.empty()) return s;
    for (double x : v) s.mean += x;
    s.mean /= s.n;
    if (s.n > 1) {
        for (double x : v) s.std += (x - s.mean) * (x - s.mean);
        s.std = std::sqrt(s.std / (s.n - 1));
    }
    return s;
}

/// \brief rows grouped by (preset, x) where x is spp or the budget.
using grouped = std::map<std::string, std::map<double, std::vector<const ablation_row*>>>;

grouped group(const std::vector<ablation_row>& rows, bool by_budget) {
    grouped g;
    for (const auto& r : rows) g[r.preset][by_budget ? r.budget : static_cast<double>(r.spp)].push_back(&r);
    return g;
}

void write_csv(const fs::path& path, const std::vector<ablation_row>& rows, bool with_budget) {
    exr::write_atomically(path, [&](const fs::path& tmp) {
        std::ofstream o(tmp);
        o << "scene,preset,sampler,seed,spp,seconds,mse,relmse,ssim,flip" << (with_budget ? ",budget" : "") << "\n";
        for (const auto& r : rows) {
            o << fmt::format("{},{},{},{},{},{:.6f},{:.9g},{:.9g},{:.9g},{:.9g}", r.scene, r.preset, r.sampler, r.seed, r.spp,
                             r.seconds, r.mse, r.relmse, r.ssim, r.flip);
            if (with_budget) o << fmt::format(",{:g}", r.budget);
            o << "\n";
        }
        if (!o) throw std::runtime_error("cannot write " + path.string());
    });
}

/// \brief The metrics plotted against spp and time.
enum class metric { ssim, mse, flip };

void metric_plot(const grouped& g, const std::vector<std::string>& order, bool seconds_axis, metric which,
                 const std::string& scene, const fs::path& out) {
    static constexpr const char* names[] = {"SSIM", "MSE", "FLIP"};
    static constexpr const char* labels[] = {"SSIM (higher is better)", "MSE (lower is better)",
                                             "mean HDR-FLIP (lower is better)"};
    const auto k = static_cast<std::size_t>(which);
    plot p;
    p.title = fmt::format("{}: {} vs {}", scene, names[k], seconds_axis ? "time" : "samples per pixel");
    p.xlabel = seconds_axis ? "seconds" : "samples per pixel";
    p.ylabel = labels[k];
    p.log_x = true;
    p.log_y = which != metric::ssim;
    p.points = true;
    for (const auto& preset : order) {
        const auto it = g.find(preset);
        if (it == g.end()) continue;
        series s{preset, {}, {}};
        for (const auto& [x, rows] : it->second) {
            std::vector<double> xs, ys;
            for (const auto* r : rows) {
                xs.push_back(seconds_axis ? r->seconds : x);
                ys.push_back(which == metric::ssim ? r->ssim : which == metric::mse ? r->mse : r->flip);
            }
            s.x.push_back(summarise(xs).mean);
            s.y.push_back(summarise(ys).mean);
        }
        p.lines.push_back(std::move(s));
    }
    write_plot(p, out);
}

/// \brief Reference and each preset's crop at the smallest spp, side by side (scaled up
/// by pixel replication to at least 160 px tall so the noise is visible).
void write_crops(const ablation_options& opt, const ablation_result& r, const fs::path& out) {
    const image& ref = r.reference;
    const auto [cx, cy, cw, ch] = crop_rectangle(opt.crop, ref.width(), ref.height());
    const int scale = std::max(1, 160 / std::max(1, ch));
    const int gap = 4;
    const int panels = 1 + static_cast<int>(r.first_snapshots.size());
    image sheet(panels * cw * scale + (panels - 1) * gap, ch * scale);
    auto blit = [&](const image& img, int panel) {
        const int x0 = panel * (cw * scale + gap);
        for (int y = 0; y < ch * scale; ++y)
            for (int x = 0; x < cw * scale; ++x) sheet(x0 + x, y) = img(cx + x / scale, cy + y / scale);
    };
    blit(ref, 0);
    for (std::size_t i = 0; i < r.first_snapshots.size(); ++i) blit(r.first_snapshots[i].second, static_cast<int>(i) + 1);
    exr::write_png(out, sheet);
}

}  // namespace

crop_rect crop_rectangle(const std::string& crop, int width, int height) {
    if (crop.empty()) return {width / 4, height / 4, width / 2, height / 2};
    std::stringstream ss(crop);
    std::string part;
    std::vector<double> v;
    while (std::getline(ss, part, ',')) v.push_back(parse_number(part, "--crop entry"));
    const bool integers = std::all_of(v.begin(), v.end(), [](double x) { return x == std::floor(x) && std::abs(x) < 1e9; });
    if (v.size() != 4 || !integers || v[0] < 0 || v[1] < 0 || v[2] < 1 || v[3] < 1 || v[0] + v[2] > width ||
        v[1] + v[3] > height)
        throw usage_error(fmt::format("--crop '{}' must be integers x,y,w,h inside the {}x{} image", crop, width, height));
    return {static_cast<int>(v[0]), static_cast<int>(v[1]), static_cast<int>(v[2]), static_cast<int>(v[3])};
}

void write_report(const ablation_options& opt, const ablation_result& r) {
    const std::string scene = r.spp_rows.empty() ? opt.scene : r.spp_rows.front().scene;
    write_csv(opt.out / "results.csv", r.spp_rows, false);
    if (!r.time_rows.empty()) write_csv(opt.out / "results_time.csv", r.time_rows, true);

    const auto by_spp = group(r.spp_rows, false);
    const bool has_flip = !r.spp_rows.empty() && !std::isnan(r.spp_rows.front().flip);
    metric_plot(by_spp, opt.presets, false, metric::ssim, scene, opt.out / "ssim_vs_spp.png");
    metric_plot(by_spp, opt.presets, false, metric::mse, scene, opt.out / "mse_vs_spp.png");
    if (has_flip) metric_plot(by_spp, opt.presets, false, metric::flip, scene, opt.out / "flip_vs_spp.png");
    // vs seconds: the time-equal snapshots when there are any, else the spp snapshots' times
    const auto by_time = r.time_rows.empty() ? by_spp : group(r.time_rows, true);
    metric_plot(by_time, opt.presets, true, metric::ssim, scene, opt.out / "ssim_vs_seconds.png");
    metric_plot(by_time, opt.presets, true, metric::mse, scene, opt.out / "mse_vs_seconds.png");
    if (has_flip) metric_plot(by_time, opt.presets, true, metric::flip, scene, opt.out / "flip_vs_seconds.png");
    write_crops(opt, r, opt.out / fmt::format("crops_{}spp.png", opt.spp.front()));

    // summary.md
    std::string md = fmt::format("# Ablation: {}\n\n", scene);
    md += fmt::format("Reference: {}. Sampler of the renders: `{}`, estimator `{}`. Seeds: {}. Size: {}x{}. "
                      "N_thold = {}. Mean ± standard deviation over seeds; gain = SSIM relative to `hwss` at the same "
                      "spp.\n\n",
                      r.reference_source, opt.sampler, opt.estimator, opt.seeds, r.reference.width(), r.reference.height(), opt.nthold);
    md += "| spp | preset | SSIM | SSIM gain vs hwss | MSE | MSE vs hwss | relMSE | FLIP | seconds |\n"
          "|---|---|---|---|---|---|---|---|---|\n";
    for (int spp : opt.spp) {
        const auto base_it = by_spp.find("hwss");
        stat base_ssim, base_mse;
        if (base_it != by_spp.end() && base_it->second.count(spp)) {
            std::vector<double> s, m;
            for (const auto* row : base_it->second.at(spp)) {
                s.push_back(row->ssim);
                m.push_back(row->mse);
            }
            base_ssim = summarise(s);
            base_mse = summarise(m);
        }
        for (const auto& preset : opt.presets) {
            const auto it = by_spp.find(preset);
            if (it == by_spp.end() || !it->second.count(spp)) continue;
            std::vector<double> s, m, rm, fl, sec, gain;
            const auto& rows = it->second.at(spp);
            for (std::size_t i = 0; i < rows.size(); ++i) {
                s.push_back(rows[i]->ssim);
                m.push_back(rows[i]->mse);
                rm.push_back(rows[i]->relmse);
                fl.push_back(rows[i]->flip);
                sec.push_back(rows[i]->seconds);
                if (base_it != by_spp.end() && base_it->second.count(spp) && i < base_it->second.at(spp).size())
                    gain.push_back(100.0 * (rows[i]->ssim / base_it->second.at(spp)[i]->ssim - 1.0));  // paired by seed
            }
            const auto ss = summarise(s), ms = summarise(m), rs = summarise(rm), ts = summarise(sec), gs = summarise(gain);
            const auto fs_ = summarise(fl);
            md += fmt::format("| {} | {} | {:.4f} ± {:.4f} | {} | {:.4g} ± {:.2g} | {} | {:.4g} | {} | {:.2f} |\n", spp, preset,
                              ss.mean, ss.std, gain.empty() ? "—" : fmt::format("{:+.1f} % ± {:.1f}", gs.mean, gs.std),
                              ms.mean, ms.std,
                              base_mse.n ? fmt::format("{:+.1f} %", 100.0 * (ms.mean / base_mse.mean - 1.0)) : "—",
                              rs.mean, has_flip ? fmt::format("{:.4f} ± {:.4f}", fs_.mean, fs_.std) : "—", ts.mean);
        }
    }
    if (!r.time_rows.empty()) {
        md += "\n## Time-equal\n\n| budget (s) | preset | spp reached | SSIM | MSE | FLIP |\n|---|---|---|---|---|---|\n";
        const auto by_budget = group(r.time_rows, true);
        for (double b : opt.budgets)
            for (const auto& preset : opt.presets) {
                const auto it = by_budget.find(preset);
                if (it == by_budget.end() || !it->second.count(b)) continue;
                std::vector<double> s, m, n, f;
                for (const auto* row : it->second.at(b)) {
                    s.push_back(row->ssim);
                    m.push_back(row->mse);
                    n.push_back(row->spp);
                    f.push_back(row->flip);
                }
                md += fmt::format("| {:g} | {} | {:.0f} | {:.4f} ± {:.4f} | {:.4g} | {} |\n", b, preset, summarise(n).mean,
                                  summarise(s).mean, summarise(s).std, summarise(m).mean,
                                  has_flip ? fmt::format("{:.4f}", summarise(f).mean) : "—");
            }
    }
    md += fmt::format("\nFLIP: mean HDR-FLIP against the reference (docs/metrics.md; lower is better).\n"
                      "Plots: `ssim_vs_spp.png`, `mse_vs_spp.png`, `flip_vs_spp.png`, `ssim_vs_seconds.png`, "
                      "`mse_vs_seconds.png`, `flip_vs_seconds.png`; "
                      "crops at {} spp (reference first, then {}): `crops_{}spp.png`.\n",
                      opt.spp.front(), fmt::format("{}", fmt::join(opt.presets, ", ")), opt.spp.front());
    exr::write_atomically(opt.out / "summary.md", [&](const fs::path& tmp) {
        std::ofstream o(tmp);
        o << md;
    });
    fmt::print("{}", md);
}

}  // namespace iris::app
