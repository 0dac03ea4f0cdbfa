#pragma once
/// \file
/// \brief Reading the spectral parts of a scene file: reflectances, emission SPDs, IOR
/// models (format: docs/scene-format.md).

#include <array>
#include <optional>
#include <string>

#include "iris/render/scene.hpp"
#include "iris/spectrum/tabulated.hpp"
#include "reader.hpp"

namespace iris::scene::detail {

/// \brief The spectral domain [min, max] nm that checks and power integrals use.
struct domain {
    double min = 380.0, max = 780.0;
};

/// \brief A reflectance in [0, 1]: number, {"srgb"}, {"linear_srgb"} or a table.
tabulated_spectrum read_reflectance(const reader& r);

/// \brief Which of a medium's coefficients is read, for messages.
struct coefficient {
    const char* what;    ///< "an absorption coefficient" or "a scattering coefficient"
    const char* symbol;  ///< "σ_a" or "σ_s"
};
inline constexpr coefficient absorption_coefficient{"an absorption coefficient", "σ_a"},
    scattering_coefficient{"a scattering coefficient", "σ_s"};
/// \brief A medium's absorption or scattering coefficient ≥ 0 per scene unit: a number (grey)
/// or a table.
tabulated_spectrum read_coefficient(const reader& r, const coefficient& c);

/// \brief An emission SPD and the name the feature summary reports for it.
struct named_spd {
    std::string name;
    tabulated_spectrum table;
};
/// \brief An SPD: illuminant name, "blackbody:K", {"blackbody": K} or a table.
named_spd read_spd(const reader& r);

/// \brief An IOR model; n(λ) is checked to be finite and in [1, 10] over `d`.
ior_model read_ior(const reader& r, const domain& d);

/// \brief A conductor's complex index: {"metal": NAME} of the built-in metals, or
/// {"eta": ..., "k": ...}, each a number or a {"wavelengths", "values"} table (η > 0,
/// k ≥ 0). `r` is the material object; nothing if it names neither.
std::optional<material::conductor_ior> read_conductor_ior(const reader& r);

/// \brief ∫ s(λ) dλ over the domain by 1 nm trapezoids (the light sampler's rule).
double integrate_over(const tabulated_spectrum& s, const domain& d) noexcept;

/// \brief The three emission basis spectra of an environment image: the reflectance basis
/// (iris/spectrum/rgb_upsampling.hpp) times `d65` at luminance 1, so that a texel of linear
/// sRGB (1, 1, 1) is D65 with Y = 1.
std::array<tabulated_spectrum, 3> environment_basis(const tabulated_spectrum& d65);

}  // namespace iris::scene::detail
