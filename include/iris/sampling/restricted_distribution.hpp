#pragma once
/// \file
/// \brief `restricted_distribution`: p_α(λ) = p(λ) r_α(λ) / Z_α on Λ (docs/method.md §1), sampled
/// by an exact inverse CDF, and its hero-rotated C-wavelength draw (docs/method.md §3).
///
/// Representation: piecewise constant on cells. Λ is cut into a uniform grid of at most
/// `max_grid_cells` cells (default 1 nm); the support of r_α (the kernel's intervals) is
/// cut by the same grid, so a box edge is always a cell edge and p_α is exactly 0 outside
/// a window. A cell's mass is ∫ p over it (from the base pdf's primitive, no quadrature)
/// times the mean of r_α over it (the kernel's `average`: 1 for boxes, erfc for the
/// Gaussian). `pdf` is then the *exact* density of `sample`, mutually consistent to
/// float precision; it differs from p r_α / Z_α only by replacing both by their cell
/// means. Since the estimators divide by `pdf` (the density actually sampled) and
/// multiply by the exact `restriction`, that changes variance only, never the mean.
///
/// Degenerate cases never produce NaN, Inf or a zero-pdf sample:
/// - r_α has no mass under p (e.g. a window outside Λ, or where p = 0): the distribution
///   samples p itself, `normalisation()` is 1 and `restricted_fallback()` is true — every
///   sample then has r_α = 0, so F_R = 0 and the B term carries everything;
/// - p has no mass on Λ (an emitter that is dark there): p is taken as uniform on Λ and
///   `base_fallback()` is true;
/// - a cell whose density would underflow (or overflow) a float gets no mass.
/// For a box kernel every sample has r_α = 1. For a smooth kernel a sample can land where
/// r_α, evaluated in float, has underflowed to 0 (a Gaussian's far tail, or most of a
/// cell when σ is far below the cell size): it then contributes r f / p_α = 0, its true
/// (rounded) contribution, so the estimate stays unbiased.
///
/// Cost: a rebuild evaluates the base primitive once per cell edge and, for smooth
/// kernels, two `erfc` per cell (docs/performance.md); a sample is a guide-table lookup
/// and one multiply-add per wavelength. No allocation anywhere; the object is read-only
/// after construction, so one instance can serve every thread of a pass.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

#include "iris/sampling/domain.hpp"
#include "iris/sampling/hwss.hpp"
#include "iris/sampling/restriction/concept.hpp"
#include "iris/sampling/spectral_pdf/concept.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief One drawn wavelength and the density p_α it was drawn with.
struct wavelength_sample {
    float lambda = 0.0f;  ///< nm
    float pdf = 0.0f;     ///< 1/nm, > 0
};

/// \brief Grid resolution of a restricted distribution.
struct distribution_resolution {
    static constexpr float default_cell_nm = 1.0f;
    static constexpr std::size_t max_grid_cells = 1024;
};

template <SpectralPdf BasePdf, RestrictionKernel Kernel>
class restricted_distribution {
public:
    using base_pdf_type = BasePdf;
    using kernel_type = Kernel;
    using bound_type = decltype(std::declval<const Kernel&>().bind(0.0f, spectral_domain{}));
    static constexpr std::size_t max_grid_cells = distribution_resolution::max_grid_cells;
    static constexpr std::size_t max_cells = max_grid_cells + Kernel::max_intervals + 1;

    /// \brief p_α for the base pdf `base`, the kernel `kernel` at extent `alpha` (clamped
    /// to [0, 1], NaN → 1) on `domain`, with grid cells of about `cell_nm` (default 1 nm;
    /// coarser if the domain would need more than `max_grid_cells`).
    /// \throws std::invalid_argument if `domain` is not valid (see spectral_domain::valid).
    restricted_distribution(const BasePdf& base, const Kernel& kernel, float alpha, spectral_domain domain = {},
                            float cell_nm = distribution_resolution::default_cell_nm)
        : m_base(base), m_kernel(kernel), m_domain(checked(domain)), m_alpha(restriction::detail::clamp_alpha(alpha)),
          m_r(kernel.bind(m_alpha, m_domain)) {
        build(cell_nm);
    }

