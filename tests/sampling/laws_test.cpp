// The laws of docs/method.md §1 and the checks of its §5 for every kernel × base pdf × domain, at α ∈ {0, 1e-6, 0.5,
// 1 − 1e-6, 1} and at the domain edges: r_1 ≡ 1, r monotone in α, Z_α > 0, p_α ≥ 0,
// finite and of mass 1 (1e-5), pdf(sample(u)) > 0 for u = 0, 1 − ε and random u, every
// sample inside the restriction; plus the degenerate cases (width-0 boxes, windows
// outside Λ, dark emitters, N_thold = 1) and the cell masses against quadrature.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <type_traits>
#include <thread>
#include <vector>

#include "cases.hpp"

namespace {

using namespace iris;
using iris::test::named;

struct nan_curve {
    static constexpr std::string_view name = "nan";
    float operator()(float) const { return std::numeric_limits<float>::quiet_NaN(); }
};

constexpr float law_alphas[] = {0.0f, 1e-6f, 0.5f, 1.0f - 1e-6f, 1.0f};
constexpr float eps_below_one = 0x1.fffffep-1f;

/// \brief Wavelengths to probe on d: both edges, their float neighbours inside, and an
/// irregular grid (0.37 nm) in between.
std::vector<float> probe_wavelengths(const spectral_domain& d) {
    std::vector<float> l = {d.min_nm, std::nextafter(d.min_nm, d.max_nm), d.max_nm, std::nextafter(d.max_nm, d.min_nm)};
    for (double x = d.min_nm; x < d.max_nm; x += 0.37) l.push_back(static_cast<float>(x));
    return l;
}

/// \brief ∫Λ pdf by the midpoint rule on 1/64 nm steps, cut at the support's edges and
/// at whole nm (the cell edges of the default grid), so no jump falls inside a step.
template <class D>
double integrate_pdf(const D& dist) {
    const auto& d = dist.domain();
    std::vector<double> cuts = {d.min_nm, d.max_nm};
    for (const auto& s : dist.bound_kernel().support()) cuts.insert(cuts.end(), {s.lo, s.hi});
    for (double x = std::ceil(d.min_nm); x < d.max_nm; x += 1.0) cuts.push_back(x);
    std::sort(cuts.begin(), cuts.end());
    double sum = 0.0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
        const double a = cuts[i], b = cuts[i + 1];
        if (!(b > a)) continue;
        const int n = std::max(1, static_cast<int>(std::ceil((b - a) * 64.0)));
        const double h = (b - a) / n;
        for (int k = 0; k < n; ++k) sum += h * dist.pdf(static_cast<float>(a + (k + 0.5) * h));
    }
    return sum;
}

/// \brief ∫_a^b g by composite Simpson with n (even) intervals, in double.
template <class G>
double simpson(G&& g, double a, double b, int n = 64) {
    const double h = (b - a) / n;
    double s = g(a) + g(b);
    for (int k = 1; k < n; ++k) s += (k % 2 ? 4.0 : 2.0) * g(a + k * h);
    return s * h / 3.0;
}

/// \brief The mean of r over [a, b], independently of `average`: the midpoint rule for
/// boxes, the closed form s + (1 − s) σ√(π/2) (erf(·) − erf(·)) / (b − a) for Gaussians.
template <class B>
double reference_mean(const B& r, float a, float b) {
    const double lo = a, hi = b;
    if constexpr (std::is_same_v<B, restriction::gaussian::bound>) {
        if (r.floor >= 1.0) return 1.0;
        const double s2 = std::sqrt(1.0 / r.inv_two_sigma2);  // σ√2
        const double g = 0.5 * s2 * std::sqrt(std::numbers::pi) * (std::erf((hi - r.centre) / s2) - std::erf((lo - r.centre) / s2));
        return r.floor + (1.0 - r.floor) * g / (hi - lo);
    } else {
        const int n = 4096;
        double sum = 0.0;
        for (int k = 0; k < n; ++k) sum += r(static_cast<float>(lo + (k + 0.5) * (hi - lo) / n));
        return sum / n;
    }
}

/// \brief True if λ is an edge of one of the distribution's cells.
template <class D>
bool on_cell_edge(const D& dist, float l) {
    for (std::size_t i = 0; i < dist.cell_count(); ++i)
        if (dist.cell(i).lo == l || dist.cell(i).hi == l) return true;
    return false;
}

// ---- kernels --------------------------------------------------------------------------

