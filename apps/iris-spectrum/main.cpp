// iris-spectrum — inspect the spectra, glasses and sampling policies compiled into iris.
//
//   iris-spectrum list                      illuminants and glasses known to iris
//   iris-spectrum xyz NAME                  XYZ, xy and linear sRGB of an illuminant (Y = 1)
//   iris-spectrum ior GLASS NM [--model M]  refractive index (sellmeier | cauchy)
//   iris-spectrum plot NAME... -o FILE.png  plot of SPDs, each normalised to luminance 1
//   iris-spectrum presets                   the sampling presets (CLI and config names)
//   iris-spectrum pdf --preset P (--alpha A | --iteration I [--nthold N]) [--step NM]
//                                           CSV lambda,pdf of the restricted pdf p_α
//   iris-spectrum sample --preset P --alpha A --count N [--seed S]
//                                           CSV lambda,pdf of N draws of C wavelengths
//   iris-spectrum plot-pdf --preset P -o FILE.png   p_α for α = 0, .25, .5, .75, 1
//   iris-spectrum windows SCENE | --spd NAME    multibox3's windows by hand and placed from
//                                           the emitted spectrum, with each channel's share
//
// NAME is a built-in illuminant (`iris-spectrum list`) or blackbody:KELVIN.
// Bad input: one line on stderr, exit status 2.
#include <fmt/core.h>

#include <iris/version.hpp>

#include "cli.hpp"
#include "commands.hpp"

int main(int argc, char** argv) {
    CLI::App app{"iris-spectrum: inspect the spectra, glasses and sampling policies of iris", "iris-spectrum"};
    app.set_version_flag("--version", std::string(iris::version));
    app.require_subcommand(1);
    iris::app::add_spectrum_commands(app);
    iris::app::add_policy_commands(app);
    iris::app::add_window_commands(app);
    return iris::app::run(app, argc, argv);
}