    /// \brief p_α(λ) (1/nm): the density `sample` draws with; 0 outside the support and Λ.
    float pdf(float lambda_nm) const noexcept {
        const std::size_t i = locate(lambda_nm);
        return i == npos ? 0.0f : m_density[i];
    }
    /// \brief r_α(λ) of the kernel (exact, not tabulated).
    float restriction(float lambda_nm) const noexcept { return m_r(lambda_nm); }
    /// \brief The normalised base pdf p(λ) / ∫Λ p (exact), 0 outside Λ.
    float base_pdf(float lambda_nm) const noexcept {
        if (!m_domain.contains(lambda_nm)) return 0.0f;
        if (m_base_fallback) return static_cast<float>(m_inv_base_total);
        const double v = m_base.density(static_cast<double>(lambda_nm)) * m_inv_base_total;
        return v >= 0.0 && v < 3.0e38 ? static_cast<float>(v) : 0.0f;
    }
    /// \brief Z_α = ∫Λ p̂ r_α with p̂ the normalised base pdf; 1 in the restricted fallback.
    float normalisation() const noexcept { return m_z; }
    /// \brief ∫ from λmin to λ of `pdf` (exact for the cells), in [0, 1].
    double cdf(float lambda_nm) const noexcept {
        if (!(lambda_nm >= m_domain.min_nm)) return 0.0;
        if (lambda_nm >= m_domain.max_nm) return 1.0;
        std::size_t i = start_cell(lambda_nm);
        while (i < m_n && m_right[i] < lambda_nm) ++i;
        if (i == m_n) return 1.0;
        if (m_left[i] >= lambda_nm) return m_cdf[i];
        const double x = static_cast<double>(lambda_nm) - static_cast<double>(m_left[i]);
        return std::min(m_cdf[i + 1], m_cdf[i] + x * static_cast<double>(m_density[i]));
    }

    /// \brief λ = P_α⁻¹(u) for u in [0, 1) (u outside is clamped, NaN → 0).
    float sample(float u) const noexcept { return draw(static_cast<double>(u)).lambda; }
    /// \brief λ = P_α⁻¹(u) with its density (saves the lookup `pdf` would do).
    wavelength_sample sample_with_pdf(float u) const noexcept { return draw(static_cast<double>(u)); }
    /// \brief C hero-rotated wavelengths: u_j = frac(u + j/C), λ_j = P_α⁻¹(u_j),
    /// pdf(j) = p_α(λ_j). λ_0 is the hero; every λ_j lies in the support of r_α.
    template <std::size_t C>
    sampled_wavelengths<C> sample_wavelengths(float u) const noexcept {
        sampled_wavelengths<C> wl;
        for (std::size_t j = 0; j < C; ++j) {
            const wavelength_sample s = draw(hwss_rotation(u, j, C));
            wl.lambda(j) = s.lambda;
            wl.pdf(j) = s.pdf;
        }
        return wl;
    }

    float alpha() const noexcept { return m_alpha; }
    const spectral_domain& domain() const noexcept { return m_domain; }
    const BasePdf& base() const noexcept { return m_base; }
    const Kernel& kernel() const noexcept { return m_kernel; }
    const bound_type& bound_kernel() const noexcept { return m_r; }
    /// \brief True if r_α had no mass under p and p itself is sampled (see file comment).
    bool restricted_fallback() const noexcept { return m_restricted_fallback; }
    /// \brief True if p had no mass on Λ and uniform was used instead.
    bool base_fallback() const noexcept { return m_base_fallback; }

    /// \brief Number of cells (including massless ones, whose pdf is 0).
    std::size_t cell_count() const noexcept { return m_n; }
    /// \brief Cell i as [lo, hi] with its density.
    spectral_interval cell(std::size_t i) const noexcept { return {m_left[i], m_right[i]}; }
    float cell_density(std::size_t i) const noexcept { return m_density[i]; }

private:
    static constexpr std::size_t npos = static_cast<std::size_t>(-1);

    /// \brief d, if valid (checked before the kernel is bound to it).
    static spectral_domain checked(const spectral_domain& d) {
        if (!d.valid())
            throw std::invalid_argument("restricted distribution: invalid spectral domain [" + std::to_string(d.min_nm) +
                                        ", " + std::to_string(d.max_nm) +
                                        "] nm (need 0 <= min, max <= 1e5, max - min >= 1e-3)");
        return d;
    }

    double primitive(double x) const noexcept {
        return m_base_fallback ? x : m_base.primitive(x);
    }

