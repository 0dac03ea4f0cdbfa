#pragma once
/// \file
/// \brief The presets: one type list of named `integrator_config`s. It drives the name →
/// instantiation registry (`dispatch_preset`), the typed tests and the templated
/// benchmarks; adding a preset here adds it everywhere (the renderer spreads the presets'
/// instantiations over several translation units: raise `IRIS_PRESET_COUNT` in
/// modules/renderer/CMakeLists.txt, which renderer.cpp's static_assert asks for).
///
/// | CLI name | config name | what it is |
/// |---|---|---|
/// | `hwss` | `unrestricted/none/C4/none` | the baseline: plain HWSS, uniform p, 4 wavelengths |
/// | `paper` | `multibox3/linear/C4/propagate` | the paper's method: three boxes, linear relaxation, propagation |
/// | `paper-quadratic` | `multibox3/quadratic/C4/propagate` | the paper's suggested quadratic relaxation |
/// | `paper-fast` | `multibox3/linear/C4/propagate8` | `paper` with 8 B-term bins (50 nm) instead of 80: cheaper, noisier B |
/// | `box` | `box/linear/C4/propagate` | one window at 580 nm (paper Fig. 5) with propagation |
/// | `gaussian` | `gaussian/linear/C4/propagate` | the smooth kernel with propagation |
/// | `scaled-pdf` | `multibox3/linear/C4/scaled` | the paper's "scaling PDFs" (Fig. 7) |
/// | `paper-auto` | `multibox3-auto/linear/C4/propagate` | `paper` with its windows placed from the scene's emitters (placement.hpp) |
/// | `scaled-pdf-auto` | `multibox3-auto/linear/C4/scaled` | `scaled-pdf` with the windows placed from the emitters |
/// | `paper-fade` | `multibox3/linear/C4/propagate/fade` | `paper` whose biased early samples fade out of the image (accumulation.hpp) |
/// | `paper-auto-fade` | `multibox3-auto/linear/C4/propagate/fade` | `paper-auto` with the fade |
/// | `restrict-only` | `multibox3/linear/C4/none` | restriction without a bias term (dim early) |
/// | `hwss-c1` | `unrestricted/none/C1/none` | one wavelength per path |
/// | `hwss-c8` | `unrestricted/none/C8/none` | eight wavelengths per path |
/// | `hwss-visible` | `unrestricted/none/C4/none/visible` | HWSS with pbrt-v4's luminance-shaped p |
///
/// Every preset's base pdf is default-constructible, so `cfg.distribution(alpha)` works
/// for all of them; an illuminant-shaped base pdf needs the scene's emitters and is made
/// with `integrator_config<…, spectral_pdf::illuminant>` by the caller.

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "iris/sampling/integrator_config.hpp"

