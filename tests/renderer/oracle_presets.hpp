#pragma once
// The presets the estimators' exact-solution oracles render (tests/renderer): one per shared
// instantiation — a preset's estimator code is that of its shape, (C, the B term's bins or
// none), modules/renderer/CMakeLists.txt's IRIS_RENDERER_CORES — the first of each in the
// preset list. What differs between presets of one shape is their policy (wavelengths,
// windows, weights, complement, fade), which the furnace tests render for every preset
// (RendererCore.WhiteFurnaceIsFiveForEveryPresetBeforeAndAfterNthold,
// Statistical.FurnaceIsFiveForEveryPreset). With IRIS_TEST_EVERY_PRESET=1 (`ctest --preset
// every-preset`) the oracles render all of them, as before 2026-12-07.
#include <cstdlib>
#include <set>
#include <string>
#include <vector>

#include <iris/renderer/renderer.hpp>

namespace iris_test {

/// \brief The shape of a preset from its config name ("kernel/relaxation/C4/bias[/…]"):
/// C and its B term ("propagate", "propagate8") or "none" (no B term: `none`, `scaled`).
inline std::string preset_shape(const iris::renderer::preset_info& p) {
    std::vector<std::string> parts;
    std::string::size_type from = 0;
    for (;;) {
        const auto slash = p.config.find('/', from);
        parts.push_back(p.config.substr(from, slash == std::string::npos ? std::string::npos : slash - from));
        if (slash == std::string::npos) break;
        from = slash + 1;
    }
    const std::string bias = parts.size() > 3 ? parts[3] : "";
    return std::to_string(p.wavelengths) + "/" + (bias.rfind("propagate", 0) == 0 ? bias : std::string("none"));
}

/// \brief The oracles' presets (see above).
inline std::vector<iris::renderer::preset_info> oracle_presets() {
    auto all = iris::renderer::presets();
    if (const char* e = std::getenv("IRIS_TEST_EVERY_PRESET"); e && std::string(e) == "1") return all;
    std::vector<iris::renderer::preset_info> out;
    std::set<std::string> seen;
    for (auto& p : all)
        if (seen.insert(preset_shape(p)).second) out.push_back(p);
    return out;
}

}  // namespace iris_test