TEST(Kernels, LawsOnEveryDomain) {
    const std::vector<float> alphas = {0.0f, 1e-6f, 0.1f, 0.3f, 0.5f, 0.9f, 1.0f - 1e-6f, 1.0f};
    for (const auto& dom : iris::test::domains()) {
        const auto lambdas = probe_wavelengths(dom.value);
        std::apply(
            [&](const auto&... k) {
                ([&] {
                    SCOPED_TRACE(k.name + " on " + dom.name);
                    std::vector<float> previous(lambdas.size(), 0.0f);
                    for (float a : alphas) {
                        const auto b = k.value.bind(a, dom.value);
                        for (std::size_t i = 0; i < lambdas.size(); ++i) {
                            const float r = b(lambdas[i]);
                            ASSERT_TRUE(std::isfinite(r) && r >= 0.0f && r <= 1.0f) << "r=" << r << " at " << lambdas[i];
                            if (a == 1.0f) {
                                ASSERT_EQ(r, 1.0f) << "law 1 at " << lambdas[i];  // r_1 ≡ 1
                            }
                            ASSERT_GE(r, previous[i]) << "law 2 at λ=" << lambdas[i] << " α=" << a;  // monotone
                            previous[i] = r;
                        }
                        // the support: sorted, inside Λ, r > 0 inside, r = 0 between (boxes)
                        const auto s = b.support();
                        float last = -1.0f;
                        for (const auto& iv : s) {
                            ASSERT_LT(iv.lo, iv.hi);
                            ASSERT_GE(iv.lo, dom.value.min_nm);
                            ASSERT_LE(iv.hi, dom.value.max_nm);
                            ASSERT_GT(iv.lo, last);
                            last = iv.hi;
                            using bound = std::decay_t<decltype(b)>;
                            if constexpr (bound::indicator) {  // a Gaussian's r underflows far out
                                ASSERT_EQ(b(iv.lo), 1.0f);
                                ASSERT_EQ(b(iv.hi), 1.0f);
                                ASSERT_EQ(b(0.5f * (iv.lo + iv.hi)), 1.0f);
                            }
                        }
                        using bound = std::decay_t<decltype(b)>;
                        if constexpr (bound::indicator) {
                            for (float l : lambdas) {
                                bool inside = false;
                                for (const auto& iv : s) inside |= l >= iv.lo && l <= iv.hi;
                                ASSERT_EQ(b(l), inside ? 1.0f : 0.0f) << "at " << l;
                            }
                        }
                        // average(lo, hi) is the mean of r: against a 4096-point midpoint sum
                        // for boxes (error ≤ one step per edge), against erf for the Gaussian
                        for (double lo = dom.value.min_nm; lo + 7.3 < dom.value.max_nm; lo += 41.1) {
                            const float a0 = static_cast<float>(lo), a1 = static_cast<float>(lo + 7.3);
                            const double mean = b.average(a0, a1);
                            ASSERT_GE(mean, 0.0);
                            ASSERT_LE(mean, 1.0);
                            ASSERT_NEAR(mean, reference_mean(b, a0, a1), 1e-3) << "[" << a0 << ", " << a1 << "]";
                        }
                    }
                }(), ...);
            },
            iris::test::kernels());
    }
}

TEST(Kernels, DegenerateParametersStayFinite) {
    const spectral_domain d{};
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (float a : {nan, -1.0f, 2.0f, 0.0f}) {
        for (const restriction::box& k : {restriction::box{nan, 20.0f}, restriction::box{580.0f, nan},
                                          restriction::box{inf, -inf}, restriction::box{580.0f, inf}}) {
            const auto b = k.bind(a, d);
            for (float l : {380.0f, 580.0f, 780.0f, nan}) ASSERT_TRUE(std::isfinite(b(l)));
        }
        for (const restriction::gaussian& k : {restriction::gaussian{nan, nan}, restriction::gaussian{580.0f, inf},
                                               restriction::gaussian{580.0f, 0.0f}, restriction::gaussian{-inf, 5.0f}}) {
            const auto b = k.bind(a, d);
            for (float l : {380.0f, 580.0f, 780.0f, nan}) ASSERT_TRUE(std::isfinite(b(l)));
            ASSERT_TRUE(std::isfinite(b.average(380.0f, 780.0f)));
        }
    }
    // nonsense domains (the distribution rejects them) still bind to finite windows
    for (const spectral_domain bad : {spectral_domain{0.0f, 3e38f}, spectral_domain{-3e38f, 3e38f}, spectral_domain{nan, inf}}) {
        const auto b = restriction::multi_box<3>{}.bind(0.5f, bad);
        ASSERT_TRUE(std::isfinite(b(1.0f)));
        const auto g = restriction::gaussian{}.bind(0.5f, bad);
        ASSERT_TRUE(std::isfinite(g(1.0f)));
    }
    // α NaN counts as 1: no restriction
    EXPECT_EQ(restriction::box{}.bind(nan, d)(400.0f), 1.0f);
}

// ---- relaxation -----------------------------------------------------------------------

TEST(Relaxation, CurvesAreMonotoneFromZeroToOne) {
    for (std::uint64_t n_thold : {1ull, 2ull, 7ull, 512ull}) {
        float prev_l = -1.0f, prev_q = -1.0f;
        for (std::uint64_t i = 0; i <= n_thold + 3; ++i) {
            const float l = relaxation::alpha_at(relaxation::linear{}, i, n_thold);
            const float q = relaxation::alpha_at(relaxation::quadratic{}, i, n_thold);
            EXPECT_GE(l, prev_l);
            EXPECT_GE(q, prev_q);
            EXPECT_LE(q, l);  // quadratic holds the restriction longer
            EXPECT_EQ(relaxation::alpha_at(relaxation::none{}, i, n_thold), 1.0f);
            prev_l = l;
            prev_q = q;
        }
        EXPECT_EQ(relaxation::alpha_at(relaxation::linear{}, 0, n_thold), 0.0f);
        EXPECT_EQ(relaxation::alpha_at(relaxation::linear{}, n_thold, n_thold), 1.0f);
    }
    EXPECT_EQ(relaxation::alpha_at(nan_curve{}, 3, 10), 1.0f);
}

// ---- restricted distribution: every kernel × base pdf × domain × α ---------------------

