#pragma once
// An independent model of a thin film for the tests (tests/render/thin_film_test.cpp and the
// renderer's film oracles): the characteristic (Abelès) matrix of one layer in double-
// precision std::complex, written from the textbook form (Macleod, *Thin-Film Optical
// Filters*, ch. 2: N = n − ik, tilted admittances, the fourth-quadrant root), sharing nothing
// with iris's Airy sum (`iris::detail::film_reflectance`) but the physics.

#include <cmath>
#include <complex>
#include <numbers>

namespace iris_test {

using cd = std::complex<double>;

struct rt {
    double r = 0.0, t = 0.0;
};

/// \brief R and T (unpolarised) of incident medium n0 (real) | a layer of real index n1 and
/// thickness d | substrate N2 = n2 − ik2, at incidence angle with sin θ0 = s0 (in the incident
/// medium) and wavelength λ (same unit as d). Macleod's characteristic matrix per
/// polarisation: δ = 2π N1 d cos θ1 / λ, [B; C] = [[cos δ, i sin δ/η1], [i η1 sin δ, cos δ]]·[1; η2],
/// with η = N cos θ (s) or N / cos θ (p) and N cos θ = √(N² − n0² s0²) on the branch with
/// Im ≤ 0; r = (η0 B − C)/(η0 B + C), T = 4 η0 Re η2 / |η0 B + C|².
inline rt matrix_method(double n0, double n1, double d, cd n2, double s0, double lambda) {
    const double a2 = n0 * n0 * s0 * s0;  // (n sin θ)² is conserved
    const auto root = [](cd z) {          // √z with Im ≤ 0 (a decaying wave for e^{i(ωt − kz)})
        cd q = std::sqrt(z);
        if (q.imag() > 0.0) q = -q;
        if (q.imag() == 0.0 && q.real() < 0.0) q = -q;
        return q;
    };
    const cd q0 = root(cd(n0 * n0 - a2)), q1 = root(cd(n1 * n1 - a2)), q2 = root(n2 * n2 - a2);
    const cd delta = 2.0 * std::numbers::pi * d * q1 / lambda;
    rt out;
    for (int p = 0; p < 2; ++p) {
        const cd e0 = p ? n0 * n0 / q0 : q0, e1 = p ? n1 * n1 / q1 : q1, e2 = p ? n2 * n2 / q2 : q2;
        const cd i(0.0, 1.0);
        const cd b = std::cos(delta) + i * std::sin(delta) / e1 * e2;
        const cd c = i * e1 * std::sin(delta) + std::cos(delta) * e2;
        const cd r = (e0 * b - c) / (e0 * b + c);
        out.r += 0.5 * std::norm(r);
        out.t += 0.5 * 4.0 * e0.real() * e2.real() / std::norm(e0 * b + c);
    }
    return out;
}

}  // namespace iris_test
