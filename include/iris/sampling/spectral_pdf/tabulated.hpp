#pragma once
/// \file
/// \brief `spectral_pdf::tabulated` (any non-negative table, linear between its points)
/// and `spectral_pdf::illuminant` (∝ emitter SPD × ȳ, the power-weighted sum over a
/// scene's emitters, tabulated on the CMF's 1 nm grid, 360–830 nm).
///
/// The table lives behind a `shared_ptr<const …>`: copying a model (into every rebuilt
/// distribution) costs a reference count, never an allocation, and the data is
/// read-only, so threads may share it.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "iris/sampling/spectral_pdf/concept.hpp"
#include "iris/spectrum/color.hpp"
#include "iris/spectrum/spectrum.hpp"
#include "iris/spectrum/tabulated.hpp"

namespace iris::spectral_pdf {

/// \brief A density given by a table: linear interpolation between its points, 0 outside.
/// Values are rescaled so that the largest is 1 (the shape is all a pdf needs, and sums
/// of products never overflow).
class tabulated {
public:
    static constexpr std::string_view name = "tabulated";
    /// \brief Wavelengths accepted in a table (nm).
    static constexpr double max_wavelength_nm = 1e6;

    /// \brief From wavelengths (nm, strictly increasing, in [0, 1e6], at least 2) and
    /// values (finite, ≥ 0; all zero is allowed: a distribution then falls back to uniform).
    /// \throws std::invalid_argument otherwise, naming the first bad entry.
    tabulated(std::vector<double> lambda_nm, std::vector<double> values)
        : m_table(std::make_shared<const table>(std::move(lambda_nm), std::move(values))) {}

    /// \brief From a tabulated spectrum's own points (its values must be ≥ 0).
    explicit tabulated(const tabulated_spectrum& s)
        : tabulated(std::vector<double>(s.wavelengths().begin(), s.wavelengths().end()),
                    std::vector<double>(s.values().begin(), s.values().end())) {}

    double density(double lambda_nm) const noexcept {
        const table& t = *m_table;
        if (!(lambda_nm >= t.lambda.front() && lambda_nm <= t.lambda.back())) return 0.0;  // also NaN
        const std::size_t i = t.segment(lambda_nm);
        const double u = (lambda_nm - t.lambda[i]) / (t.lambda[i + 1] - t.lambda[i]);
        return (1.0 - u) * t.value[i] + u * t.value[i + 1];
    }
    /// \brief ∫ density from the first table point to λ (exact for the linear pieces).
    double primitive(double lambda_nm) const noexcept {
        const table& t = *m_table;
        if (!(lambda_nm > t.lambda.front())) return 0.0;  // also NaN
        if (lambda_nm >= t.lambda.back()) return t.prefix.back();
        const std::size_t i = t.segment(lambda_nm);
        const double h = t.lambda[i + 1] - t.lambda[i];
        const double dx = lambda_nm - t.lambda[i];
        return t.prefix[i] + dx * (t.value[i] + 0.5 * (t.value[i + 1] - t.value[i]) * (dx / h));
    }

    /// \brief ∫ density over the whole table.
    double total() const noexcept { return m_table->prefix.back(); }
    std::span<const double> wavelengths() const noexcept { return m_table->lambda; }
    /// \brief The (rescaled) values: the largest is 1 unless all are 0.
    std::span<const double> values() const noexcept { return m_table->value; }

private:
    struct table {
        std::vector<double> lambda, value, prefix;
        double step = 1.0;
        bool uniform = false;