TEST(Distribution, LawsForEveryKernelAndBasePdf) {
    for (const auto& dom : iris::test::domains()) {
        const auto lambdas = probe_wavelengths(dom.value);
        iris::test::for_each_pair([&](const auto& k, const auto& base) {
            const bool positive_base = base.name == "uniform" || base.name == "visible";
            using bound = typename std::decay_t<decltype(k.value)>::bound;
            // boxes: every sample and every λ with p_α > 0 has r = 1; a smooth kernel's r may
            // underflow to 0 in float where its cells still hold mass (see the distribution)
            constexpr bool indicator = bound::indicator;
            const restricted_distribution full(base.value, restriction::unrestricted{}, 1.0f, dom.value);
            float previous_z = 0.0f;
            for (float a : law_alphas) {
                SCOPED_TRACE(k.name + " × " + base.name + " on " + dom.name + " at α=" + std::to_string(a));
                const restricted_distribution dist(base.value, k.value, a, dom.value);
                const float z = dist.normalisation();
                // law 3: Z_α > 0 (and ≤ 1); with a strictly positive p there is never a fallback
                ASSERT_TRUE(std::isfinite(z) && z > 0.0f && z <= 1.0f + 1e-6f) << "Z=" << z;
                if (positive_base) {
                    ASSERT_FALSE(dist.restricted_fallback());
                }
                if (!dist.restricted_fallback()) {
                    ASSERT_GE(z, previous_z * (1.0f - 1e-6f)) << "Z_α must not shrink as α grows";
                    previous_z = z;
                }
                // mass 1, twice: exactly over the cells, and by quadrature of pdf()
                double cells = 0.0;
                for (std::size_t i = 0; i < dist.cell_count(); ++i)
                    cells += static_cast<double>(dist.cell_density(i)) *
                             (static_cast<double>(dist.cell(i).hi) - dist.cell(i).lo);
                ASSERT_NEAR(cells, 1.0, 1e-5);
                // pdf() is exactly that piecewise-constant function: the cell's density
                // inside each cell, 0 in the gaps between cells
                for (std::size_t i = 0; i < dist.cell_count(); ++i) {
                    const auto c = dist.cell(i);
                    const float mid = c.lo + 0.5f * (c.hi - c.lo);
                    if (mid > c.lo && mid < c.hi) {
                        ASSERT_EQ(dist.pdf(mid), dist.cell_density(i)) << "in cell " << i;
                    }
                    if (i + 1 < dist.cell_count() && dist.cell(i + 1).lo > c.hi) {
                        const float gap = c.hi + 0.5f * (dist.cell(i + 1).lo - c.hi);
                        if (gap > c.hi && gap < dist.cell(i + 1).lo) {
                            ASSERT_EQ(dist.pdf(gap), 0.0f) << "between cells " << i << " and " << i + 1;
                        }
                    }
                }
                ASSERT_NEAR(integrate_pdf(dist), 1.0, 1e-5);
                // non-negative and finite everywhere, 0 outside Λ
                for (float l : lambdas) {
                    const float p = dist.pdf(l);
                    ASSERT_TRUE(std::isfinite(p) && p >= 0.0f) << "pdf=" << p << " at " << l;
                    ASSERT_TRUE(std::isfinite(dist.base_pdf(l)) && dist.base_pdf(l) >= 0.0f);
                    if (indicator && p > 0.0f && !dist.restricted_fallback()) {
                        ASSERT_EQ(dist.restriction(l), 1.0f) << "at " << l;
                    }
                }
                for (float l : {dom.value.min_nm - 1.0f, dom.value.max_nm + 1.0f, std::numeric_limits<float>::quiet_NaN(),
                                std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()})
                    ASSERT_EQ(dist.pdf(l), 0.0f);
                // samples: inside Λ and the restriction, pdf > 0 and the same from both routes
                iris::counter_rng rng(20240601);
                std::vector<float> us = {0.0f, 1e-7f, 0.5f, eps_below_one, 1.0f, -0.5f, std::numeric_limits<float>::quiet_NaN()};
                for (int n = 0; n < 2000; ++n) us.push_back(rng.next());
                for (float u : us) {
                    const wavelength_sample s = dist.sample_with_pdf(u);
                    ASSERT_EQ(s.lambda, dist.sample(u));
                    ASSERT_TRUE(dom.value.contains(s.lambda)) << "λ=" << s.lambda << " u=" << u;
                    ASSERT_GT(s.pdf, 0.0f) << "u=" << u;
                    ASSERT_TRUE(std::isfinite(s.pdf));
                    const float p = dist.pdf(s.lambda);
                    ASSERT_GT(p, 0.0f) << "pdf(sample(" << u << ")) at λ=" << s.lambda;
                    if (p != s.pdf) {
                        ASSERT_TRUE(on_cell_edge(dist, s.lambda)) << "pdf disagrees inside a cell at " << s.lambda;
                    }
                    if (indicator && !dist.restricted_fallback()) {
                        ASSERT_EQ(dist.restriction(s.lambda), 1.0f) << "λ=" << s.lambda;
                    }
                    ASSERT_TRUE(dist.restriction(s.lambda) >= 0.0f);
                    // the CDF inverts the sample (to the float resolution of λ)
                    if (u >= 0.0f && u < 1.0f) {
                        const double tol = 2e-6 + 4.0 * p * std::fabs(s.lambda) * 0x1.0p-23;
                        ASSERT_NEAR(dist.cdf(s.lambda), u, tol) << "λ=" << s.lambda;
                    }
                }
                // α = 1 is plain HWSS: the same cells as the unrestricted distribution
                if (a == 1.0f) {
                    ASSERT_FALSE(dist.restricted_fallback());
                    ASSERT_NEAR(z, 1.0f, 1e-6f);
                    for (float l : lambdas) ASSERT_EQ(dist.pdf(l), full.pdf(l)) << "at " << l;
                }
                // cell densities: (∫_cell p̂) · mean_cell(r_α) / Z_α, the representation the
                // distribution promises, with ∫p̂ by Simpson (not the primitive) and the mean
                // of r by the independent reference above
                for (std::size_t i = 0; i < dist.cell_count(); i += 7) {
                    const auto c = dist.cell(i);
                    const double w = static_cast<double>(c.hi) - c.lo;
                    if (w < 1e-3) continue;  // Simpson on a sliver of a few ulps says nothing
                    const double base_mass =
                        simpson([&](double x) { return static_cast<double>(dist.base_pdf(static_cast<float>(x))); }, c.lo, c.hi);
                    const double r = dist.restricted_fallback() ? 1.0 : reference_mean(dist.bound_kernel(), c.lo, c.hi);
                    const double expect = base_mass * r / (dist.restricted_fallback() ? 1.0 : z) / w;
                    // 1e-5 relative; the absolute 1e-12 / Z covers erf's cancellation in a
                    // Gaussian's far tail (the reference loses ~1e-16 of the window's mass
                    // that erfc in the library keeps, then divides by Z)
                    ASSERT_NEAR(dist.cell_density(i), expect, 1e-5 * expect + 1e-12 / z)
                        << "cell [" << c.lo << ", " << c.hi << "]";
                }
            }
        });
    }
}

