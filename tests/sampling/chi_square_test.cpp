// Goodness of fit of `sample` against `pdf` (docs/method.md §5): for every kernel × base pdf at
// α ∈ {0, 0.3, 1}, and for each of the C hero-rotated wavelengths separately (each must
// be marginally p_α-distributed, docs/method.md §3).
//
// Method: N = 100 000 draws (fixed seeds) histogrammed into 457 equal bins over the
// range where p_α > 0; expected counts are N ∫_bin pdf, exact from the distribution's
// cells (a separate unit test shows pdf() is exactly that piecewise-constant function);
// adjacent bins are pooled until each expects ≥ 5; Pearson's χ² with (groups − 1) dof.
// Confidence: family-wise significance 0.01 over every test in this file (Šidák):
// per test α' = 1 − 0.99^(1/m), m counted below (154 today, so α' ≈ 6.5e-5). A correct
// sampler makes this file fail with probability ≤ 1 %; with the fixed seeds the outcome
// is deterministic (IRIS_TEST_VERBOSE=1 prints m, α' and the smallest p). The tests of
// the C rotations of one u are dependent; treating them as independent, as Šidák does,
// errs on the conservative side for such positively dependent tests.
//
// Negative controls show the test can fail: samples of one distribution are tested
// against a slightly different pdf (σ 7.98 vs 8.5 nm), against a different base pdf, and
// with the right mass per cell but the wrong shape inside the cells; each must be
// rejected at the same α'.
//
// Left out: the width-0 box (its window is 16 float ulps wide, so its samples are
// quantised and no binning can test them; its unit test checks it instead).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <vector>

#include "cases.hpp"
#include "stats.hpp"

