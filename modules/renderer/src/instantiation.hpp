#pragma once
// A preset's own code (internal to iris::renderer): its passes — p_α at each pass's α, behind
// `pass_source` — and the functions of the dispatch table, which hand them to the shared
// instantiation of its shape (core.hpp). Included by the units presets.cpp.in generates.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>

#include "iris/render/sample_policy.hpp"
#include "iris/sampling/presets.hpp"
#include "dispatch.hpp"
#include "windows.hpp"

namespace iris::renderer::detail {

/// \brief A preset's configuration for one render, and p_α for pass i — rebuilt only when α
/// changes (every pass until N_thold, then never) — as the shared instantiations read it.
template <class Preset>
class preset_passes final : public pass_source<Preset::wavelength_count, iris::detail::bins_of<Preset>()> {
public:
    explicit preset_passes(const render_job& job) : m_cfg(parameters(job)) {}
    std::pair<float, const sample_policy<Preset::wavelength_count, iris::detail::bins_of<Preset>()>&> operator()(
        int i) override {
        const float a = m_cfg.alpha(static_cast<std::uint64_t>(i));
        if (a != m_alpha) {
            m_dist.emplace(m_cfg.distribution(a));
            m_policy.emplace(*m_dist);
            m_alpha = a;
        }
        return {a, *m_policy};
    }

private:
    /// The preset's parameters for this render, its windows resolved for the scene
    /// (and reported in the status).
    static typename Preset::parameters parameters(const render_job& job) {
        typename Preset::parameters params;
        params.n_thold = static_cast<std::uint32_t>(job.opt.nthold);
        params.domain = {job.scene.lambda_min, job.scene.lambda_max};
        job.st.windows = resolve_windows<Preset>(params, job.scene);
        return params;
    }
    const Preset m_cfg;
    float m_alpha = -1.0f;
    std::optional<typename Preset::distribution_type> m_dist;
    std::optional<preset_sample_policy<Preset>> m_policy;
};

/// \brief The shared instantiation a preset runs on.
template <class Preset>
struct core_key_of {
    static constexpr std::size_t C = Preset::wavelength_count;
    static constexpr std::size_t bins = iris::detail::bins_of<Preset>();
    static constexpr bool propagates = Preset::bias_type::propagates;
};

template <class Preset, isa I>
void render_preset(const render_job& job) {
    if constexpr (I != isa::baseline && !has_isa_copy<Preset>) {
        job.st.isa = isa_name(isa::baseline);  // no copy of this preset's loop (dispatch.hpp)
        render_preset<Preset, isa::baseline>(job);
        return;
    } else {
        using k = core_key_of<Preset>;
        preset_passes<Preset> passes(job);
        render_path_core<I, k::C, k::bins, k::propagates>(job, passes);
    }
}

template <class Preset>
void render_light(const render_job& job) {
    using k = core_key_of<Preset>;
    preset_passes<Preset> passes(job);
    render_light_core<k::C, k::bins, k::propagates>(job, passes);
}

template <class Preset>
void render_bdpt(const render_job& job) {
    using k = core_key_of<Preset>;
    preset_passes<Preset> passes(job);
    render_bdpt_core<k::C, k::bins, k::propagates>(job, passes);
}

}  // namespace iris::renderer::detail
