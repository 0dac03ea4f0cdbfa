#pragma once
/// \file
/// \brief `sampled_spectrum<N>` and `sampled_wavelengths<N>`: a spectrum known at N
/// wavelengths (nm) and those wavelengths with the pdf each was drawn with.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>

namespace iris {

/// \brief Values of a spectral quantity at N wavelengths; element-wise arithmetic.
///
/// N is a compile-time width (the hero-wavelength count C, or a bin count for the
/// bias term), never a global constant.
template <std::size_t N>
    requires(N >= 1)
class sampled_spectrum {
public:
    static constexpr std::size_t size() noexcept { return N; }

    constexpr sampled_spectrum() noexcept = default;
    constexpr explicit sampled_spectrum(float c) noexcept { m_v.fill(c); }
    constexpr explicit sampled_spectrum(const std::array<float, N>& v) noexcept : m_v(v) {}

    constexpr float& operator[](std::size_t i) noexcept { return m_v[i]; }
    constexpr float operator[](std::size_t i) const noexcept { return m_v[i]; }
    constexpr const std::array<float, N>& values() const noexcept { return m_v; }

#define IRIS_SPECTRUM_OP(op)                                                                 \
    constexpr sampled_spectrum& operator op##=(const sampled_spectrum& o) noexcept {        \
        for (std::size_t i = 0; i < N; ++i) m_v[i] op## = o.m_v[i];                         \
        return *this;                                                                        \
    }                                                                                        \
    constexpr sampled_spectrum& operator op##=(float s) noexcept {                          \
        for (auto& v : m_v) v op## = s;                                                      \
        return *this;                                                                        \
    }                                                                                        \
    friend constexpr sampled_spectrum operator op(sampled_spectrum a,                        \
                                                  const sampled_spectrum& b) noexcept {      \
        return a op## = b;                                                                   \
    }                                                                                        \
    friend constexpr sampled_spectrum operator op(sampled_spectrum a, float s) noexcept {    \
        return a op## = s;                                                                   \
    }
    IRIS_SPECTRUM_OP(+)
    IRIS_SPECTRUM_OP(-)
    IRIS_SPECTRUM_OP(*)
    IRIS_SPECTRUM_OP(/)
#undef IRIS_SPECTRUM_OP

    friend constexpr sampled_spectrum operator*(float s, sampled_spectrum a) noexcept { return a *= s; }
    friend constexpr sampled_spectrum operator-(sampled_spectrum a) noexcept { return a *= -1.0f; }
    friend constexpr bool operator==(const sampled_spectrum&, const sampled_spectrum&) = default;

    /// \brief Division that yields 0 where the divisor is 0 (pdf-safe, as in pbrt).
    friend constexpr sampled_spectrum safe_div(sampled_spectrum a, const sampled_spectrum& b) noexcept {
        for (std::size_t i = 0; i < N; ++i) a.m_v[i] = b.m_v[i] != 0.0f ? a.m_v[i] / b.m_v[i] : 0.0f;
        return a;
    }

    constexpr float sum() const noexcept {
        float s = 0.0f;
        for (float v : m_v) s += v;
        return s;
    }
    constexpr float average() const noexcept { return sum() / static_cast<float>(N); }
    constexpr float max_value() const noexcept { return *std::max_element(m_v.begin(), m_v.end()); }
    constexpr float min_value() const noexcept { return *std::min_element(m_v.begin(), m_v.end()); }
    constexpr bool is_zero() const noexcept {
        return std::all_of(m_v.begin(), m_v.end(), [](float v) { return v == 0.0f; });
    }
    bool all_finite() const noexcept {
        return std::all_of(m_v.begin(), m_v.end(), [](float v) { return std::isfinite(v); });
    }

    /// \brief Apply `f` element-wise (e.g. `exp`, `sqrt`).
    template <class F>
    constexpr sampled_spectrum map(F&& f) const {
        sampled_spectrum r;
        for (std::size_t i = 0; i < N; ++i) r.m_v[i] = std::invoke(f, m_v[i]);
        return r;
    }

private:
    std::array<float, N> m_v{};
};

/// \brief N wavelengths in nm with the density each was sampled with (1/nm).
///
/// Index 0 is the hero wavelength: it alone chooses directions. At a specular dispersive
/// event the others do not die here (pbrt-v4 zeroes their wavelength pdfs): the BxDF
/// gives them zero f and zero p(ωi | λ_k), so their MIS ratios and contributions vanish
/// (iris/render/materials/smooth_dielectric.hpp, docs/method.md §3).
template <std::size_t N>
    requires(N >= 1)
class sampled_wavelengths {
public:
    static constexpr std::size_t size() noexcept { return N; }

    constexpr sampled_wavelengths() noexcept = default;
    constexpr sampled_wavelengths(const std::array<float, N>& lambda_nm,
                                  const std::array<float, N>& pdf) noexcept
        : m_lambda(lambda_nm), m_pdf(pdf) {}

    constexpr float operator[](std::size_t i) const noexcept { return m_lambda[i]; }
    constexpr float lambda(std::size_t i) const noexcept { return m_lambda[i]; }
    constexpr float& lambda(std::size_t i) noexcept { return m_lambda[i]; }
    constexpr float pdf(std::size_t i) const noexcept { return m_pdf[i]; }
    constexpr float& pdf(std::size_t i) noexcept { return m_pdf[i]; }
    constexpr const std::array<float, N>& lambdas() const noexcept { return m_lambda; }
    constexpr sampled_spectrum<N> pdfs() const noexcept { return sampled_spectrum<N>(m_pdf); }

    friend constexpr bool operator==(const sampled_wavelengths&, const sampled_wavelengths&) = default;

private:
    std::array<float, N> m_lambda{};
    std::array<float, N> m_pdf{};
};

}  // namespace iris
