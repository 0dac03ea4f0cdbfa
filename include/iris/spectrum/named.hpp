#pragma once
/// \file
/// \brief The spectra and glasses compiled into iris, looked up by name.
///
/// Illuminants (relative SPDs, outside::zero beyond their tables): `D65`, `A`
/// (300–830 nm, 1 nm) and the nine CIE LED illuminants `LED-B1` … `LED-V2`
/// (380–780 nm, 1 nm). Glasses: the 14-row Sellmeier catalogue (13 SCHOTT glasses and
/// Malitson's fused silica) with a two-term Cauchy fit of each. Sources: data/README.md.

#include <algorithm>
#include <array>
#include <optional>
#include <span>
#include <string_view>

#include "iris/spectrum/blackbody.hpp"
#include "iris/spectrum/data/cie_a.hpp"
#include "iris/spectrum/data/cie_d65.hpp"
#include "iris/spectrum/data/cie_led.hpp"
#include "iris/spectrum/data/glass.hpp"
#include "iris/spectrum/data/metals.hpp"
#include "iris/spectrum/ior.hpp"
#include "iris/spectrum/tabulated.hpp"

namespace iris {

/// \brief A built-in illuminant: its name, one-line description and table.
struct named_illuminant {
    std::string_view name;
    std::string_view description;
    double lambda_min;
    double lambda_step;
    std::span<const double> values;

    tabulated_spectrum spectrum() const { return tabulated_spectrum::uniform(lambda_min, lambda_step, values); }
};

inline constexpr std::array<named_illuminant, 11> illuminants{{
    {"D65", "CIE standard illuminant D65 (average daylight, 6504 K)", data::cie_d65::lambda_min,
     data::cie_d65::lambda_step, data::cie_d65::values},
    {"A", "CIE standard illuminant A (incandescent tungsten, 2856 K)", data::cie_a::lambda_min,
     data::cie_a::lambda_step, data::cie_a::values},
#define IRIS_LED(name, ident, what)                                                                   \
    {name, what, data::cie_led::lambda_min, data::cie_led::lambda_step, data::cie_led::ident}
    IRIS_LED("LED-B1", led_b1, "CIE LED illuminant, phosphor-converted blue, 2733 K"),
    IRIS_LED("LED-B2", led_b2, "CIE LED illuminant, phosphor-converted blue, 2998 K"),
    IRIS_LED("LED-B3", led_b3, "CIE LED illuminant, phosphor-converted blue, 4103 K"),
    IRIS_LED("LED-B4", led_b4, "CIE LED illuminant, phosphor-converted blue, 5109 K"),
    IRIS_LED("LED-B5", led_b5, "CIE LED illuminant, phosphor-converted blue, 6598 K"),
    IRIS_LED("LED-BH1", led_bh1, "CIE LED illuminant, blue-excited hybrid, 2851 K"),
    IRIS_LED("LED-RGB1", led_rgb1, "CIE LED illuminant, red-green-blue mixture, 2840 K"),
    IRIS_LED("LED-V1", led_v1, "CIE LED illuminant, violet-pumped phosphor, 2724 K"),
    IRIS_LED("LED-V2", led_v2, "CIE LED illuminant, violet-pumped phosphor, 4070 K"),
#undef IRIS_LED
}};

/// \brief The illuminant called `name` (exact, case-sensitive), if iris knows it.
inline std::optional<named_illuminant> find_illuminant(std::string_view name) {
    const auto it = std::find_if(illuminants.begin(), illuminants.end(),
                                 [&](const named_illuminant& i) { return i.name == name; });
    return it == illuminants.end() ? std::nullopt : std::optional(*it);
}

/// \brief A catalogue glass: Sellmeier model (reference) and its two-term Cauchy fit.
struct named_glass {
    std::string_view name;
    sellmeier_ior sellmeier;
    cauchy_ior cauchy;
};

inline constexpr std::array<named_glass, data::glass::catalogue.size()> glasses = [] {
    std::array<named_glass, data::glass::catalogue.size()> g{};
    for (std::size_t i = 0; i < g.size(); ++i) {
        const auto& r = data::glass::catalogue[i];
        g[i] = {r.name, {r.b1, r.b2, r.b3, r.c1, r.c2, r.c3}, {r.cauchy_a, r.cauchy_b_um2}};
    }
    return g;
}();

/// \brief The catalogue glass called `name` (exact, case-sensitive), if any.
inline std::optional<named_glass> find_glass(std::string_view name) {
    const auto it = std::find_if(glasses.begin(), glasses.end(), [&](const named_glass& g) { return g.name == name; });
    return it == glasses.end() ? std::nullopt : std::optional(*it);
}

/// \brief A built-in metal: its complex refractive index η + ik, measured (data/README.md).
struct named_metal {
    std::string_view name;
    std::string_view description;
    std::span<const double> lambda, eta, k;

    /// \brief η(λ) and k(λ) as tables (linear between the measured nodes, clamped beyond).
    tabulated_spectrum eta_spectrum() const {
        return {{lambda.begin(), lambda.end()}, {eta.begin(), eta.end()}, outside::clamp};
    }
    tabulated_spectrum k_spectrum() const { return {{lambda.begin(), lambda.end()}, {k.begin(), k.end()}, outside::clamp}; }
};

inline constexpr std::array<named_metal, 5> metals{{
    {"Ag", "silver (Johnson & Christy 1972)", data::metals::ag_lambda, data::metals::ag_eta, data::metals::ag_k},
    {"Al", "aluminium (Rakić 1995)", data::metals::al_lambda, data::metals::al_eta, data::metals::al_k},
    {"Au", "gold (Johnson & Christy 1972)", data::metals::au_lambda, data::metals::au_eta, data::metals::au_k},
    {"Cu", "copper (Johnson & Christy 1972)", data::metals::cu_lambda, data::metals::cu_eta, data::metals::cu_k},
    {"CuZn", "brass, Cu70Zn30 (Querry 1985)", data::metals::cuzn_lambda, data::metals::cuzn_eta, data::metals::cuzn_k},
}};

/// \brief The metal called `name` (exact, case-sensitive), if iris knows it.
inline std::optional<named_metal> find_metal(std::string_view name) {
    const auto it = std::find_if(metals.begin(), metals.end(), [&](const named_metal& m) { return m.name == name; });
    return it == metals.end() ? std::nullopt : std::optional(*it);
}

}  // namespace iris
