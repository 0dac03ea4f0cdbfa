// The B term's lattice tables (iris/render/bins.hpp) against direct evaluation.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <iris/render/bins.hpp>
#include <iris/sampling/random.hpp>
#include <iris/spectrum/named.hpp>
#include <iris/spectrum/rgb_upsampling.hpp>

namespace {

using lattice = iris::bin_lattice<80>;

// jitters at the ends of [0, 1) and where u·K lands on or next to a lattice node
std::vector<float> jitters() {
    std::vector<float> u = {0.0f, 1e-7f, 0.2f, std::nextafter(0.2f, 0.0f), 0.4f, 0.5f, 0.8f, std::nextafter(1.0f, 0.0f)};
    iris::counter_rng rng(7, 0, 0);
    for (int i = 0; i < 64; ++i) u.push_back(rng.next());
    return u;
}

// domains and bin counts: (K, whole-nm lattice?) as bins.hpp promises
TEST(BinLattice, StepsPerBinFollowTheDomain) {
    EXPECT_EQ(iris::bin_lattice<80>(380.0f, 780.0f).steps(), 5u);   // h = 1 nm
    EXPECT_EQ(iris::bin_lattice<80>(400.0f, 700.0f).steps(), 15u);  // Δ = 3.75 nm, h = 0.25 nm
    EXPECT_EQ(iris::bin_lattice<8>(380.0f, 780.0f).steps(), 50u);   // paper-fast
    EXPECT_EQ(iris::bin_lattice<7>(380.0f, 780.0f).steps(), 400u);  // h = 1/7 nm: whole nm are nodes
    EXPECT_EQ(iris::bin_lattice<80>(380.3f, 780.0f).steps(), 5u);   // no whole-nm lattice: ≈ 1 nm
}

// One estimator: the renderer's λ_b is the sampling layer's bin_layout::lambda, bit for bit
// (the estimator tests and the fuzzer check that function), on the domains above.
template <std::size_t B>
void expect_layout_wavelengths(float lo, float hi) {
    const iris::bin_lattice<B> l(lo, hi);
    const auto layout = iris::bias::bin_layout::with_count({lo, hi}, B);
    ASSERT_EQ(layout.count(), B);
    for (float u : jitters())
        for (std::size_t b = 0; b < B; ++b) ASSERT_EQ(l.lambda(b, u), layout.lambda(b, u)) << "u " << u << " bin " << b;
}

TEST(BinLattice, WavelengthsAreTheBinLayouts) {
    expect_layout_wavelengths<80>(380.0f, 780.0f);
    expect_layout_wavelengths<80>(400.0f, 700.0f);
    expect_layout_wavelengths<80>(380.0f, 779.0f);
    expect_layout_wavelengths<8>(380.0f, 780.0f);
    expect_layout_wavelengths<7>(380.0f, 780.0f);
    expect_layout_wavelengths<80>(380.3f, 780.0f);
}

template <std::size_t B>
void expect_positions_inside(float lo, float hi) {
    const iris::bin_lattice<B> l(lo, hi);
    for (float u : jitters()) {
        const auto p = l.position(u);
        EXPECT_LT(p.row, l.steps());
        EXPECT_GE(p.t, 0.0f);
        EXPECT_LE(p.t, 1.0f);
        // row and fraction put every bin at its own wavelength
        for (std::size_t b : {std::size_t{0}, B / 2, B - 1}) {
            const double at = l.node(b, p.row) + static_cast<double>(p.t) * (l.node(b, p.row + 1) - l.node(b, p.row));
            EXPECT_NEAR(at, static_cast<double>(l.lambda(b, u)), 2e-4) << "u " << u << " bin " << b;
        }
    }
    EXPECT_LE(l.node(B - 1, l.steps()), static_cast<double>(hi));  // never past λmax
}

TEST(BinLattice, PositionStaysInsideTheTable) {
    expect_positions_inside<80>(380.0f, 780.0f);
    expect_positions_inside<80>(400.0f, 700.0f);
    expect_positions_inside<80>(380.0f, 779.0f);  // 4.9875 nm bins: float width is inexact
    expect_positions_inside<8>(380.0f, 780.0f);
    expect_positions_inside<7>(380.0f, 780.0f);
    expect_positions_inside<80>(380.3f, 780.0f);
}

// With a whole-nm lattice every table with knots on whole nm is reproduced exactly (to float
// rounding); a table the lattice would not reproduce is evaluated directly — exact too.
template <std::size_t B>
void expect_reproduced(const iris::tabulated_spectrum& s, float lo, float hi, bool on_lattice, const char* what) {
    const iris::bin_lattice<B> l(lo, hi);
    const iris::binned_spectrum<B> binned(l, s);
    EXPECT_EQ(binned.on_lattice(), on_lattice) << what;
    for (float u : jitters()) {
        const auto got = binned(l.position(u));
        for (std::size_t b = 0; b < B; ++b) {
            const double want = s(static_cast<double>(l.lambda(b, u)));
            ASSERT_NEAR(got[b], want, 2e-5 * std::fabs(want) + 1e-6) << what << " u " << u << " bin " << b;
        }
    }
}

TEST(BinnedSpectrum, ReproducesTablesExactly) {
    for (const char* name : {"D65", "A", "LED-B1", "LED-RGB1"}) {
        const auto s = iris::find_illuminant(name)->spectrum();
        expect_reproduced<80>(s, 380.0f, 780.0f, true, name);
        expect_reproduced<80>(s, 400.0f, 700.0f, true, name);
        expect_reproduced<8>(s, 380.0f, 780.0f, true, name);
        expect_reproduced<7>(s, 380.0f, 780.0f, true, name);
        expect_reproduced<80>(s, 380.3f, 780.0f, false, name);  // no whole-nm lattice: direct
    }
    // a box emitter 450–650 nm in zero mode: a step inside the domain → evaluated directly
    // (on the lattice its edges would be 1 nm ramps, +0.5 % in ∫, found in review)
    const auto box = iris::tabulated_spectrum(std::vector<double>{450, 650}, std::vector<double>{1, 1});
    expect_reproduced<80>(box, 380.0f, 780.0f, false, "box 450-650");
    // knots off the lattice → direct
    std::vector<double> ramp(50);
    for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = 0.1 + 0.01 * static_cast<double>(i * i % 7);
    expect_reproduced<80>(iris::tabulated_spectrum::uniform(360.5, 10.0, ramp), 380.0f, 780.0f, false, "knots at .5 nm");
    // an sRGB-upsampled reflectance (1 nm, 360–830) → on the lattice
    expect_reproduced<80>(iris::reflectance_from_srgb({0.8, 0.3, 0.1}), 380.0f, 780.0f, true, "sRGB reflectance");
    // the CMFs as the integrator tabulates them
    const iris::bin_lattice<80> l(380.0f, 780.0f);
    const iris::binned_spectrum<80> y(l, iris::tabulated_spectrum::uniform(iris::cie::cmf_lambda_min, 1.0,
                                                                           iris::data::cie1931::y_bar));
    EXPECT_TRUE(y.on_lattice());
    for (float u : jitters()) {
        const auto got = y(l.position(u));
        for (std::size_t b = 0; b < 80; ++b) ASSERT_NEAR(got[b], iris::cie::y_bar(l.lambda(b, u)), 2e-6);
    }
}

// Smooth models (refractive indices) are interpolated on the lattice: within the error bound.
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
    EXPECT_TRUE(t.albedo[0].on_lattice());
    EXPECT_TRUE(t.emission[0].on_lattice());
    EXPECT_TRUE(t.x_bar.on_lattice() && t.y_bar.on_lattice() && t.z_bar.on_lattice());
    const auto p = t.lattice.position(0.5f);
    EXPECT_NEAR(t.albedo[0](p)[0], 0.25 + 0.5 * 2.5 / 400.0, 1e-6);  // λ = 382.5 nm on the linear ramp
    EXPECT_FLOAT_EQ(t.eta[1](p)[40], 1.5f);
    EXPECT_FLOAT_EQ(t.albedo[1](p)[40], 0.0f);  // a dielectric has no albedo table
}

