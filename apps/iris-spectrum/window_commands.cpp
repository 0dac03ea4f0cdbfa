// iris-spectrum's `windows` subcommand: where the restriction windows of multi_box<3> sit —
// the paper's, placed by hand, and those placed from the emitted spectrum (the `-auto`
// presets; iris/sampling/placement.hpp) — and what share of each display channel's (linear
// sRGB, positive lobes) emitted signal falls inside them at α = 0.
//
//   windows SCENE                 the scene's emitters (and environment), as the renderer sees them
//   windows --spd NAME            one illuminant (`iris-spectrum list`) or blackbody:KELVIN
//
// The automatic windows come from the function the renderer calls, with the scene's
// emitted power (iris/render/emission.hpp), so they are the ones `iris-render --preset
// paper-auto` records as iris:windows.
#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include <fmt/core.h>

#include <iris/render/emission.hpp>
#include <iris/sampling/placement.hpp>
#include <iris/sampling/restriction.hpp>
#if IRIS_HAVE_SCENE
#include <iris/scene/scene.hpp>
#endif

#include "cli.hpp"
#include "commands.hpp"

namespace iris::app {
namespace {

struct window_options {
    std::string scene, spd;
};

std::string share(double v) { return std::isnan(v) ? std::string("    —") : fmt::format("{:5.3f}", v); }

void print_windows(const window_options& o) {
    if (o.scene.empty() == o.spd.empty()) throw usage_error("give a SCENE or --spd NAME (one of them)");
    std::function<double(double)> emitted;
    spectral_domain d;
    std::string what;
#if IRIS_HAVE_SCENE
    std::shared_ptr<scene_desc> scene;
#endif
    if (!o.spd.empty()) {
        emitted = named_emitter(o.spd);
        what = fmt::format("the illuminant {}", o.spd);
    } else {
#if IRIS_HAVE_SCENE
        try {
            scene = std::make_shared<scene_desc>(scene::load_scene(o.scene));
        } catch (const std::exception& e) {
            throw usage_error(e.what());
        }
        d = {scene->lambda_min, scene->lambda_max};
        emitted = [p = std::make_shared<emitted_power>(*scene)](double l) { return (*p)(l); };
        std::string spds;
        for (const auto& n : scene->features().emitter_spds) spds += (spds.empty() ? "" : ", ") + n;
        what = fmt::format("scene {} (emitters: {})", scene->name, spds.empty() ? "none" : spds);
#else
        throw usage_error("this build of iris-spectrum reads no scenes: use --spd NAME");
#endif
    }
    const auto signal = placement::channel_signals(emitted, d);
    const restriction::multi_box<3> hand;
    const auto by_hand = placement::evaluate_windows<3>(signal, d, hand.centres_nm, hand.widths_nm);
    const auto automatic = placement::place_windows<3>(signal, d, hand.centres_nm, hand.widths_nm);
    fmt::print("windows of multibox3 for {}, Λ = {:g}–{:g} nm\n", what, d.min_nm, d.max_nm);
    fmt::print("share of each channel's emitted signal inside the windows at α = 0 (J = Σ log share):\n");
    fmt::print("{:<24} {:<28} {:>6} {:>6} {:>6} {:>8}\n", "placement", "centre:width (nm)", "r̄⁺", "ḡ⁺", "b̄⁺", "J");
    const auto row = [](const char* name, const auto& w) {
        std::string spec;
        for (std::size_t k = 0; k < 3; ++k)
            spec += fmt::format("{}{:g}:{:g}", k ? "," : "", w.centres_nm[k], w.widths_nm[k]);
        fmt::print("{:<24} {:<28} {:>6} {:>6} {:>6} {:>8.3f}\n", name, spec, share(w.captured[0]), share(w.captured[1]),
                   share(w.captured[2]), w.score);
    };
    row("hand (paper)", by_hand);
    if (automatic.placed)
        row("auto (paper-auto)", automatic);
    else
        fmt::print("{:<24} nothing is emitted inside Λ: the -auto presets keep the hand-placed windows\n",
                   "auto (paper-auto)");
}

}  // namespace

void add_window_commands(CLI::App& app) {
    auto o = std::make_shared<window_options>();
    auto* cmd = app.add_subcommand("windows",
                                   "Where multibox3's windows sit, by hand (paper) and placed from the emitted spectrum "
                                   "(paper-auto), and the share of each sRGB channel's signal inside them");
    cmd->add_option("SCENE", o->scene, "built-in scene name or scene JSON file");
    cmd->add_option("--spd", o->spd, "an illuminant (iris-spectrum list) or blackbody:KELVIN instead of a scene");
    cmd->callback([o] { print_windows(*o); });
}

}  // namespace iris::app