namespace iris {

/// \brief A compile-time list of types.
template <class... T>
struct type_list {
    static constexpr std::size_t size = sizeof...(T);
};

/// \brief A configuration with the short name the command lines use (`paper`). It *is*
/// the configuration (it derives from it), so it can be passed wherever one is expected.
template <detail::fixed_string CliName, class Config>
struct named_preset : Config {
    using config_type = Config;
    static constexpr std::string_view cli_name = CliName.view();
    using Config::Config;
};

/// \brief The presets, one type each (`iris::preset::paper`, …).
namespace preset {
using namespace iris::restriction;
using hwss = named_preset<"hwss", integrator_config<unrestricted, relaxation::none, 4, bias::none>>;
using paper = named_preset<"paper", integrator_config<multi_box<3>, relaxation::linear, 4, bias::propagate_unused>>;
using paper_fast =
    named_preset<"paper-fast", integrator_config<multi_box<3>, relaxation::linear, 4, bias::propagate_coarse<8>>>;
using paper_quadratic =
    named_preset<"paper-quadratic", integrator_config<multi_box<3>, relaxation::quadratic, 4, bias::propagate_unused>>;
using box_linear = named_preset<"box", integrator_config<box, relaxation::linear, 4, bias::propagate_unused>>;
using gaussian_linear =
    named_preset<"gaussian", integrator_config<gaussian, relaxation::linear, 4, bias::propagate_unused>>;
using scaled_pdf = named_preset<"scaled-pdf", integrator_config<multi_box<3>, relaxation::linear, 4, bias::scaled_pdf>>;
using paper_auto = named_preset<"paper-auto", integrator_config<multi_box<3>, relaxation::linear, 4, bias::propagate_unused,
                                                                 spectral_pdf::uniform, placement::emitters>>;
using scaled_pdf_auto = named_preset<"scaled-pdf-auto", integrator_config<multi_box<3>, relaxation::linear, 4, bias::scaled_pdf,
                                                                          spectral_pdf::uniform, placement::emitters>>;
using paper_fade = named_preset<"paper-fade", integrator_config<multi_box<3>, relaxation::linear, 4, bias::propagate_unused,
                                                                 spectral_pdf::uniform, placement::fixed, accumulation::fade>>;
using paper_auto_fade =
    named_preset<"paper-auto-fade", integrator_config<multi_box<3>, relaxation::linear, 4, bias::propagate_unused,
                                                      spectral_pdf::uniform, placement::emitters, accumulation::fade>>;
using restrict_only = named_preset<"restrict-only", integrator_config<multi_box<3>, relaxation::linear, 4, bias::none>>;
using hwss_c1 = named_preset<"hwss-c1", integrator_config<unrestricted, relaxation::none, 1, bias::none>>;
using hwss_c8 = named_preset<"hwss-c8", integrator_config<unrestricted, relaxation::none, 8, bias::none>>;
using hwss_visible =
    named_preset<"hwss-visible", integrator_config<unrestricted, relaxation::none, 4, bias::none, spectral_pdf::visible>>;
}  // namespace preset

/// \brief Every preset, in the order the tools list them (`hwss` first: the baseline).
using presets = type_list<preset::hwss, preset::paper, preset::paper_fast, preset::paper_quadratic, preset::box_linear,
                          preset::gaussian_linear, preset::scaled_pdf, preset::restrict_only, preset::hwss_c1,
                          preset::hwss_c8, preset::hwss_visible, preset::paper_auto, preset::scaled_pdf_auto,
                          preset::paper_fade, preset::paper_auto_fade>;

namespace detail {
template <std::size_t I, class List>
struct type_at_impl;
template <std::size_t I, class T, class... Rest>
struct type_at_impl<I, type_list<T, Rest...>> : type_at_impl<I - 1, type_list<Rest...>> {};
template <class T, class... Rest>
struct type_at_impl<0, type_list<T, Rest...>> {
    using type = T;
};
}  // namespace detail

/// \brief The I-th preset of the list (`preset_at<0>` is `preset::hwss`): what the
/// renderer's generated translation units (src/presets.cpp.in) instantiate.
template <std::size_t I>
using preset_at = typename detail::type_at_impl<I, presets>::type;

/// \brief The index of preset P in the list.
template <class P>
constexpr std::size_t preset_index() noexcept {
    return []<class... L>(type_list<L...>) {
        std::size_t i = 0, found = sizeof...(L);
        ((std::is_same_v<P, L> ? (found = i, ++i) : ++i), ...);
        return found;
    }(presets{});
}

namespace detail {
template <class... P>
constexpr std::array<std::string_view, sizeof...(P)> cli_names(type_list<P...>) noexcept {
    return {P::cli_name...};
}
template <class... P>
constexpr std::array<std::string_view, sizeof...(P)> config_names(type_list<P...>) noexcept {
    return {P::name...};
}

template <class F, class P, class... Rest>
decltype(auto) dispatch_in(std::string_view name, F& f, type_list<P, Rest...>);
}  // namespace detail

/// \brief The presets' CLI names (`hwss`, `paper`, …), in list order.
constexpr std::array<std::string_view, presets::size> preset_names() noexcept { return detail::cli_names(presets{}); }
/// \brief The presets' config names (`multibox3/linear/C4/propagate`, …), in list order.
constexpr std::array<std::string_view, presets::size> preset_config_names() noexcept {
    return detail::config_names(presets{});
}

/// \brief "unknown preset 'x'; accepted: hwss, paper, …" (the message `dispatch_preset` throws).
inline std::string unknown_preset_message(std::string_view name) {
    std::string s = "unknown preset '" + std::string(name) + "'; accepted: ";
    const auto names = preset_names();
    for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + std::string(names[i]);
    return s;
}

/// \brief Call `f.template operator()<P>()` for the preset P whose CLI name or config
/// name is `name`, and return what it returns (the same type for every preset).
/// This is the one place where a runtime name becomes a compile-time configuration.
/// \throws std::invalid_argument listing the valid names if there is no such preset.
template <class F>
decltype(auto) dispatch_preset(std::string_view name, F&& f) {
    return detail::dispatch_in(name, f, presets{});
}

/// \brief Call `f.template operator()<P>()` for every preset P, in list order.
template <class F>
void for_each_preset(F&& f) {
    [&]<class... P>(type_list<P...>) { (f.template operator()<P>(), ...); }(presets{});
}

namespace detail {
template <class F, class P, class... Rest>
decltype(auto) dispatch_in(std::string_view name, F& f, type_list<P, Rest...>) {
    if constexpr (sizeof...(Rest) == 0) {
        if (name == P::cli_name || name == P::name) return f.template operator()<P>();
        throw std::invalid_argument(unknown_preset_message(name));
    } else {
        if (name == P::cli_name || name == P::name) return f.template operator()<P>();
        return dispatch_in(name, f, type_list<Rest...>{});
    }
}
}  // namespace detail

}  // namespace iris