// A medium whose σ_a is one number (or none) is read once for every bin (propagation.hpp's
// `attenuate` and `light_absorbed` take one exponential): `constant` must hold exactly when
// every bin reads the same value at every jitter, so the shortcut gives the same numbers.
TEST(BinTables, GreyAbsorptionIsTheSameNumberAtEveryBin) {
    iris::scene_desc s;
    const auto flat = [](double v) { return iris::tabulated_spectrum(std::vector<double>{360, 830}, std::vector<double>{v, v}, iris::outside::clamp); };
    iris::material::dielectric grey{iris::constant_ior{1.5}, 0.0f};
    grey.absorption = flat(0.7);
    iris::material::dielectric chromatic = grey;
    chromatic.absorption = iris::tabulated_spectrum(std::vector<double>{360, 600, 830}, std::vector<double>{0.7, 0.7, 0.7000001},
                                                    iris::outside::clamp);  // grey but for the last nanometres
    iris::material::dielectric clear{iris::constant_ior{1.5}, 0.0f};
    s.materials = {grey, chromatic, clear};
    s.medium = iris::medium_desc{flat(0.0), std::nullopt};  // the scene's medium: absorbs nothing
    const iris::bin_tables<80> t(s);
    ASSERT_EQ(t.grey_absorption.size(), 4u);  // three solids and the scene's medium
    EXPECT_EQ(t.grey_absorption[0], 1);
    EXPECT_EQ(t.grey_absorption[1], 0);
    EXPECT_EQ(t.grey_absorption[2], 1);  // no absorption: zeros
    EXPECT_EQ(t.grey_absorption[3], 1);
    for (std::uint32_t m = 0; m < 4; ++m) {
        if (!t.grey_absorption[m]) continue;
        std::array<float, 80> scratch;
        for (float u : jitters()) {
            const auto v = t.absorption[m].at(t.lattice.position(u), scratch);
            for (std::size_t b = 1; b < 80; ++b) ASSERT_EQ(v[b], v[0]) << "medium " << m << " bin " << b << " u " << u;
        }
    }
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
    // a NaN wavelength reads the first node, never outside the table
    const iris::lattice_spectrum d65(iris::find_illuminant("D65")->spectrum(), 380.0f, 780.0f);
    const iris::sampled_wavelengths<1> nan({std::numeric_limits<float>::quiet_NaN()}, {1.0f});
    EXPECT_FLOAT_EQ(d65(nan)[0], static_cast<float>(iris::find_illuminant("D65")->spectrum()(380.0)));
}

}  // namespace
