#pragma once
/// \file
/// \brief `spectral_pdf::visible`: a luminance-shaped closed form,
/// p(λ) ∝ sech²(k (λ − c)), k = 0.0072 /nm, c = 538 nm — the shape pbrt-v4 samples its
/// visible wavelengths with. Its primitive is tanh(k (λ − c)) / k, so both the
/// normalisation on any domain and the inverse CDF are closed forms.

#include <cmath>
#include <string_view>

#include "iris/sampling/domain.hpp"
#include "iris/sampling/spectral_pdf/concept.hpp"

namespace iris::spectral_pdf {

/// \brief sech² bump centred near the peak of ȳ, wide enough to keep every visible
/// wavelength at ≥ 7 % of the peak density on 380–780 nm.
struct visible {
    static constexpr std::string_view name = "visible";
    static constexpr double centre_nm = 538.0;
    static constexpr double k_per_nm = 0.0072;

    double density(double lambda_nm) const noexcept {
        const double c = std::cosh(k_per_nm * (lambda_nm - centre_nm));
        return 1.0 / (c * c);
    }
    /// \brief tanh(k (λ − c)) / k, with tanh from one exp (a distribution calls this once
    /// per cell edge; only differences matter, and their absolute error is ~1e-14).
    double primitive(double lambda_nm) const noexcept {
        const double y = k_per_nm * (lambda_nm - centre_nm);
        const double t = 1.0 - 2.0 / (std::exp(2.0 * std::fabs(y)) + 1.0);
        return (y < 0.0 ? -t : t) * (1.0 / k_per_nm);
    }

    /// \brief The normalised density on `d` (closed form), 0 outside.
    double pdf(double lambda_nm, const spectral_domain& d) const noexcept {
        if (!(lambda_nm >= d.min_nm && lambda_nm <= d.max_nm)) return 0.0;
        return density(lambda_nm) / (primitive(d.max_nm) - primitive(d.min_nm));
    }
    /// \brief Closed-form inverse CDF on `d`: λ = c + atanh(t_a + u (t_b − t_a)) / k with
    /// t = tanh(k (λ − c)) at the ends; u in [0, 1), the result clamped into `d`.
    double sample(double u, const spectral_domain& d) const noexcept {
        const double ta = std::tanh(k_per_nm * (d.min_nm - centre_nm));
        const double tb = std::tanh(k_per_nm * (d.max_nm - centre_nm));
        const double l = centre_nm + std::atanh(ta + u * (tb - ta)) / k_per_nm;
        return std::fmin(std::fmax(l, static_cast<double>(d.min_nm)), static_cast<double>(d.max_nm));
    }
};

static_assert(SpectralPdf<visible>);

}  // namespace iris::spectral_pdf