    void build(float cell_nm) {
        const double lo = static_cast<double>(m_domain.min_nm), hi = static_cast<double>(m_domain.max_nm);
        const double width = hi - lo;
        double n = cell_nm > 0.0f ? std::ceil(width / static_cast<double>(cell_nm)) : 0.0;  // NaN → 0
        if (!(n >= 1.0)) n = width;  // a bad cell size: 1 nm
        m_grid = static_cast<std::size_t>(std::clamp(n, 1.0, static_cast<double>(max_grid_cells)));
        m_h = width / static_cast<double>(m_grid);
        m_inv_h = 1.0 / m_h;

        const double total = m_base.primitive(hi) - m_base.primitive(lo);
        m_base_fallback = !(total > 0.0 && total < 1e300);  // also NaN/Inf
        m_inv_base_total = 1.0 / (m_base_fallback ? width : total);

        double z = 0.0;
        for (const spectral_interval& s : m_r.support()) z += add_cells(s.lo, s.hi, !bound_type::indicator);
        if (!(static_cast<float>(z) > 0.0f)) {
            m_restricted_fallback = true;
            m_n = 0;
            z = add_cells(m_domain.min_nm, m_domain.max_nm, false);
            if (!(z > 0.0)) {  // p's cells all massless though its total is not: use uniform
                m_base_fallback = true;
                m_inv_base_total = 1.0 / width;
                m_n = 0;
                z = add_cells(m_domain.min_nm, m_domain.max_nm, false);
            }
            m_z = 1.0f;
        } else {
            m_z = static_cast<float>(std::min(z, 1.0));
        }

        // cumulative masses, ending at exactly 1, with each cell's density and inverse CDF
        // slope. A cell whose density would underflow (or overflow) a float gets no mass:
        // sampling it would return pdf 0. Dropping such cells renormalises the others,
        // which only raises their densities, so a second pass always settles it.
        for (int pass = 0; pass < 2; ++pass) {
            double sum = 0.0;
            for (std::size_t i = 0; i < m_n; ++i) sum += m_scale[i];
            const double inv_sum = 1.0 / sum;
            double acc = 0.0;
            bool dropped = false;
            std::size_t last = 0;  // one past the last cell with mass
            m_cdf[0] = 0.0;
            for (std::size_t i = 0; i < m_n; ++i) {
                acc += m_scale[i];
                m_cdf[i + 1] = std::min(1.0, acc * inv_sum);
                if (m_scale[i] > 0.0) last = i + 1;
            }
            // exactly 1 from the last cell with mass on: massless cells at the end get no
            // rounding crumbs (they would be sampled with pdf ≈ 1e-16 where p_α = 0)
            for (std::size_t i = last; i <= m_n; ++i) m_cdf[i] = 1.0;
            for (std::size_t i = 0; i < m_n; ++i) {
                const double d = m_cdf[i + 1] - m_cdf[i];
                const double w = static_cast<double>(m_right[i]) - static_cast<double>(m_left[i]);
                const double density = d / w;
                if (!(d > 0.0)) {
                    m_density[i] = 0.0f;
                } else if (density < 3.0e38 && static_cast<float>(density) > 0.0f) {
                    m_density[i] = static_cast<float>(density);
                } else {
                    m_density[i] = 0.0f;
                    dropped = true;
                }
            }
            if (!dropped) break;
            for (std::size_t i = 0; i < m_n; ++i)
                if (m_density[i] == 0.0f) m_scale[i] = 0.0;
        }
        for (std::size_t i = 0; i < m_n; ++i) {
            const double d = m_cdf[i + 1] - m_cdf[i];
            m_scale[i] = d > 0.0 ? (static_cast<double>(m_right[i]) - static_cast<double>(m_left[i])) / d : 0.0;
        }

        // grid cell k → first cell whose right edge reaches the grid cell's left edge
        std::size_t i = 0;
        for (std::size_t k = 0; k < m_grid; ++k) {
            const float g = static_cast<float>(lo + static_cast<double>(k) * m_h);
            while (i < m_n && m_right[i] < g) ++i;
            m_first[k] = static_cast<std::uint16_t>(i);
        }
        // guide table: entry g → first cell whose CDF interval reaches g / n
        m_guide_n = std::max<std::size_t>(m_n, 1);
        i = 0;
        for (std::size_t g = 0; g < m_guide_n; ++g) {
            const double target = static_cast<double>(g) / static_cast<double>(m_guide_n);
            while (i + 1 < m_n && m_cdf[i + 1] <= target) ++i;
            m_guide[g] = static_cast<std::uint16_t>(i);
        }
    }

