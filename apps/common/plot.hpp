#pragma once
/// \file
/// \brief Line plots rendered to PNG by gnuplot (Debian's gnuplot-nox), driven by the
/// apps; iris never draws plots by hand.

#include <filesystem>
#include <string>
#include <vector>

namespace iris::app {

struct series {
    std::string title;
    std::vector<double> x;
    std::vector<double> y;
};

struct plot {
    std::string title;
    std::string xlabel;
    std::string ylabel;
    bool log_x = false;
    bool log_y = false;
    bool points = false;  ///< mark the data points (few samples, e.g. spp sweeps)
    int width = 1000;
    int height = 600;
    std::vector<series> lines;
};

/// \brief Render `p` to a PNG at `png`, atomically (gnuplot writes a temporary that is
/// renamed). \throws usage_error for an unwritable target, std::runtime_error when
/// gnuplot is missing or fails.
void write_plot(const plot& p, const std::filesystem::path& png);

}  // namespace iris::app
