#pragma once
/// \file
/// \brief The ablation run behind iris-ablate: references, progressive renders with
/// snapshots at spp counts and time budgets, metrics against the reference.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <iris/image.hpp>

namespace iris::app {

struct ablation_options {
    std::string scene;
    std::vector<std::string> presets{"hwss", "paper"};
    std::vector<int> spp{16, 32, 64, 128, 256, 512};
    std::vector<double> budgets;  ///< seconds; empty: no time-equal mode
    int reference_spp = 16384;
    int seeds = 1;
    int width = 0, height = 0;  ///< 0: the scene's
    int threads = 0;
    int nthold = 512;
    std::filesystem::path out;
    std::filesystem::path cache;
    std::string crop;  ///< "x,y,w,h"; empty: the centre
    std::string sampler = "sobol";  ///< of every preset's renders
    std::string reference_sampler;         ///< of the reference; empty: `sampler`
    std::string estimator = "nee-mis";     ///< of every preset's renders: nee-mis, bdpt or light
    std::string reference_estimator;       ///< of the reference; empty: `estimator`
    std::filesystem::path reference_file;  ///< a reference rendered elsewhere; empty: render (or cache) one
    const std::string& ref_sampler() const { return reference_sampler.empty() ? sampler : reference_sampler; }
    const std::string& ref_estimator() const { return reference_estimator.empty() ? estimator : reference_estimator; }
};

/// \brief One row of results.csv (and of the time-equal table, where `budget` > 0).
struct ablation_row {
    std::string scene, preset, sampler;
    int seed = 0;
    int spp = 0;
    double seconds = 0, mse = 0, relmse = 0, ssim = 0;
    double budget = 0;
    double flip = 0;  ///< mean HDR-ꟻLIP against the reference (NaN where the reference has no exposure range)
};

struct ablation_result {
    std::vector<ablation_row> spp_rows;
    std::vector<ablation_row> time_rows;
    image reference;
    std::string reference_source;  ///< where the reference came from, for summary.md
    std::vector<std::pair<std::string, image>> first_snapshots;  ///< per preset, seed 0, smallest spp
};

/// \brief Validate the options against the scene (image size, --crop), then render.
/// \throws usage_error for bad options, before anything is rendered or written.
ablation_result run_ablation(const ablation_options& opt);

/// \brief The rectangle of the side-by-side crops PNG in a width x height image: `crop`
/// ("x,y,w,h", integers, inside the image) or, if empty, the centre half. \throws usage_error
struct crop_rect {
    int x = 0, y = 0, w = 0, h = 0;
};
crop_rect crop_rectangle(const std::string& crop, int width, int height);

/// \brief results.csv, plots, crops, summary.md in opt.out.
void write_report(const ablation_options& opt, const ablation_result& r);

}  // namespace iris::app
