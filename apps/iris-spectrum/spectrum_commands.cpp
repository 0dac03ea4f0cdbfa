#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>

#include <iris/spectrum/blackbody.hpp>
#include <iris/spectrum/color.hpp>
#include <iris/spectrum/named.hpp>

#include "cli.hpp"
#include "commands.hpp"
#include "plot.hpp"

namespace iris::app {
namespace {

constexpr double max_kelvin = 1e6;

/// \brief A named emitter spectrum: a built-in illuminant or blackbody:KELVIN.
struct named_spectrum {
    std::string name;
    std::optional<tabulated_spectrum> table;
    std::optional<blackbody_spectrum> blackbody;

    double operator()(double l) const { return table ? (*table)(l) : (*blackbody)(l); }
};

std::string accepted_names() {
    std::string s;
    for (const auto& i : illuminants) s += std::string(i.name) + ", ";
    return s + "or blackbody:KELVIN";
}

named_spectrum resolve(const std::string& name) {
    if (const auto ill = find_illuminant(name)) return {name, ill->spectrum(), std::nullopt};
    constexpr std::string_view prefix = "blackbody:";
    if (name.rfind(prefix, 0) == 0) {
        const double k = parse_number(name.substr(prefix.size()), "blackbody temperature");
        if (!(k > 0.0 && k <= max_kelvin))
            throw usage_error(fmt::format("blackbody temperature must be in (0, {:g}] K, got '{}'", max_kelvin,
                                          name.substr(prefix.size())));
        return {name, std::nullopt, blackbody_spectrum(k)};
    }
    throw usage_error(fmt::format("unknown spectrum '{}'; accepted: {}", name, accepted_names()));
}

void list() {
    fmt::print("illuminants:\n");
    for (const auto& i : illuminants)
        fmt::print("  {:<10} {:.0f}-{:.0f} nm  {}\n", i.name, i.lambda_min,
                   i.lambda_min + i.lambda_step * static_cast<double>(i.values.size() - 1), i.description);
    fmt::print("  blackbody:KELVIN      Planck's law, peak normalised to 1\n");
    fmt::print("glasses (Sellmeier; n_d at 587.5618 nm, Abbe number V_d):\n");
    for (const auto& g : glasses)
        fmt::print("  {:<13} n_d={:.5f} V_d={:.2f}\n", g.name, g.sellmeier.n(fraunhofer_d), abbe_number(g.sellmeier));
}

void print_xyz(const std::string& name) {
    const named_spectrum s = resolve(name);
    const xyz c = normalise_y(spectrum_to_xyz(s));
    const chromaticity_xy xy = chromaticity(c);
    const rgb r = xyz_to_linear_srgb(c);
    fmt::print("X={:.6f} Y={:.6f} Z={:.6f} x={:.6f} y={:.6f} R={:.6f} G={:.6f} B={:.6f}\n", c.x, c.y, c.z, xy.x,
               xy.y, r.r, r.g, r.b);
}

void print_ior(const std::string& glass, const std::string& nm_text, const std::string& model) {
    const auto g = find_glass(glass);
    if (!g) {
        std::string names;
        for (const auto& x : glasses) names += (names.empty() ? "" : ", ") + std::string(x.name);
        throw usage_error(fmt::format("unknown glass '{}'; accepted: {}", glass, names));
    }
    const double nm = parse_number(nm_text, "wavelength (nm)");
    if (!(nm >= cie::cmf_lambda_min && nm <= cie::cmf_lambda_max))
        throw usage_error(fmt::format("wavelength {} nm is outside {:g}-{:g} nm, the range iris renders", nm_text,
                                      cie::cmf_lambda_min, cie::cmf_lambda_max));
    const double n = model == "cauchy" ? g->cauchy.n(nm) : g->sellmeier.n(nm);
    fmt::print("n={:.6f}\n", n);
}

void plot_spds(const std::vector<std::string>& names, const std::string& out) {
    plot p;
    p.title = "Spectral power distributions (each normalised to luminance Y = 1)";
    p.xlabel = "wavelength (nm)";
    p.ylabel = "relative power";
    for (const auto& name : names) {
        const named_spectrum s = resolve(name);
        const double k = white_normalisation(s);
        series line{name, {}, {}};
        for (double l = 380.0; l <= 780.0; l += 1.0) {
            line.x.push_back(l);
            line.y.push_back(k * s(l));
        }
        p.lines.push_back(std::move(line));
    }
    write_plot(p, out);
    fmt::print("wrote {}\n", out);
}

}  // namespace

std::function<double(double)> named_emitter(const std::string& name) {
    auto spd = std::make_shared<named_spectrum>(resolve(name));
    return [spd](double l) { return (*spd)(l); };
}

void add_spectrum_commands(CLI::App& app) {
    // Option storage lives as long as the callbacks that read it (shared ownership).
    struct options {
        std::string name, glass, nm, model = "sellmeier", out;
        std::vector<std::string> names;
    };
    auto o = std::make_shared<options>();

    app.add_subcommand("list", "List the illuminants and glasses known to iris")->callback(list);

    auto* xyz_cmd = app.add_subcommand("xyz", "Print X Y Z x y R G B (Y = 1, linear sRGB) of an illuminant");
    xyz_cmd->add_option("NAME", o->name, "illuminant name or blackbody:KELVIN")->required();
    xyz_cmd->callback([o] { print_xyz(o->name); });

    auto* ior_cmd = app.add_subcommand("ior", "Print the refractive index n of a catalogue glass at a wavelength");
    ior_cmd->add_option("GLASS", o->glass, "glass name (see `iris-spectrum list`)")->required();
    ior_cmd->add_option("NM", o->nm, "wavelength in nm (360-830)")->required();
    ior_cmd->add_option("--model", o->model, "dispersion model: sellmeier (catalogue) or cauchy (two-term fit)")
        ->check(CLI::IsMember({"sellmeier", "cauchy"}))
        ->capture_default_str();
    ior_cmd->callback([o] { print_ior(o->glass, o->nm, o->model); });

    auto* plot_cmd = app.add_subcommand("plot", "Plot SPDs (normalised to Y = 1) to a PNG with gnuplot");
    plot_cmd->add_option("NAME", o->names, "illuminant names or blackbody:KELVIN")->required();
    plot_cmd->add_option("-o,--output", o->out, "output PNG file")->required();
    plot_cmd->callback([o] { plot_spds(o->names, o->out); });
}

}  // namespace iris::app
