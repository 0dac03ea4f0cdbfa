#pragma once
/// \file
/// \brief The subcommand families of iris-spectrum, each registered by one function.

#include <functional>
#include <string>

#include <CLI/CLI.hpp>

namespace iris::app {

/// \brief `list`, `xyz`, `ior`, `plot`: the spectra and glasses compiled into iris.
void add_spectrum_commands(CLI::App& app);

/// \brief `presets`, `pdf`, `sample`, `plot-pdf`: what a sampling preset's restricted
/// wavelength pdf does (policy_commands.cpp).
void add_policy_commands(CLI::App& app);

/// \brief `windows`: where the restriction windows sit, by hand and placed automatically
/// from a scene's or an illuminant's emitted spectrum (window_commands.cpp).
void add_window_commands(CLI::App& app);

/// \brief A built-in illuminant or blackbody:KELVIN as a function of λ (nm). \throws usage_error
std::function<double(double)> named_emitter(const std::string& name);

}  // namespace iris::app
