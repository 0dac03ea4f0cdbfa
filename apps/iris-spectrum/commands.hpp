#pragma once
/// \file
/// \brief The subcommand families of iris-spectrum, each registered by one function.

#include <CLI/CLI.hpp>

namespace iris::app {

/// \brief `list`, `xyz`, `ior`, `plot`: the spectra and glasses compiled into iris.
void add_spectrum_commands(CLI::App& app);

/// \brief `presets`, `pdf`, `sample`, `plot-pdf`: what a sampling preset's restricted
/// wavelength pdf does (policy_commands.cpp).
void add_policy_commands(CLI::App& app);

}  // namespace iris::app