namespace {

using namespace iris;
using iris::test::chi2_result;

constexpr int draws = 100000;
constexpr int bins = 457;  // prime: bin edges never line up with the 1 nm cells
constexpr double family_alpha = 0.01;

/// \brief The range where `pdf` > 0: from the first to the last cell with mass.
template <class D>
std::pair<double, double> support_range(const D& d) {
    double lo = d.domain().max_nm, hi = d.domain().min_nm;
    for (std::size_t i = 0; i < d.cell_count(); ++i) {
        if (d.cell_density(i) > 0.0f) {
            lo = std::min(lo, static_cast<double>(d.cell(i).lo));
            hi = std::max(hi, static_cast<double>(d.cell(i).hi));
        }
    }
    return {lo, hi};
}

/// \brief χ² of the wavelengths produced by `draw(u)` against the pdf of `reference`,
/// binned over `reference`'s support. A sample outside it is an error.
template <class D, class Draw>
chi2_result fit(const D& reference, Draw&& draw, std::uint64_t seed) {
    const auto [lo, hi] = support_range(reference);
    const double width = (hi - lo) / bins;
    std::vector<double> expected(bins, 0.0), observed(bins, 0.0);
    for (std::size_t i = 0; i < reference.cell_count(); ++i) {  // exact ∫_bin pdf
        const double a = reference.cell(i).lo, b = reference.cell(i).hi, p = reference.cell_density(i);
        if (p <= 0.0) continue;
        for (int k = std::max(0, static_cast<int>((a - lo) / width) - 1);
             k < bins && lo + k * width < b; ++k) {
            const double overlap = std::min(b, lo + (k + 1) * width) - std::max(a, lo + k * width);
            if (overlap > 0.0) expected[static_cast<std::size_t>(k)] += draws * p * overlap;
        }
    }
    double mass = 0.0;
    for (double e : expected) mass += e;
    EXPECT_NEAR(mass, draws, 1e-5 * draws) << "expected counts must sum to N (the pdf's mass is 1)";
    iris::counter_rng rng(seed);
    for (int n = 0; n < draws; ++n) {
        const double l = draw(rng.next());
        if (!(l >= lo && l <= hi)) {
            chi2_result r;
            r.impossible = "sample " + std::to_string(l) + " outside the support [" + std::to_string(lo) + ", " +
                           std::to_string(hi) + "]";
            return r;
        }
        observed[std::min<std::size_t>(bins - 1, static_cast<std::size_t>((l - lo) / width))] += 1.0;
    }
    return iris::test::chi_square(expected, observed);
}

struct fit_case {
    std::string name;
    std::function<chi2_result()> run;
};

/// \brief Every sample-vs-pdf case: kernel × base pdf × α, and the rotations.
std::vector<fit_case> all_cases() {
    std::vector<fit_case> cases;
    std::uint64_t seed = 1;
    iris::test::for_each_pair([&](const auto& k, const auto& base) {
        if (k.name == "box-width0") return;
        for (float a : {0.0f, 0.3f, 1.0f}) {
            const std::string name = k.name + " × " + base.name + " α=" + std::to_string(a);
            cases.push_back({name, [kv = k.value, bv = base.value, a, s = seed++] {
                                 const restricted_distribution d(bv, kv, a);
                                 return fit(d, [&](float u) { return d.sample(u); }, s);
                             }});
        }
    });
    // each rotated wavelength j of C is marginally p_α
    auto rotations = [&]<std::size_t C>(std::string name, auto dist_factory) {
        for (std::size_t j = 0; j < C; ++j)
            cases.push_back({name + " C=" + std::to_string(C) + " j=" + std::to_string(j),
                             [dist_factory, j, s = seed++] {
                                 const auto d = dist_factory();
                                 return fit(d, [&](float u) { return d.template sample_wavelengths<C>(u)[j]; }, s);
                             }});
    };
    const auto paper = [] { return restricted_distribution(spectral_pdf::uniform{}, restriction::multi_box<3>{}, 0.0f); };
    const auto smooth = [] { return restricted_distribution(spectral_pdf::visible{}, restriction::gaussian{}, 0.3f); };
    const auto led = [] {
        return restricted_distribution(spectral_pdf::illuminant(find_illuminant("LED-RGB1")->spectrum()),
                                       restriction::box{}, 0.5f);
    };
    rotations.template operator()<4>("multibox3 × uniform α=0", paper);
    rotations.template operator()<3>("multibox3 × uniform α=0", paper);
    rotations.template operator()<4>("gaussian × visible α=0.3", smooth);
    rotations.template operator()<8>("box × LED-RGB1 α=0.5", led);
    return cases;
}

TEST(ChiSquare, SampleMatchesPdfForEveryKernelBasePdfAndRotation) {
    const auto cases = all_cases();
    const double alpha = iris::test::sidak(family_alpha, cases.size());
    RecordProperty("tests", static_cast<int>(cases.size()));
    double min_p = 1.0;
    std::string min_name;
    for (const auto& c : cases) {
        const chi2_result r = c.run();
        if (r.p_value < min_p) {
            min_p = r.p_value;
            min_name = c.name;
        }
        ASSERT_TRUE(r.impossible.empty()) << c.name << ": " << r.impossible;
        EXPECT_GE(r.p_value, alpha) << c.name << ": χ²=" << r.statistic << " dof=" << r.dof << " p=" << r.p_value
                                    << " < α'=" << alpha;
        EXPECT_GE(r.dof, 5u) << c.name << ": too few groups to test anything";
    }
    if (std::getenv("IRIS_TEST_VERBOSE"))
        std::printf("%zu χ² tests, α' = %.3g, smallest p = %.3g (%s)\n", cases.size(), alpha, min_p, min_name.c_str());
}

// ---- negative controls: the same test, at the same α', must reject these -------------------

double control_alpha() { return iris::test::sidak(family_alpha, all_cases().size()); }

TEST(ChiSquare, RejectsASlightlyWrongWidth) {
    const restricted_distribution truth(spectral_pdf::uniform{}, restriction::gaussian{580.0f, 7.98f}, 0.0f);
    const restricted_distribution claimed(spectral_pdf::uniform{}, restriction::gaussian{580.0f, 8.5f}, 0.0f);
    const chi2_result r = fit(claimed, [&](float u) { return truth.sample(u); }, 99);
    EXPECT_LT(r.p_value, control_alpha()) << "χ²=" << r.statistic << " dof=" << r.dof;
}

TEST(ChiSquare, RejectsTheWrongBasePdf) {
    const restricted_distribution truth(spectral_pdf::visible{}, restriction::unrestricted{}, 1.0f);
    const restricted_distribution claimed(spectral_pdf::uniform{}, restriction::unrestricted{}, 1.0f);
    const chi2_result r = fit(claimed, [&](float u) { return truth.sample(u); }, 98);
    EXPECT_LT(r.p_value, control_alpha()) << "χ²=" << r.statistic << " dof=" << r.dof;
}

TEST(ChiSquare, RejectsTheWrongShapeInsideCells) {
    // an inverse CDF that is right cell by cell (1 nm cells from 380 nm) but puts the
    // samples at t² instead of t inside each cell
    const restricted_distribution d(spectral_pdf::visible{}, restriction::unrestricted{}, 1.0f);
    const chi2_result r = fit(
        d,
        [&](float u) {
            const double l = d.sample(u), lo = std::floor(l), t = l - lo;
            return lo + t * t;
        },
        97);
    EXPECT_LT(r.p_value, control_alpha()) << "χ²=" << r.statistic << " dof=" << r.dof;
}

TEST(ChiSquare, TailProbabilitiesAreRight) {
    // the χ² tail against tabulated quantiles (dof, x at p = 0.05 and 0.01)
    EXPECT_NEAR(iris::test::chi2_sf(3.841459, 1), 0.05, 1e-6);
    EXPECT_NEAR(iris::test::chi2_sf(18.307038, 10), 0.05, 1e-6);
    EXPECT_NEAR(iris::test::chi2_sf(135.806723, 100), 0.01, 1e-6);
    EXPECT_NEAR(iris::test::normal_two_sided(1.959964), 0.05, 1e-6);
    EXPECT_NEAR(iris::test::sidak(0.01, 1), 0.01, 1e-12);
}

}  // namespace
