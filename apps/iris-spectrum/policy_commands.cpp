// iris-spectrum's sampling-policy subcommands: look at what a preset's restricted
// wavelength pdf p_α does.
//
//   pdf --preset NAME (--alpha A | --iteration I [--nthold N]) [--step NM]
//       CSV `lambda,pdf`: p_α on the preset's domain (380–780 nm) every NM nm (default 1),
//       α given directly or as α_I = curve(min(1, I / N)) (N default 512).
//   sample --preset NAME (--alpha A | --iteration I [--nthold N]) --count N [--seed S]
//       CSV `lambda,pdf`: N hero-rotated draws of C wavelengths each (C rows per draw,
//       the hero first), pdf = p_α(λ); S (default 1) keys the counter-based generator.
//   plot-pdf --preset NAME -o FILE.png [--step NM]
//       p_α for α = 0, 0.25, 0.5, 0.75, 1 in one plot (gnuplot; default step 0.5 nm).
//
// NAME is a preset's CLI name (`iris-spectrum presets`) or its config name. Bad values
// (α outside [0, 1], count ≤ 0, unknown preset, …): one line on stderr, exit status 2.
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <fmt/format.h>

#include <iris/sampling/presets.hpp>
#include <iris/sampling/random.hpp>

#include "cli.hpp"
#include "commands.hpp"
#include "plot.hpp"

