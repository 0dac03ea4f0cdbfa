#pragma once
/// \file
/// \brief Spectral output (docs/method.md §3, "Spectral output"): the bands a spectral film
/// keeps, and one sample's spectrum gathered at them.
///
/// An estimator's sample is a sum of **point contributions** (λ, v): each hero wavelength
/// λ_j adds v = r_α(λ_j)/p_α(λ_j) · L(λ_j) (÷ Z_α), the term the XYZ film weights by
/// cmf(λ_j); each of the B term's jittered bin wavelengths λ_b adds v = Δλ · L_b; the
/// BSDF-only estimator's one uniform λ adds (λmax − λmin) · L(λ). XYZ is Σ v · cmf(λ) / ∫ȳ;
/// the spectral film instead adds v to the band that holds λ. Band o of width Δ_o then
/// estimates the mean spectral radiance over the band, (1/Δ_o) ∫_o L(λ) dλ, with the same
/// expectation as the XYZ estimate's: an unbiased estimator gives an unbiased band, a
/// biased one (a restriction before N_thold) the same bias.

#include <cmath>
#include <cstddef>

namespace iris {

/// \brief `count` equal bands over [lambda_min, lambda_max] nm.
struct spectral_bands {
    int count = 0;  ///< 0: no spectral output
    double lambda_min = 380.0, lambda_max = 780.0;

    double width() const noexcept { return (lambda_max - lambda_min) / count; }
    double lower(int o) const noexcept { return lambda_min + (lambda_max - lambda_min) * o / count; }
    double centre(int o) const noexcept { return lambda_min + (lambda_max - lambda_min) * (o + 0.5) / count; }
    /// \brief The band holding λ (λmax in the last band); −1 outside [λmin, λmax] or NaN.
    int index(double lambda) const noexcept {
        const double x = (lambda - lambda_min) / (lambda_max - lambda_min) * count;
        if (!(x >= 0.0) || x > count) return -1;
        const int o = static_cast<int>(x);
        return o < count ? o : count - 1;
    }
    friend bool operator==(const spectral_bands&, const spectral_bands&) = default;
};

/// \brief One sample's point contributions summed per band, into `count` doubles the caller
/// owns (zero before the sample; `film::add` reads and clears them). The renderer's bands
/// span the scene's spectral domain, where every wavelength an estimator samples lies; a
/// wavelength outside them (none in a render) would be left out.
class spectral_row {
public:
    spectral_row(const spectral_bands& bands, double* values) noexcept : m_bands(bands), m_v(values) {}
    void add(double lambda, double v) noexcept {
        const int o = m_bands.index(lambda);
        if (o >= 0) m_v[o] += v;
    }
    const spectral_bands& bands() const noexcept { return m_bands; }
    double* values() const noexcept { return m_v; }

private:
    spectral_bands m_bands;
    double* m_v;
};

}  // namespace iris
