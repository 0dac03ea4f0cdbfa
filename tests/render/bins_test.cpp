// The B term's lattice tables (iris/render/bins.hpp) against direct evaluation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include <iris/render/bins.hpp>
#include <iris/sampling/random.hpp>
#include <iris/spectrum/named.hpp>

namespace {

using lattice = iris::bin_lattice<80>;

// jitters at the ends of [0, 1) and where u·K lands on or next to a lattice node
std::vector<float> jitters() {
    std::vector<float> u = {0.0f, 1e-7f, 0.2f, std::nextafter(0.2f, 0.0f), 0.4f, 0.5f, 0.8f, std::nextafter(1.0f, 0.0f)};
    iris::counter_rng rng(7, 0, 0);
    for (int i = 0; i < 64; ++i) u.push_back(rng.next());
    return u;
}

TEST(BinLattice, PositionStaysInsideTheTable) {
    const lattice l(380.0f, 780.0f);
    EXPECT_FLOAT_EQ(l.bin_width(), 5.0f);
    for (float u : jitters()) {
        const auto p = l.position(u);
        EXPECT_LT(p.row, lattice::steps);
        EXPECT_GE(p.t, 0.0f);
        EXPECT_LE(p.t, 1.0f);
        // row and fraction put every bin at its own wavelength
        for (std::size_t b : {std::size_t{0}, std::size_t{41}, std::size_t{79}}) {
            const double at = l.node(b, p.row) + static_cast<double>(p.t) * (l.node(b, p.row + 1) - l.node(b, p.row));
            EXPECT_NEAR(at, static_cast<double>(l.lambda(b, u)), 1e-4) << "u " << u << " bin " << b;
        }
    }
}

// On 380–780 nm with 80 bins the lattice step is 1 nm, so a 1 nm or 5 nm table is
// reproduced exactly (up to float rounding of the blend).
TEST(BinnedSpectrum, ReproducesTablesWhoseKnotsAreOnTheLattice) {
    const lattice l(380.0f, 780.0f);
    for (const char* name : {"D65", "A", "LED-B1", "LED-RGB1"}) {
        const auto s = iris::find_illuminant(name)->spectrum();
        const iris::binned_spectrum<80> binned(l, s);
        for (float u : jitters()) {
            const auto got = binned(l.position(u));
            for (std::size_t b = 0; b < 80; ++b) {
                const double want = s(static_cast<double>(l.lambda(b, u)));
                ASSERT_NEAR(got[b], want, 2e-5 * std::fabs(want) + 1e-6) << name << " u " << u << " bin " << b;
            }
        }
    }
    const iris::binned_spectrum<80> y(l, [](double x) { return iris::cie::y_bar(x); });
    for (float u : jitters()) {
        const auto got = y(l.position(u));
        for (std::size_t b = 0; b < 80; ++b) ASSERT_NEAR(got[b], iris::cie::y_bar(l.lambda(b, u)), 2e-6);
    }
}

// Smooth models and off-lattice domains differ by the interpolation error only.
TEST(BinnedSpectrum, SmoothModelsWithinTheInterpolationError) {
    const auto glass = iris::find_glass("N-SF11")->sellmeier;  // strongly dispersive
    for (const auto& [lo, hi] : {std::pair{380.0f, 780.0f}, std::pair{400.0f, 700.0f}}) {
        const lattice l(lo, hi);
        const iris::binned_spectrum<80> eta(l, [&](double x) { return glass.n(x); });
        for (float u : jitters()) {
            const auto got = eta(l.position(u));
            // |error| ≤ h²/8 · max|n″|; n″ < 2e-5 /nm² above 380 nm for N-SF11, h ≤ 1 nm → 2.5e-6
            for (std::size_t b = 0; b < 80; ++b)
                ASSERT_NEAR(got[b], glass.n(l.lambda(b, u)), 3e-6) << lo << "-" << hi << " bin " << b;
        }
    }
}

TEST(BinTables, OneEntryPerMaterialAndEmitter) {
    iris::scene_desc s;
    s.materials.emplace_back(iris::material::diffuse{iris::tabulated_spectrum::uniform(380.0, 400.0, std::vector<double>{0.25, 0.75})});
    s.materials.emplace_back(iris::material::dielectric{iris::constant_ior{1.5}, 0.0f});
    s.emitters.push_back({"D65", iris::find_illuminant("D65")->spectrum(), false});
    const iris::bin_tables<80> t(s);
    ASSERT_EQ(t.albedo.size(), 2u);
    ASSERT_EQ(t.eta.size(), 2u);
    ASSERT_EQ(t.emission.size(), 1u);
    const auto p = t.lattice.position(0.5f);
    EXPECT_NEAR(t.albedo[0](p)[0], 0.25 + 0.5 * 2.5 / 400.0, 1e-6);  // λ = 382.5 nm on the linear ramp
    EXPECT_FLOAT_EQ(t.eta[1](p)[40], 1.5f);
    EXPECT_FLOAT_EQ(t.albedo[1](p)[40], 0.0f);  // a dielectric has no albedo table
}

}  // namespace

namespace {

// The hero wavelengths' lattice tables reproduce the scene's tables exactly (to float
// rounding) where their knots are on the 1 nm lattice, and fall back to the table itself
// where they are not: the hero path never sees an interpolation the scene did not ask for.
TEST(LatticeSpectrum, ExactOnTheLatticeAndFallsBackOffIt) {
    iris::counter_rng rng(3, 0, 0);
    auto check = [&](const iris::tabulated_spectrum& s, float lo, float hi, bool expect_lattice, const char* what) {
        const iris::lattice_spectrum l(s, lo, hi);
        EXPECT_EQ(l.exact_lattice(), expect_lattice) << what;
        for (int i = 0; i < 2000; ++i) {
            const float u = i == 0 ? 0.0f : i == 1 ? 1.0f : rng.next();
            const iris::sampled_wavelengths<1> wl({lo + u * (hi - lo)}, {1.0f});
            const double want = s(static_cast<double>(wl[0]));
            ASSERT_NEAR(l(wl)[0], want, 1e-6 * std::fabs(want) + 1e-9) << what << " at " << wl[0];
        }
    };
    check(iris::find_illuminant("D65")->spectrum(), 380.0f, 780.0f, true, "D65 (5 nm)");
    check(iris::find_illuminant("LED-B1")->spectrum(), 380.0f, 780.0f, true, "LED-B1 (1 nm)");
    check(iris::find_illuminant("A")->spectrum(), 400.0f, 700.0f, true, "A on 400-700");
    // knots off the lattice, a table that does not cover the domain, a fractional domain
    std::vector<double> ramp(50);
    for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = 0.1 + 0.01 * static_cast<double>(i * i % 7);
    check(iris::tabulated_spectrum::uniform(360.5, 10.0, ramp), 380.0f, 780.0f, false, "knots at .5 nm");
    check(iris::tabulated_spectrum::uniform(400.0, 5.0, ramp), 380.0f, 780.0f, false, "table starts inside");
    check(iris::find_illuminant("D65")->spectrum(), 380.0f, 779.5f, false, "fractional domain");
}

}  // namespace
