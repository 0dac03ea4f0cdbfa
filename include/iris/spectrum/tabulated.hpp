#pragma once
/// \file
/// \brief `tabulated_spectrum`: dense samples at any (strictly increasing) spacing,
/// linear interpolation between them.
///
/// Outside the table the value is either 0 (`outside::zero`, the default: a light or a
/// CMF has no energy where it was not measured) or the nearest end value
/// (`outside::clamp`: reflectances and indices of refraction, which stay finite).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace iris {

/// \brief What a tabulated spectrum returns outside [front, back] of its table.
enum class outside { zero, clamp };

class tabulated_spectrum {
public:
    tabulated_spectrum() = default;

    /// \brief From wavelengths (nm, strictly increasing, at least 2) and values.
    /// \throws std::invalid_argument on sizes that differ, fewer than 2 points,
    ///         non-increasing or non-finite wavelengths, non-finite values.
    tabulated_spectrum(std::vector<double> lambda_nm, std::vector<double> values,
                       outside mode = outside::zero)
        : m_lambda(std::move(lambda_nm)), m_value(std::move(values)), m_mode(mode) {
        validate();
    }

    /// \brief From values at `start`, `start + step`, … (a uniform table).
    static tabulated_spectrum uniform(double start_nm, double step_nm, std::span<const double> values,
                                      outside mode = outside::zero) {
        if (!(step_nm > 0.0) || !std::isfinite(start_nm))
            throw std::invalid_argument("tabulated spectrum: step must be > 0 and start finite");
        std::vector<double> lambda(values.size());
        for (std::size_t i = 0; i < values.size(); ++i) lambda[i] = start_nm + step_nm * static_cast<double>(i);
        return {std::move(lambda), std::vector<double>(values.begin(), values.end()), mode};
    }

    /// \brief Linear interpolation; see `outside` for values beyond the table.
    double operator()(double lambda_nm) const noexcept {
        if (m_lambda.empty() || std::isnan(lambda_nm)) return 0.0;
        if (lambda_nm <= m_lambda.front())
            return lambda_nm == m_lambda.front() || m_mode == outside::clamp ? m_value.front() : 0.0;
        if (lambda_nm >= m_lambda.back())
            return lambda_nm == m_lambda.back() || m_mode == outside::clamp ? m_value.back() : 0.0;
        std::size_t i;
        double t;
        if (m_uniform) {  // the hot path (every CIE table): one multiply, no search, no division
            const double x = (lambda_nm - m_lambda.front()) * m_inv_step;
            i = std::min(static_cast<std::size_t>(x), m_lambda.size() - 2);
            t = std::min(1.0, x - static_cast<double>(i));
        } else {
            i = static_cast<std::size_t>(std::upper_bound(m_lambda.begin(), m_lambda.end(), lambda_nm) -
                                         m_lambda.begin()) - 1;
            double num = lambda_nm - m_lambda[i], den = m_lambda[i + 1] - m_lambda[i];
            if (!std::isfinite(den)) {  // points ~1e308 apart: the halves do not overflow (found by fuzzing)
                num = 0.5 * lambda_nm - 0.5 * m_lambda[i];
                den = 0.5 * m_lambda[i + 1] - 0.5 * m_lambda[i];
            }
            t = std::clamp(num / den, 0.0, 1.0);
        }
        // (1 − t)·a + t·b never overflows for finite a, b (a + t·(b − a) can); it can round
        // one ulp beyond [a, b], so it is clamped there (found by fuzzing: a = b, 1 ulp above)
        const double a = m_value[i], b = m_value[i + 1];
        return std::clamp((1.0 - t) * a + t * b, std::min(a, b), std::max(a, b));
    }

    std::span<const double> wavelengths() const noexcept { return m_lambda; }
    std::span<const double> values() const noexcept { return m_value; }
    outside mode() const noexcept { return m_mode; }
    double min_wavelength() const noexcept { return m_lambda.empty() ? 0.0 : m_lambda.front(); }
    double max_wavelength() const noexcept { return m_lambda.empty() ? 0.0 : m_lambda.back(); }

    /// \brief The same table with every value multiplied by `k`.
    tabulated_spectrum scaled(double k) const {
        tabulated_spectrum r = *this;
        for (double& v : r.m_value) v *= k;
        return r;
    }

private:
    void validate() {
        if (m_lambda.size() != m_value.size())
            throw std::invalid_argument("tabulated spectrum: " + std::to_string(m_lambda.size()) +
                                        " wavelengths but " + std::to_string(m_value.size()) + " values");
        if (m_lambda.size() < 2)
            throw std::invalid_argument("tabulated spectrum: needs at least 2 points");
        for (std::size_t i = 0; i < m_lambda.size(); ++i) {
            if (!std::isfinite(m_lambda[i]) || !std::isfinite(m_value[i]))
                throw std::invalid_argument("tabulated spectrum: non-finite entry at index " + std::to_string(i));
            if (i > 0 && !(m_lambda[i] > m_lambda[i - 1]))
                throw std::invalid_argument("tabulated spectrum: wavelengths must increase strictly (index " +
                                            std::to_string(i) + ")");
        }
        m_step = (m_lambda.back() - m_lambda.front()) / static_cast<double>(m_lambda.size() - 1);
        m_inv_step = 1.0 / m_step;
        // a span beyond double range, or a step so small that its inverse overflows, takes the
        // searching path (the uniform one would convert an infinite index: found by fuzzing)
        m_uniform = std::isfinite(m_step) && std::isfinite(m_inv_step);
        for (std::size_t i = 1; i < m_lambda.size() && m_uniform; ++i)
            m_uniform = std::abs((m_lambda[i] - m_lambda[i - 1]) - m_step) <= 1e-9 * m_step;
    }

    std::vector<double> m_lambda;
    std::vector<double> m_value;
    outside m_mode = outside::zero;
    double m_step = 1.0;
    double m_inv_step = 1.0;
    bool m_uniform = false;
};

}  // namespace iris
