#pragma once
/// \file
/// \brief The `SpectralPdf` concept: a base wavelength density p(λ) (docs/method.md §1), before any
/// restriction. Models: `spectral_pdf::uniform`, `spectral_pdf::visible`,
/// `spectral_pdf::tabulated`, `spectral_pdf::illuminant` (catalogue: spectral_pdf.hpp).
///
/// Required, for a `const P& p` and a wavelength `λ` in nm (double):
/// - `P::name`            a `std::string_view` used in config names and CLIs;
/// - `p.density(λ)`       → double ≥ 0, finite: p(λ) up to a constant factor (1/nm);
/// - `p.primitive(λ)`     → double, finite and non-decreasing in λ, with
///                          `primitive(b) − primitive(a) = ∫_a^b density` (exactly, or
///                          to double rounding): masses of cells come from it, so a
///                          restricted distribution never integrates p numerically.
/// The normalisation is not the model's business: the distribution divides by
/// `primitive(max) − primitive(min)` of its domain.

#include <concepts>
#include <string_view>

namespace iris {

template <class P>
concept SpectralPdf = std::copy_constructible<P> && requires(const P& p, double lambda_nm) {
    { P::name } -> std::convertible_to<std::string_view>;
    { p.density(lambda_nm) } -> std::same_as<double>;
    { p.primitive(lambda_nm) } -> std::same_as<double>;
};

}  // namespace iris