    /// \brief Append the cells of [a, b] (inside Λ) cut by the grid; returns their mass.
    /// With `weigh`, each cell's base mass is multiplied by the kernel's mean over it.
    double add_cells(float a, float b, bool weigh) noexcept {
        const double lo = static_cast<double>(m_domain.min_nm);
        double mass_sum = 0.0;
        float x0 = a;
        double p0 = primitive(static_cast<double>(x0));
        [[maybe_unused]] auto e0 = edge_of(x0);
        const double first = std::floor((static_cast<double>(a) - lo) * m_inv_h) + 1.0;
        std::size_t k = first > 0.0 ? static_cast<std::size_t>(first) : 0;
        std::size_t n = m_n;  // a local count: the member would be stored back every cell
        for (;; ++k) {
            const double node = k >= m_grid ? static_cast<double>(m_domain.max_nm) : lo + static_cast<double>(k) * m_h;
            const bool last = !(node < static_cast<double>(b));
            const float x1 = last ? b : static_cast<float>(node);
            if (x1 > x0 && n < max_cells) {
                const double p1 = primitive(static_cast<double>(x1));
                double m = std::max(0.0, p1 - p0) * m_inv_base_total;
                if constexpr (EdgeAveragedRestriction<bound_type>) {
                    const auto e1 = m_r.edge_at(x1);
                    if (weigh) m *= m_r.average(e0, e1);
                    e0 = e1;
                } else {
                    if (weigh) m *= m_r.average(x0, x1);
                }
                if (!(m < 1e300)) m = 0.0;  // NaN from a broken model: a massless cell
                m_left[n] = x0;
                m_right[n] = x1;
                m_scale[n] = m;  // the cell's mass until build() turns it into the scale
                ++n;
                mass_sum += m;
                x0 = x1;
                p0 = p1;
            }
            if (last) break;
        }
        m_n = n;
        return mass_sum;
    }

    /// \brief The kernel's edge value at x when it has one (else nothing to carry).
    auto edge_of(float x) const noexcept {
        if constexpr (EdgeAveragedRestriction<bound_type>) return m_r.edge_at(x);
        else return 0;
    }

    std::size_t start_cell(float lambda_nm) const noexcept {
        const double x = (static_cast<double>(lambda_nm) - static_cast<double>(m_domain.min_nm)) * m_inv_h;
        std::size_t k = x > 0.0 ? static_cast<std::size_t>(x) : 0;
        k = std::min(k, m_grid - 1);
        return m_first[k > 0 ? k - 1 : 0];  // one back: the float division may be one too far
    }

    /// \brief The cell containing λ, preferring one with mass at a shared edge; npos if none.
    std::size_t locate(float lambda_nm) const noexcept {
        if (!(lambda_nm >= m_domain.min_nm && lambda_nm <= m_domain.max_nm)) return npos;
        std::size_t i = start_cell(lambda_nm);
        while (i < m_n && m_right[i] < lambda_nm) ++i;
        if (i == m_n || m_left[i] > lambda_nm) return npos;
        if (m_density[i] == 0.0f && i + 1 < m_n && m_left[i + 1] <= lambda_nm) ++i;
        return i;
    }

    wavelength_sample draw(double u) const noexcept {
        if (!(u >= 0.0)) u = 0.0;
        if (u >= 1.0) u = 0x1.fffffffffffffp-1;
        std::size_t g = static_cast<std::size_t>(u * static_cast<double>(m_guide_n));
        if (g >= m_guide_n) g = m_guide_n - 1;
        std::size_t i = m_guide[g];
        // m_cdf[m_n] = 1 > u ends every walk inside the table. The first step is branch-free:
        // with equal masses (uniform p) guide buckets and cells share their edges up to
        // rounding, so whether a step is needed is a coin flip a branch would mispredict.
        i += static_cast<std::size_t>(m_cdf[i + 1] <= u);
        while (m_cdf[i + 1] <= u) ++i;
        const float l = static_cast<float>(static_cast<double>(m_left[i]) + (u - m_cdf[i]) * m_scale[i]);
        return {std::clamp(l, m_left[i], m_right[i]), m_density[i]};
    }

    BasePdf m_base;
    Kernel m_kernel;
    spectral_domain m_domain;
    float m_alpha;
    bound_type m_r;
    float m_z = 1.0f;
    bool m_restricted_fallback = false;
    bool m_base_fallback = false;
    double m_inv_base_total = 1.0;
    std::size_t m_grid = 1;
    double m_h = 1.0, m_inv_h = 1.0;
    std::size_t m_n = 0;
    std::size_t m_guide_n = 1;
    std::array<float, max_cells> m_left{}, m_right{}, m_density{};
    std::array<double, max_cells> m_scale{};
    std::array<double, max_cells + 1> m_cdf{};
    std::array<std::uint16_t, max_grid_cells> m_first{};
    std::array<std::uint16_t, max_cells> m_guide{};
};

}  // namespace iris
