// Jakob & Hanika's sigmoid-polynomial upsampling (iris/spectrum/rgb_sigmoid.hpp): the
// round trip over the sRGB cube, the range and shape of the spectra, greys, black and
// white, bad inputs, and the illuminant form. Tolerances come from the measurements in
// docs/rgb-upsampling.md (table resolution 32), each with the margin stated beside it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iris/spectrum/color.hpp>
#include <iris/spectrum/rgb_sigmoid.hpp>
#include <iris/spectrum/rgb_upsampling.hpp>
#include <limits>
#include <vector>

namespace {

static_assert(iris::Spectrum<iris::sigmoid_polynomial>);
static_assert(iris::Spectrum<iris::rgb_illuminant>);

std::vector<iris::rgb> cube_grid(int n) {
    std::vector<iris::rgb> v;
    const double d = n - 1;
    for (int r = 0; r < n; ++r)
        for (int g = 0; g < n; ++g)
            for (int b = 0; b < n; ++b) v.push_back({r / d, g / d, b / d});
    return v;
}

double max_abs_diff(const iris::rgb& a, const iris::rgb& b) {
    return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

iris::rgb round_trip(const iris::rgb& c) {
    return iris::xyz_to_linear_srgb(iris::reflectance_xyz_d65(iris::rgb_to_sigmoid(c)));
}

TEST(RgbSigmoid, TableHasTheDocumentedShape) {
    namespace d = iris::data::rgb2spec_srgb;
    EXPECT_EQ(d::coefficients.size(), 9 * d::resolution * d::resolution * d::resolution);
    EXPECT_EQ(d::z_nodes.front(), 0.0f);
    EXPECT_EQ(d::z_nodes.back(), 1.0f);
    EXPECT_TRUE(std::is_sorted(d::z_nodes.begin(), d::z_nodes.end()));
    EXPECT_TRUE(std::all_of(d::coefficients.begin(), d::coefficients.end(), [](float v) { return std::isfinite(v); }));
}

// Round trip over a 17³ grid of the cube. Measured at resolution 32 (docs/rgb-upsampling.md):
// max |Δrgb| = 0.0032, mean 0.00088 (the error is the trilinear interpolation of the
// coefficients between the fitted nodes, which reproduce their colours to ΔE < 2e-4).
// Tolerances: max 0.005 and mean 0.0015, about 1.5× the measured values.
TEST(RgbSigmoid, RoundTripsTheSrgbCube) {
    double worst = 0.0, sum = 0.0;
    iris::rgb worst_colour;
    const auto grid = cube_grid(17);
    for (const auto& c : grid) {
        const double e = max_abs_diff(round_trip(c), c);
        if (e > worst) worst_colour = c;
        worst = std::max(worst, e);
        sum += e;
    }
    EXPECT_LT(worst, 0.005) << "at (" << worst_colour.r << ", " << worst_colour.g << ", " << worst_colour.b << ")";
    EXPECT_LT(sum / static_cast<double>(grid.size()), 0.0015);
}

// The primaries and secondaries, the corners of the cube: the most saturated colours.
// Each is an exact table node (x, y ∈ {0, 1}, z = 1), so only the fit's error remains;
// measured ≤ 3.3e-6 in linear sRGB, tolerance 1e-4.
TEST(RgbSigmoid, CubeCornersAreReproduced) {
    for (const iris::rgb c : {iris::rgb{1, 0, 0}, iris::rgb{0, 1, 0}, iris::rgb{0, 0, 1}, iris::rgb{1, 1, 0},
                              iris::rgb{0, 1, 1}, iris::rgb{1, 0, 1}}) {
        EXPECT_LT(max_abs_diff(round_trip(c), c), 1e-4) << c.r << " " << c.g << " " << c.b;
    }
}

TEST(RgbSigmoid, SpectraStayInTheUnitInterval) {
    auto grid = cube_grid(17);
    for (const iris::rgb c : {iris::rgb{2, -1, 0.5}, iris::rgb{1e9, 0.3, -1e9}, iris::rgb{0.999, 1, 0.998}})
        grid.push_back(c);  // out-of-cube inputs are clamped
    for (const auto& c : grid) {
        const auto s = iris::rgb_to_sigmoid(c);
        for (int l = 360; l <= 830; ++l) {
            const double v = s(static_cast<double>(l));
            const float f = s(static_cast<float>(l));
            ASSERT_TRUE(v >= 0.0 && v <= 1.0) << v << " at " << l << " nm";
            ASSERT_TRUE(f >= 0.0f && f <= 1.0f) << f << " at " << l << " nm";
        }
    }
}

// The float form (per-sample) and the double form (Spectrum) of the same coefficients.
// Measured max difference 1.0e-5 over the 17³ grid, 360–830 nm (float rounding of x, whose
// terms reach ~1e3 for dark saturated colours); tolerance 1e-4.
TEST(RgbSigmoid, FloatAndDoubleEvaluationAgree) {
    double worst = 0.0;
    for (const auto& c : cube_grid(17)) {
        const auto s = iris::rgb_to_sigmoid(c);
        for (int l = 360; l <= 830; ++l)
            worst =
                std::max(worst, std::abs(static_cast<double>(s(static_cast<float>(l))) - s(static_cast<double>(l))));
    }
    EXPECT_LT(worst, 1e-4);
}

TEST(RgbSigmoid, WhiteBlackAndGreysAreFlat) {
    const auto white = iris::rgb_to_sigmoid({1, 1, 1});
    const auto black = iris::rgb_to_sigmoid({0, 0, 0});
    for (int l = 300; l <= 900; l += 7) {
        EXPECT_EQ(white(static_cast<double>(l)), 1.0);
        EXPECT_EQ(white(static_cast<float>(l)), 1.0f);
        EXPECT_EQ(black(static_cast<double>(l)), 0.0);
        EXPECT_EQ(black(static_cast<float>(l)), 0.0f);
    }
    for (const double g : {1e-6, 0.01, 0.18, 0.5, 0.9, 0.999999}) {
        const auto s = iris::rgb_to_sigmoid({g, g, g});
        for (int l = 360; l <= 830; l += 10) {
            EXPECT_NEAR(s(static_cast<double>(l)), g, 1e-6 * std::max(g, 1e-3)) << g;
            EXPECT_NEAR(s(static_cast<float>(l)), g, 1e-6) << g;
        }
    }
    // Next to the grey axis the table's greys are the same flat spectra, so there is no
    // jump onto the axis beyond the interpolation of c along z (c(z) is not linear).
    // Measured max |S − g| = 0.0023 (g = 0.13) over g = 0.001 … 0.999; tolerance 0.0035.
    for (int i = 1; i < 1000; ++i) {
        const double g = i / 1000.0;
        const auto s = iris::rgb_to_sigmoid({g, g, g * (1.0 - 1e-7)});
        for (int l = 360; l <= 830; l += 10) ASSERT_NEAR(s(static_cast<double>(l)), g, 0.0035) << g;
    }
}

TEST(RgbSigmoid, BadInputsAreClampedOrZeroed) {
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    const auto a = iris::rgb_to_sigmoid({nan, 0.5, 0.2}), b = iris::rgb_to_sigmoid({0.0, 0.5, 0.2});
    EXPECT_EQ(a.c0, b.c0);
    EXPECT_EQ(a.c1, b.c1);
    EXPECT_EQ(a.c2, b.c2);
    const auto c = iris::rgb_to_sigmoid({inf, -inf, 0.3}), d = iris::rgb_to_sigmoid({1.0, 0.0, 0.3});
    EXPECT_EQ(c.c2, d.c2);
    const auto all_nan = iris::rgb_to_sigmoid({nan, nan, nan});
    EXPECT_EQ(all_nan(550.0), 0.0);
    // x is clamped, so far outside the visible range the spectrum stays at its limit
    const auto red = iris::rgb_to_sigmoid({1, 0, 0});
    EXPECT_TRUE(std::isfinite(red(1e7f)));
    EXPECT_TRUE(std::isfinite(red(1e7)));
}

// Across the faces where two components are equal (r = g > b), the two slices that meet
// there hold the same fitted colours: the spectra on either side must agree. Measured
// difference ≤ 2.1e-8 (6000 colours on the three faces); tolerance 1e-6.
TEST(RgbSigmoid, NoSeamBetweenSlices) {
    for (const iris::rgb c : {iris::rgb{0.7, 0.7, 0.2}, iris::rgb{0.3, 0.05, 0.3}, iris::rgb{0.1, 0.93, 0.93}}) {
        const auto a = iris::rgb_to_sigmoid(c);
        const auto b = iris::rgb_to_sigmoid({c.r * (1 + 1e-12), c.g * (1 + 2e-12), c.b * (1 + 3e-12)});
        for (int l = 360; l <= 830; l += 5)
            EXPECT_NEAR(a(static_cast<double>(l)), b(static_cast<double>(l)), 1e-6) << c.r << " " << c.g << " " << c.b;
    }
}

/// Number of direction changes of S over 360–830 nm at 0.5 nm (steps below 1e-12 ignored).
int extrema(const iris::sigmoid_polynomial& s) {
    int changes = 0, dir = 0;
    double prev = s(360.0);
    for (int i = 1; i <= 940; ++i) {
        const double v = s(360.0 + 0.5 * i);
        const double d = v - prev;
        prev = v;
        if (std::abs(d) < 1e-12) continue;
        const int sgn = d > 0 ? 1 : -1;
        if (dir != 0 && sgn != dir) ++changes;
        dir = sgn;
    }
    return changes;
}

// σ is increasing and x(λ) is a quadratic, so S has at most one extremum: never the
// ripples of a higher-order basis. Checked on the grid, and on the colours that need the
// sharpest spectra (saturated, dark).
TEST(RgbSigmoid, AtMostOneExtremum) {
    auto grid = cube_grid(17);
    for (const iris::rgb c : {iris::rgb{1, 0, 0}, iris::rgb{0.02, 0.001, 0.0}, iris::rgb{0.0, 0.3, 0.01}})
        grid.push_back(c);
    for (const auto& c : grid) ASSERT_LE(extrema(iris::rgb_to_sigmoid(c)), 1) << c.r << " " << c.g << " " << c.b;
    // and the check can see one: a green (peak) and a magenta (dip) do have one
    EXPECT_EQ(extrema(iris::rgb_to_sigmoid({0.1, 0.8, 0.1})), 1);
    EXPECT_EQ(extrema(iris::rgb_to_sigmoid({0.8, 0.1, 0.8})), 1);
}

iris::rgb emitted_rgb(const iris::rgb_illuminant& e) {
    const iris::xyz x = iris::spectrum_to_xyz(e);
    return iris::xyz_to_linear_srgb(
        {x.x / iris::cie::y_integral, x.y / iris::cie::y_integral, x.z / iris::cie::y_integral});
}

// E = m·S(rgb/m)·D65/K reproduces rgb: its error is the reflectance round trip's at rgb/m
// (whose largest component is 1/2), scaled by m = 2·max. Measured ≤ 0.00097·m on these
// colours; tolerance 0.005·m, the reflectance test's bound.
TEST(RgbIlluminant, ReproducesTheColourTimesD65) {
    for (const iris::rgb c : {iris::rgb{1, 1, 1}, iris::rgb{5, 2, 0.5}, iris::rgb{0.1, 0.3, 3},
                              iris::rgb{0.9, 0.1, 0.1}, iris::rgb{0.02, 0.01, 0.04}, iris::rgb{40, 40, 1}}) {
        const auto e = iris::rgb_illuminant::from_linear_srgb(c);
        const double m = 2.0 * std::max({c.r, c.g, c.b});
        EXPECT_FLOAT_EQ(e.scale, static_cast<float>(m));
        EXPECT_LT(max_abs_diff(emitted_rgb(e), c), 0.005 * m) << c.r << " " << c.g << " " << c.b;
    }
}

TEST(RgbIlluminant, WhiteIsUnitLuminanceD65AndBlackIsZero) {
    const auto w = iris::rgb_illuminant::from_linear_srgb({1, 1, 1});
    EXPECT_NEAR(iris::luminance(w), 1.0, 1e-6);
    const double k = iris::luminance([](double l) {  // D65's own luminance, on the same 1 nm sums
        return iris::data::cie_d65::values[static_cast<std::size_t>(l - 300.0)];
    });
    for (int l = 360; l <= 830; l += 10)
        EXPECT_NEAR(w(static_cast<double>(l)), iris::data::cie_d65::values[static_cast<std::size_t>(l - 300)] / k,
                    1e-5);
    EXPECT_EQ(w(250.0), 0.0);  // D65's table starts at 300 nm
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const iris::rgb c : {iris::rgb{0, 0, 0}, iris::rgb{-1, -2, 0}, iris::rgb{nan, nan, nan}}) {
        const auto e = iris::rgb_illuminant::from_linear_srgb(c);
        for (int l = 360; l <= 830; l += 10) EXPECT_EQ(e(static_cast<float>(l)), 0.0f);
    }
}

TEST(RgbSigmoid, SampledEvaluationIsTheFloatForm) {
    const auto s = iris::rgb_to_sigmoid({0.6, 0.4, 0.3});
    const iris::sampled_wavelengths<4> wl({400.0f, 500.5f, 600.25f, 700.0f}, {1.0f, 1.0f, 1.0f, 1.0f});
    const auto v = iris::sample(s, wl);
    for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(v[i], s(wl[i]));
    const auto e = iris::rgb_illuminant::from_linear_srgb({2, 1, 0.5});
    const auto u = iris::sample(e, wl);
    for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(u[i], e(wl[i]));
}

}  // namespace
