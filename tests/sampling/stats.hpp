#pragma once
// Small statistics for the statistical tests: chi-square tail probabilities with pooling
// of sparse cells, two-sided normal tail probabilities and the Šidák correction.
// Written here (regularised incomplete gamma by series / continued fraction, the
// textbook method), so the tests depend on nothing but the standard library.
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace iris::test {

/// \brief Per-test significance that keeps the family-wise error at `family_alpha` over
/// m independent tests (Šidák): 1 − (1 − α)^(1/m).
inline double sidak(double family_alpha, std::size_t m) {
    return 1.0 - std::pow(1.0 - family_alpha, 1.0 / static_cast<double>(m));
}

/// \brief Regularised upper incomplete gamma Q(a, x) = Γ(a, x) / Γ(a).
inline double gamma_q(double a, double x) {
    if (x <= 0.0) return 1.0;
    const double log_prefix = -x + a * std::log(x) - std::lgamma(a);
    if (x < a + 1.0) {  // series for P, Q = 1 − P
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 100000; ++n) {
            term *= x / (a + n);
            sum += term;
            if (std::fabs(term) < std::fabs(sum) * 1e-16) break;
        }
        return std::max(0.0, 1.0 - sum * std::exp(log_prefix));
    }
    // continued fraction for Q (modified Lentz)
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 100000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        const double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1.0) < 1e-16) break;
    }
    return std::exp(log_prefix) * h;
}

/// \brief P(χ²_dof ≥ x).
inline double chi2_sf(double x, double dof) { return gamma_q(0.5 * dof, 0.5 * x); }

/// \brief P(|Z| ≥ |z|) for a standard normal Z.
inline double normal_two_sided(double z) { return std::erfc(std::fabs(z) / std::sqrt(2.0)); }

/// \brief The z with P(|Z| > z) = p for a standard normal Z (bisection on erfc).
inline double normal_quantile_two_sided(double p) {
    double lo = 0.0, hi = 40.0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (normal_two_sided(mid) > p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// \brief Outcome of a chi-square goodness-of-fit test.
struct chi2_result {
    double statistic = 0.0;
    std::size_t dof = 0;
    double p_value = 1.0;
    std::string impossible;  ///< non-empty: a sample fell where the expected count is 0
};

/// \brief Pearson's chi-square of `observed` against `expected` counts (same bins, in
/// order). Adjacent bins are pooled until each group expects ≥ 5 samples (a leftover
/// group below 5 joins the previous one), the usual condition for the χ² approximation.
/// A sample in a bin that expects exactly 0 is reported in `impossible`.
inline chi2_result chi_square(const std::vector<double>& expected, const std::vector<double>& observed) {
    chi2_result r;
    std::vector<double> e, o;
    double ge = 0.0, go = 0.0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
        if (expected[i] <= 0.0 && observed[i] > 0.0 && r.impossible.empty())
            r.impossible = "bin " + std::to_string(i) + " expects 0 samples but got " + std::to_string(observed[i]);
        ge += expected[i];
        go += observed[i];
        if (ge >= 5.0) {
            e.push_back(ge);
            o.push_back(go);
            ge = go = 0.0;
        }
    }
    if (ge > 0.0 || go > 0.0) {
        if (e.empty()) {
            e.push_back(ge);
            o.push_back(go);
        } else {
            e.back() += ge;
            o.back() += go;
        }
    }
    for (std::size_t i = 0; i < e.size(); ++i) r.statistic += (o[i] - e[i]) * (o[i] - e[i]) / e[i];
    r.dof = e.size() > 1 ? e.size() - 1 : 0;
    r.p_value = r.dof > 0 ? chi2_sf(r.statistic, static_cast<double>(r.dof)) : 1.0;
    return r;
}

/// \brief Running mean and variance (Welford), for z-tests of estimators.
struct running_stats {
    std::size_t n = 0;
    double mean = 0.0, m2 = 0.0;
    void add(double x) {
        ++n;
        const double d = x - mean;
        mean += d / static_cast<double>(n);
        m2 += d * (x - mean);
    }
    double variance() const { return n > 1 ? m2 / static_cast<double>(n - 1) : 0.0; }
    double standard_error() const { return std::sqrt(variance() / static_cast<double>(n)); }
};

}  // namespace iris::test