TEST(Distribution, WindowsHoldExactlyTheirMass) {
    // uniform p, multibox3 at α = 0 on 380–780: three 20 nm windows, Z = 60/400, p_α = 1/60
    const restricted_distribution d(spectral_pdf::uniform{}, restriction::multi_box<3>{}, 0.0f);
    EXPECT_FLOAT_EQ(d.normalisation(), 60.0f / 400.0f);
    EXPECT_FLOAT_EQ(d.pdf(464.0f), 1.0f / 60.0f);
    EXPECT_FLOAT_EQ(d.pdf(454.0f), 1.0f / 60.0f);  // closed at both edges
    EXPECT_FLOAT_EQ(d.pdf(474.0f), 1.0f / 60.0f);
    EXPECT_EQ(d.pdf(std::nextafter(454.0f, 0.0f)), 0.0f);
    EXPECT_EQ(d.pdf(std::nextafter(474.0f, 1000.0f)), 0.0f);
    EXPECT_EQ(d.pdf(500.0f), 0.0f);
    EXPECT_EQ(d.sample(0.0f), 454.0f);
    EXPECT_EQ(d.sample(eps_below_one), 621.0f);
    EXPECT_FLOAT_EQ(d.base_pdf(500.0f), 1.0f / 400.0f);
}

TEST(Distribution, WindowsGrowLinearlyIntoTheirShares) {
    // with uniform p, Z_α is the covered fraction of Λ: (Σ w0 + α (|Λ| − Σ w0)) / |Λ|
    for (float a : {0.0f, 0.1f, 0.25f, 0.5f, 0.75f, 0.99f, 1.0f}) {
        const restricted_distribution m(spectral_pdf::uniform{}, restriction::multi_box<3>{}, a);
        EXPECT_NEAR(m.normalisation(), (60.0f + a * 340.0f) / 400.0f, 2e-6f) << a;
        EXPECT_EQ(m.bound_kernel().support().size(), a < 1.0f ? 3u : 1u) << a;  // disjoint until α = 1
        const restricted_distribution b(spectral_pdf::uniform{}, restriction::box{}, a);
        EXPECT_NEAR(b.normalisation(), (20.0f + a * 380.0f) / 400.0f, 2e-6f) << a;
    }
    // centres in any order, or equal, still cover Λ at α → 1
    restriction::multi_box<3> shuffled;
    shuffled.centres_nm = {611.0f, 464.0f, 611.0f};
    const restricted_distribution s(spectral_pdf::uniform{}, shuffled, 1.0f - 1e-6f);
    EXPECT_NEAR(s.normalisation(), 1.0f, 1e-5f);
}

TEST(Distribution, GaussianHasTheAreaOfTheBox) {
    // σ0 = 20/√(2π): at α = 0 the Gaussian holds as much uniform mass as the 20 nm box
    const restricted_distribution g(spectral_pdf::uniform{}, restriction::gaussian{}, 0.0f);
    EXPECT_NEAR(g.normalisation(), 20.0f / 400.0f, 1e-6f);
}

TEST(Distribution, MasslessCellsGetNoRoundingCrumbs) {
    // a 1e-3 nm Gaussian on a cell edge: exactly the two cells beside it hold mass; the
    // cumulative sum must not hand its last rounding error to a massless cell at the end
    const restricted_distribution d(iris::test::dark_bands(), restriction::gaussian{550.0f, 1e-3f}, 0.0f);
    std::vector<std::size_t> with_mass;
    for (std::size_t i = 0; i < d.cell_count(); ++i)
        if (d.cell_density(i) > 0.0f) with_mass.push_back(i);
    ASSERT_EQ(with_mass.size(), 2u);
    EXPECT_EQ(d.cell(with_mass[0]).hi, 550.0f);
    EXPECT_EQ(d.cell(with_mass[1]).lo, 550.0f);
    EXPECT_EQ(d.pdf(779.5f), 0.0f);
}

TEST(Distribution, WidthZeroBoxIsANarrowWindow) {
    const restricted_distribution d(spectral_pdf::visible{}, restriction::box{600.0f, 0.0f}, 0.0f);
    ASSERT_FALSE(d.restricted_fallback());
    iris::counter_rng rng(7);
    for (int i = 0; i < 1000; ++i) {
        const auto s = d.sample_with_pdf(rng.next());
        ASSERT_GE(s.lambda, 600.0f - 1e-3f);
        ASSERT_LE(s.lambda, 600.0f + 1e-3f);
        ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf > 0.0f);
        ASSERT_EQ(d.restriction(s.lambda), 1.0f);
    }
    // a window of 1e-3 nm up to the float rounding of its edges (ulp(600) = 2^-14 nm), cut
    // in two cells by the grid node at 600 nm
    ASSERT_EQ(d.cell_count(), 2u);
    const double w = static_cast<double>(d.cell(1).hi) - d.cell(0).lo;
    EXPECT_NEAR(w, 1e-3, 2.0 * 0x1.0p-14);
    EXPECT_NEAR(d.pdf(600.0f), 1.0 / w, 1e-4 / w);  // p (visible) varies by ~1e-5 over the window
}

