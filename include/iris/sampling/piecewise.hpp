#pragma once
/// \file
/// \brief Piecewise-constant distributions on [0, 1) and [0, 1)²: the importance sampling
/// of environment maps (iris/render/lights/environment.hpp).
///
/// A 1-D distribution over n equal cells with weights f_i ≥ 0 has density
/// p(x) = f_i / ∫f on cell i (∫f = Σf_i / n); sampling inverts its CDF, continuous and
/// monotone, so stratified inputs stay stratified. The 2-D one (rows × columns) samples a
/// row by its marginal, then a column by the row's conditional: p(x, y) = f_ij / ∫∫f.
/// Weights that are all zero give the uniform distribution (a black map is still sampled,
/// with a density that matches the sampling).
///
/// Cost: O(n) memory; a sample is one binary search per dimension (CDF in double, so that
/// cells with a tiny weight next to huge ones are neither lost nor given a negative width).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include <glm/vec2.hpp>

namespace iris {

class piecewise_constant_1d {
public:
    piecewise_constant_1d() = default;

    /// \brief Weights of n ≥ 1 cells (negative or NaN weights count as 0).
    explicit piecewise_constant_1d(std::span<const float> f) : m_f(f.begin(), f.end()), m_cdf(f.size() + 1, 0.0) {
        const auto n = static_cast<double>(f.size());
        for (auto& v : m_f)
            if (!(v > 0.0f)) v = 0.0f;
        for (std::size_t i = 0; i < m_f.size(); ++i) m_cdf[i + 1] = m_cdf[i] + static_cast<double>(m_f[i]) / n;
        m_integral = m_cdf.back();
        if (!(m_integral > 0.0) || !std::isfinite(m_integral)) {  // all zero: uniform
            m_uniform = true;
            for (std::size_t i = 0; i <= m_f.size(); ++i) m_cdf[i] = static_cast<double>(i) / n;
        } else {
            for (auto& c : m_cdf) c /= m_integral;
        }
        m_cdf.back() = 1.0;
    }

    std::size_t size() const noexcept { return m_f.size(); }
    /// \brief ∫₀¹ f (0 for a distribution made of zeros).
    double integral() const noexcept { return m_uniform ? 0.0 : m_integral; }

    struct sample_type {
        float x;           ///< in [0, 1)
        float pdf;         ///< p(x)
        std::size_t cell;  ///< the cell x lies in
    };

    /// \brief x with density p(x), for u ∈ [0, 1).
    sample_type sample(float u) const noexcept {
        const double ud = static_cast<double>(u);
        const auto it = std::upper_bound(m_cdf.begin() + 1, m_cdf.end() - 1, ud);  // first cdf[i+1] > u
        const std::size_t i = static_cast<std::size_t>(it - m_cdf.begin()) - 1;
        const double lo = m_cdf[i], width = m_cdf[i + 1] - lo;
        double t = width > 0.0 ? (ud - lo) / width : 0.0;
        t = std::clamp(t, 0.0, 1.0);
        const auto n = static_cast<double>(m_f.size());
        float x = static_cast<float>((static_cast<double>(i) + t) / n);
        if (!(x < 1.0f)) x = std::nextafter(1.0f, 0.0f);
        return {x, pdf_cell(i), i};
    }

    /// \brief p(x) for x ∈ [0, 1] (x = 1 counts as the last cell).
    float pdf(float x) const noexcept { return pdf_cell(cell_of(x)); }
    float pdf_cell(std::size_t i) const noexcept {
        if (m_uniform) return 1.0f;
        return static_cast<float>(static_cast<double>(m_f[i]) / m_integral);
    }
    std::size_t cell_of(float x) const noexcept {
        const float c = std::clamp(x, 0.0f, 1.0f) * static_cast<float>(m_f.size());
        return std::min(static_cast<std::size_t>(c), m_f.size() - 1);
    }

private:
    std::vector<float> m_f;
    std::vector<double> m_cdf;
    double m_integral = 0.0;
    bool m_uniform = false;
};

/// \brief A piecewise-constant density on [0, 1)² over `width` × `height` cells, given row
/// by row (row 0 at y ∈ [0, 1/height)).
class piecewise_constant_2d {
public:
    piecewise_constant_2d() = default;
    piecewise_constant_2d(std::span<const float> f, std::size_t width, std::size_t height) : m_width(width) {
        std::vector<float> row_integral(height);
        m_rows.reserve(height);
        for (std::size_t y = 0; y < height; ++y) {
            m_rows.emplace_back(f.subspan(y * width, width));
            row_integral[y] = static_cast<float>(m_rows.back().integral());
        }
        m_marginal = piecewise_constant_1d(row_integral);
    }

    struct sample_type {
        glm::vec2 p;  ///< in [0, 1)²
        float pdf;
    };

    sample_type sample(glm::vec2 u) const noexcept {
        const auto row = m_marginal.sample(u.y);
        const auto col = m_rows[row.cell].sample(u.x);
        return {{col.x, row.x}, row.pdf * col.pdf};
    }
    float pdf(glm::vec2 p) const noexcept {
        const std::size_t y = m_marginal.cell_of(p.y);
        return m_marginal.pdf_cell(y) * m_rows[y].pdf(p.x);
    }
    /// \brief ∫∫f over the unit square.
    double integral() const noexcept { return m_marginal.integral(); }

private:
    std::size_t m_width = 0;
    std::vector<piecewise_constant_1d> m_rows;
    piecewise_constant_1d m_marginal;
};

}  // namespace iris
