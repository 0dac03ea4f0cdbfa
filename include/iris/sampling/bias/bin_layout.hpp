#pragma once
/// \file
/// \brief `bias::bin_layout`: the spectral bins of the B term (docs/method.md §2, Bias policies) — bins of width
/// Δλ (default 5 nm) from λmin, the last one narrower if Δλ does not divide |Λ|, and one
/// wavelength per bin per sample, λ_b = lower_b + u Δλ_b with one jitter u shared by all
/// bins (each λ_b is then uniform in its own bin, so B is an unbiased estimate of
/// ∫ (1 − r_α) f; fixed bin centres would add quadrature error).

#include <algorithm>
#include <cstddef>
#include <span>

#include "iris/sampling/domain.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris::bias {

/// \brief Bins covering a spectral domain. A value type; cheap to copy.
class bin_layout {
public:
    static constexpr float default_width_nm = 5.0f;
    static constexpr std::size_t max_count = 4096;

    /// \brief 5 nm bins over 380–780 nm (80 bins).
    constexpr bin_layout() noexcept : bin_layout(spectral_domain{}) {}

    /// \brief Bins of `width_nm` over `d` (a width ≤ 0 or NaN means the default; more than
    /// `max_count` bins are widened to fit). An invalid domain has no bins.
    constexpr explicit bin_layout(spectral_domain d, float width_nm = default_width_nm) noexcept : m_domain(d) {
        if (!d.valid()) return;
        const double span = static_cast<double>(d.max_nm) - static_cast<double>(d.min_nm);
        double w = width_nm > 0.0f && width_nm <= 1e30f ? static_cast<double>(width_nm) : static_cast<double>(default_width_nm);
        double n = span / w;
        std::size_t count = n >= static_cast<double>(max_count) ? max_count : static_cast<std::size_t>(n);
        if (count < max_count && static_cast<double>(count) * w < span) ++count;  // the narrower last bin
        if (count == max_count) w = span / static_cast<double>(max_count);
        m_count = std::max<std::size_t>(count, 1);
        m_width = w;
    }

    /// \brief Exactly n equal bins over d (n clamped to [1, max_count]).
    static constexpr bin_layout with_count(spectral_domain d, std::size_t n) noexcept {
        n = std::clamp<std::size_t>(n, 1, max_count);
        bin_layout b(d, d.width() / static_cast<float>(n));
        if (d.valid()) {
            b.m_count = n;
            b.m_width = (static_cast<double>(d.max_nm) - static_cast<double>(d.min_nm)) / static_cast<double>(n);
        }
        return b;
    }

    constexpr std::size_t count() const noexcept { return m_count; }
    constexpr const spectral_domain& domain() const noexcept { return m_domain; }
    /// \brief Nominal bin width Δλ (nm).
    constexpr double nominal_width() const noexcept { return m_width; }
    /// \brief Lower edge of bin b (nm).
    constexpr double lower(std::size_t b) const noexcept {
        return static_cast<double>(m_domain.min_nm) + static_cast<double>(b) * m_width;
    }
    /// \brief Δλ_b: the nominal width, the last bin cut at λmax.
    constexpr double width(std::size_t b) const noexcept {
        return std::min(m_width, static_cast<double>(m_domain.max_nm) - lower(b));
    }
    /// \brief Bin b's edges rounded to float (lo ≤ hi: rounding is monotonic).
    struct float_edges {
        float lo, hi;
    };
    constexpr float_edges edges(std::size_t b) const noexcept {
        const double lo = lower(b);
        return {static_cast<float>(lo), static_cast<float>(lo + width(b))};
    }
    /// \brief The jittered wavelength of a bin with float edges [lo, hi] for u in [0, 1):
    /// lo + u (hi − lo), never past hi. Inside the bin in float (lo plus a non-negative term
    /// is ≥ lo; the minimum keeps it ≤ hi), and uniform in it up to rounding. The renderer's
    /// `bin_lattice` (iris/render/bins.hpp) evaluates this function from edges it caches
    /// per bin, so λ_b is the same number here, in the estimator tests and in a render.
    static constexpr float jitter(float lo, float hi, float u) noexcept { return std::min(lo + u * (hi - lo), hi); }
    /// \brief λ_b for jitter u (u outside [0, 1) or NaN counts as 0).
    constexpr float lambda(std::size_t b, float u) const noexcept {
        const float_edges e = edges(b);
        return jitter(e.lo, e.hi, u >= 0.0f && u < 1.0f ? u : 0.0f);
    }

    /// \brief All bins' wavelengths for jitter u, with pdf(b) = 1/Δλ_b (so the B term reads
    /// Σ_b (1 − r) f / pdf(b) like any Monte Carlo sum). Needs B ≥ count(): entries past
    /// count() get λ = λmax (0 without bins) and pdf 0 (they contribute nothing); if B < count() the bins
    /// past B are missing and B is biased — check `fits<B>()` once, outside the hot path.
    template <std::size_t B>
    constexpr sampled_wavelengths<B> jittered(float u) const noexcept {
        sampled_wavelengths<B> wl;
        for (std::size_t b = 0; b < B; ++b) {
            wl.lambda(b) = b < m_count ? lambda(b, u) : padding();
            wl.pdf(b) = b < m_count ? static_cast<float>(1.0 / width(b)) : 0.0f;
        }
        return wl;
    }
    template <std::size_t B>
    constexpr bool fits() const noexcept {
        return B >= m_count;
    }

    /// \brief Runtime form: fills min(count(), lambdas.size()) wavelengths and, if `pdfs`
    /// is not empty, their pdfs 1/Δλ_b (entries past count(): λmax and pdf 0).
    constexpr void fill(float u, std::span<float> lambdas, std::span<float> pdfs) const noexcept {
        for (std::size_t b = 0; b < lambdas.size(); ++b) lambdas[b] = b < m_count ? lambda(b, u) : padding();
        for (std::size_t b = 0; b < pdfs.size(); ++b) pdfs[b] = b < m_count ? static_cast<float>(1.0 / width(b)) : 0.0f;
    }

private:
    /// \brief λ for entries past count(): λmax, or 0 when there are no bins (an invalid
    /// domain may hold NaN, and even a zero-weight NaN poisons a product).
    constexpr float padding() const noexcept { return m_count > 0 ? m_domain.max_nm : 0.0f; }

    spectral_domain m_domain{};
    std::size_t m_count = 0;
    double m_width = default_width_nm;
};

}  // namespace iris::bias
