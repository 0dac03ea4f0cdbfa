#pragma once
/// \file
/// \brief The `Spectrum` concept: a function of wavelength (nm) evaluated in double.
///
/// Required expression: `s(lambda_nm)` → `double` (const, noexcept in practice).
/// Models: `constant_spectrum`, `tabulated_spectrum`, `blackbody_spectrum`
/// (this folder). `sample(s, wavelengths)` turns any model into a `sampled_spectrum<N>`.

#include <concepts>
#include <cstddef>

#include "iris/spectrum/sampled.hpp"

namespace iris {

template <class S>
concept Spectrum = requires(const S& s, double lambda_nm) {
    { s(lambda_nm) } -> std::convertible_to<double>;
};

/// \brief Evaluate a spectrum at each of the N sampled wavelengths.
template <Spectrum S, std::size_t N>
constexpr sampled_spectrum<N> sample(const S& s, const sampled_wavelengths<N>& wl) {
    sampled_spectrum<N> out;
    for (std::size_t i = 0; i < N; ++i) out[i] = static_cast<float>(s(static_cast<double>(wl[i])));
    return out;
}

/// \brief The same value at every wavelength.
struct constant_spectrum {
    double value = 0.0;
    constexpr double operator()(double /*lambda_nm*/) const noexcept { return value; }
};

}  // namespace iris
