#pragma once
/// \file
/// \brief Index-of-refraction models n(λ) of dispersive glasses.
///
/// Concept `IorModel`: `m.n(lambda_nm)` → double. Models: `cauchy_ior` (two terms,
/// cheap; good for crowns and silica, up to 6e-3 off for dense flints in the blue),
/// `sellmeier_ior` (three-term Schott form, the catalogue's own model). Both take λ in
/// nm and convert to µm internally, as the catalogues tabulate coefficients in µm.

#include <cmath>
#include <concepts>

namespace iris {

template <class M>
concept IorModel = requires(const M& m, double lambda_nm) {
    { m.n(lambda_nm) } -> std::convertible_to<double>;
};

/// \brief n(λ) = A + B / λ², λ in µm.
struct cauchy_ior {
    double a = 1.5;
    double b_um2 = 0.0;
    constexpr double n(double lambda_nm) const noexcept {
        const double l = lambda_nm * 1e-3;
        return a + b_um2 / (l * l);
    }
};

/// \brief n²(λ) = 1 + Σ Bᵢ λ² / (λ² − Cᵢ), λ in µm, Cᵢ in µm².
struct sellmeier_ior {
    double b1 = 0, b2 = 0, b3 = 0;
    double c1 = 0, c2 = 0, c3 = 0;
    double n(double lambda_nm) const noexcept {
        const double l2 = lambda_nm * lambda_nm * 1e-6;
        return std::sqrt(1.0 + b1 * l2 / (l2 - c1) + b2 * l2 / (l2 - c2) + b3 * l2 / (l2 - c3));
    }
};

/// \brief Fraunhofer lines used for the Abbe number (nm): d (He), F (H), C (H).
inline constexpr double fraunhofer_d = 587.5618;
inline constexpr double fraunhofer_f = 486.1327;
inline constexpr double fraunhofer_c = 656.2725;

/// \brief Abbe number V_d = (n_d − 1) / (n_F − n_C): low means strong dispersion.
template <IorModel M>
double abbe_number(const M& m) {
    return (m.n(fraunhofer_d) - 1.0) / (m.n(fraunhofer_f) - m.n(fraunhofer_c));
}

}  // namespace iris