TEST(Distribution, FallbackWhenTheRestrictionHoldsNoMass) {
    // a centre outside Λ is clamped into it, so law 3 holds for any p > 0 on Λ
    const restricted_distribution c(spectral_pdf::uniform{}, restriction::box{900.0f, 20.0f}, 0.0f);
    EXPECT_FALSE(c.restricted_fallback());
    EXPECT_NEAR(c.normalisation(), 10.0f / 400.0f, 1e-6f);  // [770, 790] ∩ Λ
    // a window where the emitter is dark (0 below 500 nm): p itself is sampled, Z is
    // reported as 1, every sample has r = 0, so F_R = 0 and the B term carries everything
    const restricted_distribution e(iris::test::dark_bands(), restriction::box{450.0f, 20.0f}, 0.0f);
    EXPECT_TRUE(e.restricted_fallback());
    EXPECT_EQ(e.normalisation(), 1.0f);
    for (float u : {0.0f, 0.3f, eps_below_one}) {
        EXPECT_GT(e.pdf(e.sample(u)), 0.0f);
        EXPECT_EQ(e.restriction(e.sample(u)), 0.0f);
    }
    EXPECT_EQ(e.pdf(450.0f), 0.0f);  // p = 0 there
    // a dark emitter on the whole domain: uniform instead
    const spectral_pdf::tabulated dark({300.0, 900.0}, {0.0, 0.0});
    const restricted_distribution f(dark, restriction::multi_box<3>{}, 0.0f);
    EXPECT_TRUE(f.base_fallback());
    EXPECT_FALSE(f.restricted_fallback());
    EXPECT_FLOAT_EQ(f.pdf(464.0f), 1.0f / 60.0f);
    // an emitter that only shines outside Λ
    const spectral_pdf::tabulated infrared({800.0, 900.0}, {1.0, 1.0});
    EXPECT_TRUE(restricted_distribution(infrared, restriction::box{}, 0.5f).base_fallback());
}

TEST(Distribution, InvalidDomainsThrow) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const spectral_domain d : {spectral_domain{700.0f, 400.0f}, spectral_domain{500.0f, 500.0f},
                                    spectral_domain{nan, 700.0f}, spectral_domain{-10.0f, 700.0f},
                                    spectral_domain{400.0f, 2e5f}, spectral_domain{500.0f, 500.0001f}}) {
        EXPECT_FALSE(d.valid());
        EXPECT_THROW(restricted_distribution(spectral_pdf::uniform{}, restriction::box{}, 0.0f, d), std::invalid_argument);
    }
}

TEST(Distribution, ExtremeDomainsAndResolutions) {
    for (const spectral_domain d : {spectral_domain{500.0f, 500.01f}, spectral_domain{0.0f, 1e5f},
                                    spectral_domain{0.0f, 0.002f}, spectral_domain{99990.0f, 1e5f}}) {
        for (float cell : {1.0f, 0.0f, -1.0f, 1e-9f, 1e9f, std::numeric_limits<float>::quiet_NaN()}) {
            const restricted_distribution dist(spectral_pdf::visible{}, restriction::gaussian{}, 0.2f, d, cell);
            double mass = 0.0;
            for (std::size_t i = 0; i < dist.cell_count(); ++i)
                mass += static_cast<double>(dist.cell_density(i)) * (static_cast<double>(dist.cell(i).hi) - dist.cell(i).lo);
            ASSERT_NEAR(mass, 1.0, 1e-5) << d.min_nm << "-" << d.max_nm << " cell " << cell;
            ASSERT_LE(dist.cell_count(), dist.max_cells);
            for (float u : {0.0f, 0.25f, eps_below_one}) {
                const auto s = dist.sample_with_pdf(u);
                ASSERT_TRUE(d.contains(s.lambda));
                ASSERT_GT(dist.pdf(s.lambda), 0.0f);
                ASSERT_TRUE(std::isfinite(s.pdf));
            }
        }
    }
}

TEST(Distribution, SharedReadOnlyBetweenThreads) {
    const restricted_distribution d(spectral_pdf::visible{}, restriction::multi_box<3>{}, 0.3f);
    auto run = [&](std::uint64_t seed) {
        iris::counter_rng rng(seed);
        double s = 0.0;
        for (int i = 0; i < 20000; ++i) {
            const auto wl = d.sample_wavelengths<4>(rng.next());
            for (std::size_t j = 0; j < 4; ++j) s += static_cast<double>(wl[j]) * wl.pdf(j);
        }
        return s;
    };
    std::vector<double> serial, parallel(4);
    for (std::uint64_t t = 0; t < 4; ++t) serial.push_back(run(t));
    std::vector<std::thread> threads;
    for (std::uint64_t t = 0; t < 4; ++t) threads.emplace_back([&, t] { parallel[t] = run(t); });
    for (auto& th : threads) th.join();
    EXPECT_EQ(serial, parallel);
}

// ---- HWSS: C from 1 to 32 ----------------------------------------------------------------

template <std::size_t C, class D>
void check_rotation(const D& dist) {
    iris::counter_rng rng(C);
    for (int n = 0; n < 200; ++n) {
        const float u = n == 0 ? 0.0f : n == 1 ? eps_below_one : rng.next();
        const sampled_wavelengths<C> wl = dist.template sample_wavelengths<C>(u);
        ASSERT_EQ(wl[0], dist.sample(u)) << "λ_0 is the hero";
        for (std::size_t j = 0; j < C; ++j) {
            ASSERT_GT(dist.restriction(wl[j]), 0.0f) << "C=" << C << " j=" << j << " λ=" << wl[j];
            ASSERT_GT(wl.pdf(j), 0.0f);
            if (wl.pdf(j) != dist.pdf(wl[j])) {
                ASSERT_TRUE(on_cell_edge(dist, wl[j]));
            }
            const double uj = hwss_rotation(u, j, C);
            ASSERT_NEAR(dist.cdf(wl[j]), uj, 2e-6 + 4.0 * wl.pdf(j) * wl[j] * 0x1.0p-23) << "C=" << C << " j=" << j;
        }
    }
}