        table(std::vector<double> l, std::vector<double> v) : lambda(std::move(l)), value(std::move(v)) {
            if (lambda.size() != value.size())
                throw std::invalid_argument("tabulated pdf: " + std::to_string(lambda.size()) + " wavelengths but " +
                                            std::to_string(value.size()) + " values");
            if (lambda.size() < 2) throw std::invalid_argument("tabulated pdf: needs at least 2 points");
            double top = 0.0;
            for (std::size_t i = 0; i < lambda.size(); ++i) {
                if (!(lambda[i] >= 0.0 && lambda[i] <= max_wavelength_nm))
                    throw std::invalid_argument("tabulated pdf: wavelength at index " + std::to_string(i) +
                                                " is not in [0, 1e6] nm");
                if (i > 0 && !(lambda[i] > lambda[i - 1]))
                    throw std::invalid_argument("tabulated pdf: wavelengths must increase strictly (index " +
                                                std::to_string(i) + ")");
                if (!(value[i] >= 0.0 && std::isfinite(value[i])))
                    throw std::invalid_argument("tabulated pdf: value at index " + std::to_string(i) +
                                                " is negative or not finite");
                top = std::max(top, value[i]);
            }
            if (top > 0.0)
                for (double& x : value) x /= top;
            prefix.assign(lambda.size(), 0.0);
            for (std::size_t i = 1; i < lambda.size(); ++i)
                prefix[i] = prefix[i - 1] + 0.5 * (value[i - 1] + value[i]) * (lambda[i] - lambda[i - 1]);
            step = (lambda.back() - lambda.front()) / static_cast<double>(lambda.size() - 1);
            uniform = true;
            for (std::size_t i = 1; i < lambda.size() && uniform; ++i)
                uniform = std::abs((lambda[i] - lambda[i - 1]) - step) <= 1e-9 * step;
        }

        /// \brief i with lambda[i] ≤ λ < lambda[i+1] (λ inside the table), at most size − 2.
        std::size_t segment(double l) const noexcept {
            std::size_t i;
            if (uniform) {
                i = static_cast<std::size_t>((l - lambda.front()) / step);
                i = std::min(i, lambda.size() - 2);
                // the division may land one off at a point; fix it so lambda[i] ≤ l
                if (i > 0 && l < lambda[i]) --i;
                else if (i + 2 < lambda.size() && l >= lambda[i + 1]) ++i;
            } else {
                i = static_cast<std::size_t>(std::upper_bound(lambda.begin(), lambda.end(), l) - lambda.begin());
                i = std::min(i == 0 ? 0 : i - 1, lambda.size() - 2);
            }
            return i;
        }
    };

    std::shared_ptr<const table> m_table;
};

static_assert(SpectralPdf<tabulated>);

/// \brief p(λ) ∝ Σ_e w_e · S_e(λ) · ȳ(λ): light where there is light and where the eye
/// sees it. Sampled on the CIE table's 1 nm grid (360–830 nm) and linear in between;
/// negative SPD values (measurement noise) count as 0.
class illuminant {
public:
    static constexpr std::string_view name = "illuminant";

    /// \brief One emitter: p ∝ S(λ) ȳ(λ).
    template <Spectrum S>
    explicit illuminant(const S& spd) : m_table(build([&](double l) { return static_cast<double>(spd(l)); })) {}

    /// \brief Several emitters: p ∝ Σ_e w_e S_e(λ) ȳ(λ), where w_e turns emitter e's SPD into
    /// its emitted spectral power (e.g. area × π for a diffuse emitter of radiance S_e).
    /// \throws std::invalid_argument if the spans differ in size, are empty, or a weight is
    /// negative or not finite.
    illuminant(std::span<const tabulated_spectrum> spds, std::span<const double> weights)
        : m_table(build_sum(spds, weights)) {}

    double density(double lambda_nm) const noexcept { return m_table.density(lambda_nm); }
    double primitive(double lambda_nm) const noexcept { return m_table.primitive(lambda_nm); }
    const tabulated& table() const noexcept { return m_table; }

private:
    template <class F>
    static tabulated build(F&& spd) {
        std::vector<double> l(cie::cmf_samples), v(cie::cmf_samples);
        for (std::size_t i = 0; i < cie::cmf_samples; ++i) {
            l[i] = cie::cmf_lambda_min + static_cast<double>(i);
            const double s = spd(l[i]);
            v[i] = std::isfinite(s) && s > 0.0 ? s * data::cie1931::y_bar[i] : 0.0;
        }
        return {std::move(l), std::move(v)};
    }
    static tabulated build_sum(std::span<const tabulated_spectrum> spds, std::span<const double> weights) {
        if (spds.size() != weights.size() || spds.empty())
            throw std::invalid_argument("illuminant pdf: needs one weight per emitter and at least one emitter");
        for (double w : weights)
            if (!(w >= 0.0 && std::isfinite(w)))
                throw std::invalid_argument("illuminant pdf: emitter weights must be finite and >= 0");
        return build([&](double l) {
            double s = 0.0;
            for (std::size_t e = 0; e < spds.size(); ++e) s += weights[e] * std::max(0.0, spds[e](l));
            return s;
        });
    }

    tabulated m_table;
};

static_assert(SpectralPdf<illuminant>);

}  // namespace iris::spectral_pdf
