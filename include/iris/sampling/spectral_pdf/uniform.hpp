#pragma once
/// \file
/// \brief `spectral_pdf::uniform`: p(λ) = 1/|Λ|, the density of plain HWSS (Wilkie et al.
/// 2014) and of the paper.

#include <string_view>

#include "iris/sampling/spectral_pdf/concept.hpp"

namespace iris::spectral_pdf {

/// \brief Every wavelength equally likely.
struct uniform {
    static constexpr std::string_view name = "uniform";
    constexpr double density(double /*lambda_nm*/) const noexcept { return 1.0; }
    constexpr double primitive(double lambda_nm) const noexcept { return lambda_nm; }
};

static_assert(SpectralPdf<uniform>);

}  // namespace iris::spectral_pdf
