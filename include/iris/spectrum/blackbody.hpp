#pragma once
/// \file
/// \brief Planck's law, normalised so that the peak (Wien's displacement law) is 1.

#include <cmath>

namespace iris {

/// \brief Spectral radiance of a black body (W·sr⁻¹·m⁻²·m⁻¹) at `lambda_nm`, `kelvin`.
inline double planck(double lambda_nm, double kelvin) noexcept {
    if (!(kelvin > 0.0) || !(lambda_nm > 0.0)) return 0.0;
    constexpr double c = 299792458.0;       // speed of light, m/s
    constexpr double h = 6.62606957e-34;    // Planck constant, J·s
    constexpr double kb = 1.3806488e-23;    // Boltzmann constant, J/K
    const double l = lambda_nm * 1e-9;
    return (2.0 * h * c * c) / (l * l * l * l * l * std::expm1((h * c) / (l * kb * kelvin)));
}

/// \brief A black body of temperature T, scaled so that its maximum over λ is exactly 1.
class blackbody_spectrum {
public:
    /// \pre kelvin > 0 (checked by the callers that parse user input).
    explicit blackbody_spectrum(double kelvin) noexcept
        : m_kelvin(kelvin), m_inv_peak(1.0 / planck(peak_wavelength(kelvin), kelvin)) {}

    /// \brief Wien's displacement law, in nm.
    static double peak_wavelength(double kelvin) noexcept { return 2.897771955e-3 / kelvin * 1e9; }

    double operator()(double lambda_nm) const noexcept { return planck(lambda_nm, m_kelvin) * m_inv_peak; }
    double temperature() const noexcept { return m_kelvin; }

private:
    double m_kelvin;
    double m_inv_peak;
};

}  // namespace iris