namespace iris::app {
namespace {

struct policy_options {
    std::string preset;
    std::string alpha, iteration, nthold = "512", step, count, seed = "1", out;
};

void check_preset(const std::string& name) {
    for (const auto& n : preset_names())
        if (n == name) return;
    for (const auto& n : preset_config_names())
        if (n == name) return;
    throw usage_error(unknown_preset_message(name));
}

/// \brief A non-negative integer option, or usage_error naming it.
std::uint64_t parse_count(const std::string& text, const std::string& what, std::uint64_t min, std::uint64_t max) {
    const double v = parse_number(text, what);
    if (!(v >= static_cast<double>(min) && v <= static_cast<double>(max)) || v != std::floor(v))
        throw usage_error(fmt::format("{} must be an integer in [{}, {}], got '{}'", what, min, max, text));
    return static_cast<std::uint64_t>(v);
}

/// \brief How α is chosen: directly, or from a sample index and N_thold.
struct alpha_choice {
    bool direct = true;
    float alpha = 0.0f;
    std::uint64_t iteration = 0;
    std::uint32_t n_thold = 512;
};

alpha_choice parse_alpha(const policy_options& o) {
    alpha_choice c;
    if (!o.alpha.empty() && !o.iteration.empty()) throw usage_error("give either --alpha or --iteration, not both");
    if (!o.alpha.empty()) {
        const double a = parse_number(o.alpha, "--alpha");
        if (!(a >= 0.0 && a <= 1.0)) throw usage_error(fmt::format("--alpha must be in [0, 1], got '{}'", o.alpha));
        c.alpha = static_cast<float>(a);
        return c;
    }
    if (o.iteration.empty()) throw usage_error("give --alpha A (in [0, 1]) or --iteration I (with --nthold N)");
    c.direct = false;
    c.iteration = parse_count(o.iteration, "--iteration", 0, std::uint64_t{1} << 53);
    c.n_thold = static_cast<std::uint32_t>(parse_count(o.nthold, "--nthold", 1, std::numeric_limits<std::uint32_t>::max()));
    return c;
}

double parse_step(const std::string& text, double fallback) {
    if (text.empty()) return fallback;
    const double s = parse_number(text, "--step");
    if (!(s >= 1e-3 && s <= 400.0)) throw usage_error(fmt::format("--step must be in [0.001, 400] nm, got '{}'", text));
    return s;
}

/// \brief The preset's configuration with the sample index → α mapping applied.
template <class P>
float alpha_of(P& cfg, const alpha_choice& c) {
    if (c.direct) return c.alpha;
    cfg.params.n_thold = c.n_thold;
    return cfg.alpha(c.iteration);
}

/// \brief λ_k = min + k·step, k = 0, 1, … while λ_k ≤ max (to 1e-9 nm).
std::vector<double> wavelength_grid(const spectral_domain& d, double step) {
    std::vector<double> l;
    const double w = static_cast<double>(d.max_nm) - static_cast<double>(d.min_nm);
    for (std::uint64_t k = 0; static_cast<double>(k) * step <= w + 1e-9; ++k)
        l.push_back(static_cast<double>(d.min_nm) + static_cast<double>(k) * step);
    return l;
}

void print_pdf(const policy_options& o) {
    check_preset(o.preset);
    const alpha_choice choice = parse_alpha(o);
    const double step = parse_step(o.step, 1.0);
    dispatch_preset(o.preset, [&]<class P>() {
        P cfg;
        const auto dist = cfg.distribution(alpha_of(cfg, choice));
        fmt::memory_buffer out;
        fmt::format_to(std::back_inserter(out), "lambda,pdf\n");
        for (double l : wavelength_grid(cfg.params.domain, step))
            fmt::format_to(std::back_inserter(out), "{:.10g},{}\n", l, dist.pdf(static_cast<float>(l)));
        std::fwrite(out.data(), 1, out.size(), stdout);
    });
}

void print_samples(const policy_options& o) {
    check_preset(o.preset);
    const alpha_choice choice = parse_alpha(o);
    if (o.count.empty()) throw usage_error("--count N (draws, > 0) is required");
    const double count_value = parse_number(o.count, "--count");
    if (!(count_value >= 1.0)) throw usage_error(fmt::format("--count must be > 0, got '{}'", o.count));
    const std::uint64_t count = parse_count(o.count, "--count", 1, 100000000);
    const std::uint64_t seed = parse_count(o.seed, "--seed", 0, std::uint64_t{1} << 53);
    dispatch_preset(o.preset, [&]<class P>() {
        P cfg;
        const auto dist = cfg.distribution(alpha_of(cfg, choice));
        counter_rng rng(seed);
        fmt::memory_buffer out;
        fmt::format_to(std::back_inserter(out), "lambda,pdf\n");
        for (std::uint64_t n = 0; n < count; ++n) {
            const auto wl = dist.template sample_wavelengths<P::wavelength_count>(rng.next());
            for (std::size_t j = 0; j < P::wavelength_count; ++j)
                fmt::format_to(std::back_inserter(out), "{},{}\n", wl[j], wl.pdf(j));
            if (out.size() > (1u << 20)) {
                std::fwrite(out.data(), 1, out.size(), stdout);
                out.clear();
            }
        }
        std::fwrite(out.data(), 1, out.size(), stdout);
    });
}

void plot_pdf(const policy_options& o) {
    check_preset(o.preset);
    const double step = parse_step(o.step, 0.5);
    plot p;
    p.xlabel = "wavelength (nm)";
    p.ylabel = "p_α(λ) (1/nm)";
    dispatch_preset(o.preset, [&]<class P>() {
        P cfg;
        p.title = fmt::format("Restricted wavelength pdf of '{}' ({})", P::cli_name, P::name);
        for (float a : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
            const auto dist = cfg.distribution(a);
            series s{fmt::format("α = {:g} (Z = {:.3g})", a, dist.normalisation()), {}, {}};
            for (double l : wavelength_grid(cfg.params.domain, step)) {
                s.x.push_back(l);
                s.y.push_back(dist.pdf(static_cast<float>(l)));
            }
            p.lines.push_back(std::move(s));
        }
    });
    write_plot(p, o.out);
    fmt::print("wrote {}\n", o.out);
}

void list_presets() {
    fmt::print("presets (CLI name, config name kernel/curve/C/bias[/base pdf]):\n");
    for_each_preset([]<class P>() { fmt::print("  {:<16} {}\n", P::cli_name, P::name); });
}

}  // namespace

void add_policy_commands(CLI::App& app) {
    auto o = std::make_shared<policy_options>();
    const std::string preset_help = "preset name (`iris-spectrum presets`) or config name";
    auto alpha_options = [&](CLI::App* cmd) {
        cmd->add_option("--alpha", o->alpha, "restriction extent α in [0, 1]");
        cmd->add_option("--iteration", o->iteration, "0-based sample index I: α = curve(min(1, I / N_thold))");
        cmd->add_option("--nthold", o->nthold, "N_thold for --iteration")->capture_default_str();
    };

    app.add_subcommand("presets", "List the sampling presets")->callback(list_presets);

    auto* pdf = app.add_subcommand("pdf", "Print the restricted wavelength pdf p_α of a preset as CSV (lambda,pdf)");
    pdf->add_option("--preset", o->preset, preset_help)->required();
    alpha_options(pdf);
    pdf->add_option("--step", o->step, "wavelength step in nm (default 1)");
    pdf->callback([o] { print_pdf(*o); });

    auto* sample = app.add_subcommand("sample", "Draw hero-rotated wavelengths from p_α as CSV (lambda,pdf), C rows per draw");
    sample->add_option("--preset", o->preset, preset_help)->required();
    alpha_options(sample);
    sample->add_option("--count", o->count, "number of draws (> 0)");
    sample->add_option("--seed", o->seed, "seed of the counter-based generator")->capture_default_str();
    sample->callback([o] { print_samples(*o); });

    auto* plot_cmd = app.add_subcommand("plot-pdf", "Plot p_α for α = 0, 0.25, 0.5, 0.75, 1 to a PNG (gnuplot)");
    plot_cmd->add_option("--preset", o->preset, preset_help)->required();
    plot_cmd->add_option("-o,--output", o->out, "output PNG file")->required();
    plot_cmd->add_option("--step", o->step, "wavelength step in nm (default 0.5)");
    plot_cmd->callback([o] { plot_pdf(*o); });
}

}  // namespace iris::app
