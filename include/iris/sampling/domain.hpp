#pragma once
/// \file
/// \brief `spectral_domain`: the wavelength interval Λ = [min_nm, max_nm] that a render
/// integrates over (docs/method.md §1). Default 380–780 nm; the paper used 400–700 nm.

namespace iris {

/// \brief The spectral domain Λ in nm. A plain value; `valid()` says whether the sampling
/// code can work on it (a distribution built on an invalid domain throws).
struct spectral_domain {
    float min_nm = 380.0f;
    float max_nm = 780.0f;

    /// \brief The narrowest domain accepted (nm): below it float wavelengths cannot
    /// resolve the cells of a distribution.
    static constexpr float min_width_nm = 1e-3f;
    /// \brief The largest wavelength accepted (nm); far beyond any CMF, well inside float.
    static constexpr float max_wavelength_nm = 1e5f;

    constexpr float width() const noexcept { return max_nm - min_nm; }
    constexpr bool contains(float lambda_nm) const noexcept { return lambda_nm >= min_nm && lambda_nm <= max_nm; }
    /// \brief 0 ≤ min, max ≤ 1e5 nm, max − min ≥ 1e-3 nm (so also: both finite, no NaN).
    constexpr bool valid() const noexcept {
        return min_nm >= 0.0f && max_nm <= max_wavelength_nm && max_nm - min_nm >= min_width_nm;
    }

    friend constexpr bool operator==(const spectral_domain&, const spectral_domain&) = default;
};

}  // namespace iris
