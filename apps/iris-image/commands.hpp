#pragma once
/// \file
/// \brief The subcommands of iris-image, registered by one function.

#include <CLI/CLI.hpp>

namespace iris::app {

/// \brief `diff`, `bias`, `convert`, `crop`, `error-map`, `info`: compare and convert EXR images.
void add_image_commands(CLI::App& app);

}  // namespace iris::app