template <std::size_t... I, class D>
void check_all_c(const D& dist, std::index_sequence<I...>) {
    (check_rotation<I + 1>(dist), ...);
}

TEST(Hwss, RotatedWavelengthsForEveryCFrom1To32) {
    check_all_c(restricted_distribution(spectral_pdf::uniform{}, restriction::multi_box<3>{}, 0.0f),
                std::make_index_sequence<32>{});
    check_all_c(restricted_distribution(spectral_pdf::visible{}, restriction::gaussian{}, 0.3f), std::make_index_sequence<32>{});
}

TEST(Hwss, RotationIsStratified) {
    // exactly one u_j in each [k/C, (k+1)/C)
    iris::counter_rng rng(3);
    for (int n = 0; n < 1000; ++n) {
        const float u = rng.next();
        for (std::size_t C : {1u, 3u, 4u, 7u, 32u}) {
            std::vector<int> hits(C, 0);
            for (std::size_t j = 0; j < C; ++j) {
                const double x = hwss_rotation(u, j, C);
                ASSERT_GE(x, 0.0);
                ASSERT_LT(x, 1.0);
                ++hits[std::min(C - 1, static_cast<std::size_t>(x * static_cast<double>(C)))];
            }
            for (int h : hits) ASSERT_EQ(h, 1);
        }
    }
}

TEST(Hwss, MisWeight) {
    const float path[] = {2.0f, 1.0f, 1.0f, 0.0f};
    EXPECT_FLOAT_EQ(hwss_mis_weight(0.5f, path), 1.0f / (0.5f * 4.0f));
    EXPECT_EQ(hwss_mis_weight(0.5f, sampled_spectrum<4>({2.0f, 1.0f, 1.0f, 0.0f})), hwss_mis_weight(0.5f, path));
    // terminated secondaries (pdf 0) and garbage count as 0
    const float odd[] = {2.0f, std::numeric_limits<float>::quiet_NaN(), -1.0f, 0.0f};
    EXPECT_FLOAT_EQ(hwss_mis_weight(1.0f, odd), 0.5f);
    // never NaN or Inf
    const float zeros[] = {0.0f, 0.0f};
    EXPECT_EQ(hwss_mis_weight(1.0f, zeros), 0.0f);
    EXPECT_EQ(hwss_mis_weight(0.0f, path), 0.0f);
    EXPECT_EQ(hwss_mis_weight(-1.0f, path), 0.0f);
    EXPECT_EQ(hwss_mis_weight(std::numeric_limits<float>::quiet_NaN(), path), 0.0f);
    const float tiny[] = {1e-30f};
    EXPECT_EQ(hwss_mis_weight(1e-30f, tiny), 0.0f);  // 1e60 does not fit a float
    const float inf[] = {std::numeric_limits<float>::infinity()};
    EXPECT_EQ(hwss_mis_weight(1.0f, inf), 0.0f);
    EXPECT_EQ(hwss_mis_weight(1.0f, std::span<const float>{}), 0.0f);
    // balance: the weights of the C techniques, times their densities, sum to 1
    const float p_alpha[] = {0.004f, 0.0021f, 0.0033f, 0.0017f};
    const float p_path[] = {0.7f, 1.3f, 0.2f, 2.9f};
    double sum = 0.0;
    for (std::size_t j = 0; j < 4; ++j)
        sum += static_cast<double>(hwss_mis_weight(p_alpha[j], p_path)) * p_alpha[j] * p_path[j];
    EXPECT_NEAR(sum, 1.0, 1e-6);
}

// The ratio form the path integrator renders with equals the pdf form above, for each
// way a path can end: one strategy, a light-sampled last vertex, an emitter found by BSDF
// sampling. Inputs span two decades each; float arithmetic of a 4-term sum: rel. 1e-5.
TEST(Hwss, RatioFormIsThePdfForm) {
    constexpr std::size_t C = 4;
    counter_rng rng(11, 0);
    const auto in = [&](float lo, float hi) { return lo + (hi - lo) * rng.next(); };
    for (int trial = 0; trial < 2000; ++trial) {
        sampled_spectrum<C> q, f, pb;  // path pdfs before the last vertex, path values, BSDF pdfs there
        for (std::size_t k = 0; k < C; ++k) {
            q[k] = in(0.1f, 10.0f);
            f[k] = in(0.1f, 10.0f);
            pb[k] = in(0.0f, 5.0f);
        }
        pb[0] = in(0.1f, 5.0f);  // the hero's pdf of its own direction is positive
        const float pl = in(0.1f, 5.0f), p_alpha = in(0.001f, 0.01f);
        const sampled_spectrum<C> rho = q / q[0], beta = f / q[0];
        const auto expect_same = [&](double ratio_form, const sampled_spectrum<C>& path_pdfs, double value) {
            const double pdf_form = value * static_cast<double>(hwss_mis_weight(p_alpha, path_pdfs)) * p_alpha;
            EXPECT_NEAR(ratio_form, pdf_form, 1e-5 * pdf_form) << "trial " << trial;
        };
        for (std::size_t j = 0; j < C; ++j) {
            expect_same(beta[j] / hwss_ratio_sum(rho), q, f[j]);
            sampled_spectrum<C> p_light;  // both strategies could have made the light-sampled vertex
            for (std::size_t k = 0; k < C; ++k) p_light[k] = q[k] * (pl + pb[k]);
            expect_same(beta[j] / (pl * hwss_light_ratio_sum(rho, pb, pl)), p_light, f[j]);
            // an emitter found by BSDF sampling: ratios after the scattering and before it
            const sampled_spectrum<C> rho_after = rho * pb / pb[0], beta_after = beta / pb[0];
            expect_same(beta_after[j] / hwss_emission_ratio_sum(rho_after, rho, pl, pb[0]), p_light, f[j]);
        }
        EXPECT_FLOAT_EQ(balance_heuristic(pl, pb[0]) + balance_heuristic(pb[0], pl), 1.0f);
    }
}

