// Compile-time checks of the sampling policies: every model satisfies its concept, things
// that are not models do not, the configuration names are what the tools print, and the
// pure parts (curves, windows, bins, rotation) hold their laws in constant expressions.
// The configuration mistakes that must not compile are in compile_fail/ (CTest runs the
// compiler on them and expects the plain-English message).
#include <iris/iris.hpp>

#include <string>
#include <string_view>
#include <type_traits>

namespace {

using namespace iris;

// ---- concepts: models -----------------------------------------------------------------
static_assert(SpectralPdf<spectral_pdf::uniform>);
static_assert(SpectralPdf<spectral_pdf::visible>);
static_assert(SpectralPdf<spectral_pdf::tabulated>);
static_assert(SpectralPdf<spectral_pdf::illuminant>);

static_assert(RestrictionKernel<restriction::unrestricted>);
static_assert(RestrictionKernel<restriction::box>);
static_assert(RestrictionKernel<restriction::multi_box<1>>);
static_assert(RestrictionKernel<restriction::multi_box<3>>);
static_assert(RestrictionKernel<restriction::multi_box<16>>);
static_assert(RestrictionKernel<restriction::gaussian>);
static_assert(BoundRestriction<restriction::box::bound>);
static_assert(BoundRestriction<restriction::gaussian::bound>);

static_assert(RelaxationCurve<relaxation::linear>);
static_assert(RelaxationCurve<relaxation::quadratic>);
static_assert(RelaxationCurve<relaxation::none>);

static_assert(BiasPolicy<bias::none>);
static_assert(BiasPolicy<bias::scaled_pdf>);
static_assert(BiasPolicy<bias::propagate_unused>);

// ---- concepts: non-models -------------------------------------------------------------
struct no_name_kernel {
    static constexpr std::size_t max_intervals = 1;
    restriction::box::bound bind(float, const spectral_domain&) const { return {}; }
};
struct double_valued_curve {  // returns double, not float
    static constexpr std::string_view name = "x";
    double operator()(float t) const { return t; }
};
struct both_ways_bias {  // propagates *and* scales: would count the unsampled part twice
    static constexpr std::string_view name = "both";
    static constexpr bool propagates = true;
    static constexpr bool scales_pdf = true;
    static double restricted_factor(float, float, float) { return 0.0; }
};
struct float_pdf {  // density in float: the concept asks for double
    static constexpr std::string_view name = "f";
    float density(double) const { return 1.0f; }
    double primitive(double l) const { return l; }
};

static_assert(!RestrictionKernel<int>);
static_assert(!RestrictionKernel<std::string>);
static_assert(!RestrictionKernel<no_name_kernel>);
static_assert(!RestrictionKernel<relaxation::linear>);
static_assert(!BoundRestriction<int>);
static_assert(!RelaxationCurve<int>);
static_assert(!RelaxationCurve<double_valued_curve>);
static_assert(!RelaxationCurve<restriction::box>);
static_assert(!BiasPolicy<int>);
static_assert(!BiasPolicy<both_ways_bias>);
static_assert(!SpectralPdf<int>);
static_assert(!SpectralPdf<float_pdf>);
static_assert(!SpectralPdf<tabulated_spectrum>);  // a spectrum is not a pdf (no primitive)

// ---- names ----------------------------------------------------------------------------
static_assert(restriction::multi_box<3>::name == "multibox3");
static_assert(restriction::multi_box<12>::name == "multibox12");
static_assert(preset::paper::name == "multibox3/linear/C4/propagate");
static_assert(preset::paper::cli_name == "paper");
static_assert(preset::hwss::name == "unrestricted/none/C4/none");
static_assert(preset::hwss_visible::name == "unrestricted/none/C4/none/visible");
static_assert(preset::scaled_pdf::name == "multibox3/linear/C4/scaled");
static_assert(integrator_config<restriction::gaussian, relaxation::quadratic, 32, bias::propagate_unused,
                                spectral_pdf::illuminant>::name == "gaussian/quadratic/C32/propagate/illuminant");
static_assert(preset_names()[0] == "hwss");
static_assert(preset_names().size() == presets::size && presets::size >= 9);

// every preset: C in range, the config type exposed, names unique
template <class... P>
constexpr bool all_distinct(type_list<P...>) {
    constexpr std::array<std::string_view, sizeof...(P)> cli{P::cli_name...}, cfg{P::name...};
    for (std::size_t i = 0; i < cli.size(); ++i)
        for (std::size_t j = i + 1; j < cli.size(); ++j)
            if (cli[i] == cli[j] || cfg[i] == cfg[j]) return false;
    return ((P::wavelength_count >= 1) && ...);
}
static_assert(all_distinct(presets{}));
static_assert(std::is_base_of_v<preset::paper::config_type, preset::paper>);
static_assert(std::is_same_v<preset::paper::kernel_type, restriction::multi_box<3>>);
static_assert(std::is_same_v<preset::paper::bias_type, bias::propagate_unused>);
static_assert(preset::paper::bias_type::propagates && !preset::paper::bias_type::scales_pdf);
static_assert(preset::scaled_pdf::bias_type::scales_pdf);
static_assert(preset::hwss_c8::wavelength_count == 8);

// C from 1 to 32 forms a valid configuration
template <std::size_t... C>
constexpr bool all_c(std::index_sequence<C...>) {
    return ((integrator_config<restriction::multi_box<3>, relaxation::linear, C + 1,
                               bias::propagate_unused>::wavelength_count == C + 1) && ...);
}
static_assert(all_c(std::make_index_sequence<32>{}));

// ---- relaxation laws (exact in float for these curves) --------------------------------
static_assert(relaxation::alpha_at(relaxation::linear{}, 0, 512) == 0.0f);
static_assert(relaxation::alpha_at(relaxation::linear{}, 256, 512) == 0.5f);
static_assert(relaxation::alpha_at(relaxation::linear{}, 512, 512) == 1.0f);
static_assert(relaxation::alpha_at(relaxation::linear{}, 100000, 512) == 1.0f);
static_assert(relaxation::alpha_at(relaxation::quadratic{}, 256, 512) == 0.25f);
static_assert(relaxation::alpha_at(relaxation::none{}, 0, 512) == 1.0f);
static_assert(relaxation::alpha_at(relaxation::linear{}, 0, 1) == 0.0f);  // N_thold = 1
static_assert(relaxation::alpha_at(relaxation::linear{}, 1, 1) == 1.0f);
static_assert(relaxation::alpha_at(relaxation::linear{}, 0, 0) == 1.0f);  // N_thold = 0: relaxed
static_assert(preset::paper{}.alpha(128) == 0.25f);

// ---- box windows and bins -------------------------------------------------------------
constexpr spectral_domain dom{};
static_assert(restriction::box::window_at(580.0f, 20.0f, 0.0f, dom) == spectral_interval{570.0f, 590.0f});
static_assert(restriction::box::window_at(580.0f, 0.0f, 0.0f, dom).hi > 580.0f);  // width 0 → 1e-3 nm
static_assert(restriction::box{}.bind(1.0f, dom)(380.0f) == 1.0f && restriction::box{}.bind(1.0f, dom)(780.0f) == 1.0f);
static_assert(restriction::box{}.bind(0.0f, dom)(569.0f) == 0.0f);
static_assert(restriction::multi_box<3>{}.bind(0.0f, dom).support().size() == 3);
static_assert(bias::bin_layout().count() == 80);
static_assert(bias::bin_layout(spectral_domain{400.0f, 700.0f}, 7.0f).count() == 43);  // last bin 6 nm
static_assert(bias::bin_layout(spectral_domain{400.0f, 700.0f}, 7.0f).width(42) == 6.0);
static_assert(bias::bin_layout(spectral_domain{500.0f, 400.0f}).count() == 0);  // invalid domain: no bins
static_assert(bias::bin_layout().fits<80>() && !bias::bin_layout().fits<79>());

// ---- rotation: stratified, in [0, 1) -------------------------------------------------
static_assert(hwss_rotation(0.0f, 1, 4) == 0.25);
static_assert(hwss_rotation(0.9f, 1, 4) < 1.0 && hwss_rotation(0.9f, 1, 4) > 0.14);
static_assert(hwss_rotation(0x1.fffffep-1f, 3, 4) < 1.0);
static_assert(hwss_rotation(2.0f, 0, 1) < 1.0);

// ---- value semantics: cheap copies, no hidden state -----------------------------------
static_assert(std::is_trivially_copyable_v<restriction::multi_box<3>>);
static_assert(std::is_trivially_copyable_v<restriction::box::bound>);
static_assert(std::is_empty_v<relaxation::linear> && std::is_empty_v<bias::propagate_unused>);
static_assert(std::is_trivially_copyable_v<bias::bin_layout>);
static_assert(std::is_trivially_copyable_v<restricted_distribution<spectral_pdf::uniform, restriction::multi_box<3>>>);

}  // namespace
