#pragma once
// The restriction windows of a render (internal to iris::renderer): a preset with automatic
// placement gets its multi_box windows from the scene's emitted spectrum here, once per
// render; render_preset and renderer::windows both call this, so what iris-spectrum prints is
// what the render uses.
#include <cstddef>
#include <string>

#include "iris/render/emission.hpp"
#include "iris/render/scene.hpp"
#include "iris/renderer/renderer.hpp"
#include "iris/sampling/placement.hpp"

namespace iris::renderer::detail {

/// \brief Place `params.kernel`'s windows if the preset places them automatically; return
/// them as status::windows writes them ("" for a kernel without windows).
template <class Preset>
std::string resolve_windows(typename Preset::parameters& params, const scene_desc& scene) {
    if constexpr (iris::detail::is_multi_box<typename Preset::kernel_type>) {
        constexpr std::size_t n = Preset::kernel_type::max_intervals;
        if constexpr (Preset::placement_type::automatic) {
            const auto signal = placement::channel_signals(emitted_power(scene), params.domain);
            const auto w = placement::place_windows<n>(signal, params.domain, params.kernel.centres_nm, params.kernel.widths_nm);
            params.kernel.centres_nm = w.centres_nm;
            params.kernel.widths_nm = w.widths_nm;
        }
        return format_windows(params.kernel.centres_nm, params.kernel.widths_nm);
    } else {
        return {};
    }
}

}  // namespace iris::renderer::detail