// ---- configuration and presets ------------------------------------------------------------

TEST(Config, AlphaDistributionAndBins) {
    preset::paper cfg;
    EXPECT_EQ(cfg.params.n_thold, 512u);
    EXPECT_EQ(cfg.alpha(0), 0.0f);
    EXPECT_EQ(cfg.alpha(512), 1.0f);
    cfg.params.n_thold = 1;  // N_thold = 1: restricted for the first sample only
    EXPECT_EQ(cfg.alpha(0), 0.0f);
    EXPECT_EQ(cfg.alpha(1), 1.0f);
    cfg.params.domain = {400.0f, 700.0f};
    cfg.params.kernel.widths_nm = {10.0f, 10.0f, 10.0f};
    const auto d = cfg.distribution(cfg.alpha(0));
    EXPECT_EQ(d.domain(), cfg.params.domain);
    EXPECT_NEAR(d.normalisation(), 30.0f / 300.0f, 1e-6f);
    EXPECT_EQ(cfg.bins().count(), 80u);  // the policy's 80 equal bins, as the renderer lays them out
    EXPECT_FLOAT_EQ(static_cast<float>(cfg.bins().nominal_width()), 3.75f);
    EXPECT_EQ(preset::paper_fast{}.bins().count(), 8u);
    EXPECT_EQ(cfg.distribution(cfg.alpha(1)).normalisation(), 1.0f);
    // an illuminant-shaped config gets its base pdf from the caller
    integrator_config<restriction::multi_box<3>, relaxation::linear, 4, bias::propagate_unused, spectral_pdf::illuminant> ic;
    const auto di = ic.distribution(0.5f, spectral_pdf::illuminant(find_illuminant("A")->spectrum()));
    EXPECT_GT(di.pdf(611.0f), di.pdf(464.0f));  // illuminant A is red-heavy
}

TEST(Presets, DispatchByEitherName) {
    EXPECT_EQ(dispatch_preset("paper", []<class P>() { return std::string(P::name); }), "multibox3/linear/C4/propagate");
    EXPECT_EQ(dispatch_preset("multibox3/linear/C4/propagate", []<class P>() { return std::string(P::cli_name); }), "paper");
    EXPECT_EQ(dispatch_preset("hwss-c8", []<class P>() { return P::wavelength_count; }), 8u);
    try {
        dispatch_preset("papr", []<class P>() { return 0; });
        FAIL() << "an unknown preset must throw";
    } catch (const std::invalid_argument& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("'papr'"), std::string::npos);
        for (auto n : preset_names()) EXPECT_NE(msg.find(std::string(n)), std::string::npos) << n;
    }
    std::vector<std::string> seen;
    for_each_preset([&]<class P>() {
        seen.emplace_back(P::cli_name);
        // every preset builds a sane distribution at its first and its N_thold-th sample
        P cfg;
        for (std::uint64_t i : {0ull, 1ull, 511ull, 512ull}) {
            const auto d = cfg.distribution(cfg.alpha(i));
            EXPECT_GT(d.normalisation(), 0.0f) << P::name;
            EXPECT_GT(d.pdf(d.sample(0.5f)), 0.0f) << P::name;
        }
        EXPECT_EQ(cfg.distribution(cfg.alpha(512)).normalisation(), 1.0f) << P::name;
    });
    const auto names = preset_names();
    EXPECT_EQ(seen, std::vector<std::string>(names.begin(), names.end()));
    for (auto required : {"hwss", "paper", "paper-quadratic", "box", "gaussian", "scaled-pdf", "restrict-only", "hwss-c1",
                          "hwss-c8"})
        EXPECT_NE(std::find(names.begin(), names.end(), required), names.end()) << required;
}

// ---- base pdfs ---------------------------------------------------------------------------

TEST(BasePdf, PrimitiveIsTheIntegralOfTheDensity) {
    std::apply(
        [&](const auto&... b) {
            ([&] {
                SCOPED_TRACE(b.name);
                for (double a = 300.0; a < 850.0; a += 23.7) {
                    const double ref = simpson([&](double x) { return b.value.density(x); }, a, a + 11.3, 4096);
                    const double got = b.value.primitive(a + 11.3) - b.value.primitive(a);
                    ASSERT_NEAR(got, ref, 1e-6 * std::max(1.0, std::fabs(ref)));
                    ASSERT_GE(b.value.density(a), 0.0);
                }
            }(), ...);
        },
        iris::test::base_pdfs());
}

TEST(BasePdf, VisibleClosedFormsAgree) {
    const spectral_pdf::visible v;
    for (const spectral_domain d : {spectral_domain{}, spectral_domain{400.0f, 700.0f}, spectral_domain{360.0f, 830.0f}}) {
        EXPECT_NEAR(simpson([&](double x) { return v.pdf(x, d); }, d.min_nm, d.max_nm, 4096), 1.0, 1e-9);
        const restricted_distribution dist(v, restriction::unrestricted{}, 1.0f, d);
        for (double u = 0.0; u < 1.0; u += 0.0625) {
            const double l = v.sample(u, d);
            ASSERT_TRUE(d.contains(static_cast<float>(l)));
            // the closed-form inverse and the tabulated one agree to the 1 nm cells' resolution
            ASSERT_NEAR(dist.cdf(static_cast<float>(l)), u, 2e-4);
        }
        EXPECT_EQ(v.sample(std::numeric_limits<double>::quiet_NaN(), d), d.min_nm);
    }
    // pbrt-v4's normalisation on 360–830 nm: 0.0039398042 at the peak
    EXPECT_NEAR(v.pdf(538.0, {360.0f, 830.0f}), 0.0039398042, 1e-8);
}

TEST(BasePdf, TabulatedRejectsBadTables) {
    using T = spectral_pdf::tabulated;
    EXPECT_THROW(T({1.0}, {1.0}), std::invalid_argument);
    EXPECT_THROW(T({1.0, 2.0}, {1.0}), std::invalid_argument);
    EXPECT_THROW(T({2.0, 1.0}, {1.0, 1.0}), std::invalid_argument);
    EXPECT_THROW(T({1.0, 2.0}, {1.0, -1.0}), std::invalid_argument);
    EXPECT_THROW(T({1.0, 2.0}, {1.0, std::numeric_limits<double>::infinity()}), std::invalid_argument);
    EXPECT_THROW(T({-1.0, 2.0}, {1.0, 1.0}), std::invalid_argument);
    EXPECT_THROW(T({1.0, 2e6}, {1.0, 1.0}), std::invalid_argument);
    EXPECT_NO_THROW(T({1.0, 2.0}, {0.0, 0.0}));
    const T big({400.0, 500.0}, {1e300, 1e300});  // rescaled: no overflow in the primitive
    EXPECT_TRUE(std::isfinite(big.primitive(500.0)));
    EXPECT_DOUBLE_EQ(big.density(450.0), 1.0);
}

TEST(BasePdf, IlluminantOfSeveralEmittersIsTheirPowerWeightedSum) {
    const auto d65 = find_illuminant("D65")->spectrum(), a = find_illuminant("A")->spectrum();
    const std::vector<tabulated_spectrum> spds = {d65, a};
    const std::vector<double> weights = {2.0, 0.5};
    const spectral_pdf::illuminant mix(spds, weights), one(d65), two(a);
    // shapes are rescaled to a peak of 1, so compare ratios
    const double k = mix.density(560.0) / ((2.0 * d65(560.0) + 0.5 * a(560.0)) * cie::y_bar(560.0));
    for (double l : {400.0, 455.0, 610.0, 700.0})
        EXPECT_NEAR(mix.density(l), k * (2.0 * d65(l) + 0.5 * a(l)) * cie::y_bar(l), 1e-9) << l;
    (void)one;
    (void)two;
    EXPECT_THROW(spectral_pdf::illuminant(spds, std::vector<double>{1.0}), std::invalid_argument);
    EXPECT_THROW(spectral_pdf::illuminant(spds, std::vector<double>{1.0, -1.0}), std::invalid_argument);
    EXPECT_EQ(mix.density(300.0), 0.0);  // ȳ = 0 below 360 nm
}

// ---- bins and random numbers ---------------------------------------------------------------

TEST(BinLayout, CoversTheDomainOnce) {
    for (const spectral_domain d : {spectral_domain{}, spectral_domain{400.0f, 700.0f}, spectral_domain{380.0f, 383.3f}}) {
        for (float w : {5.0f, 7.0f, 0.0f, -3.0f, 1e-3f}) {
            const bias::bin_layout bins(d, w);
            ASSERT_GE(bins.count(), 1u);
            ASSERT_LE(bins.count(), bias::bin_layout::max_count);
            double total = 0.0;
            for (std::size_t b = 0; b < bins.count(); ++b) {
                ASSERT_GT(bins.width(b), 0.0);
                if (b > 0) {
                    ASSERT_DOUBLE_EQ(bins.lower(b), bins.lower(b - 1) + bins.width(b - 1));
                }
                total += bins.width(b);
                for (float u : {0.0f, 0.5f, eps_below_one}) {
                    const float l = bins.lambda(b, u);
                    ASSERT_GE(l, static_cast<float>(bins.lower(b)));
                    ASSERT_LE(l, static_cast<float>(bins.lower(b) + bins.width(b)));
                }
            }
            ASSERT_NEAR(total, d.width(), 1e-6 * d.width());
        }
    }
    const bias::bin_layout bins;
    const auto wl = bins.jittered<84>(0.5f);
    EXPECT_FLOAT_EQ(wl[0], 382.5f);
    EXPECT_FLOAT_EQ(wl.pdf(0), 0.2f);
    EXPECT_EQ(wl.pdf(80), 0.0f);  // past count(): contributes nothing
    const auto b7 = bias::bin_layout::with_count({400.0f, 700.0f}, 7);
    EXPECT_EQ(b7.count(), 7u);
    EXPECT_NEAR(b7.width(6), 300.0 / 7.0, 1e-9);
}

TEST(CounterRng, IsAPureFunctionOfItsKey) {
    iris::counter_rng a(1, 2, 3), b(1, 2, 3), c(1, 2, 4);
    for (int i = 0; i < 100; ++i) {
        const float x = a.next();
        ASSERT_EQ(x, b.next());
        ASSERT_GE(x, 0.0f);
        ASSERT_LT(x, 1.0f);
    }
    EXPECT_EQ(iris::counter_rng(1, 2, 3).at(57), a.at(57));
    EXPECT_NE(iris::counter_rng(1, 2, 3).at(0), c.at(0));
    EXPECT_EQ(a.dimension(), 100u);
}

}  // namespace
