#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <iris/spectrum/blackbody.hpp>
#include <iris/spectrum/named.hpp>
#include <iris/spectrum/tabulated.hpp>

namespace {

TEST(Tabulated, InterpolatesLinearlyAtAnySpacing) {
    const iris::tabulated_spectrum s({400.0, 410.0, 450.0}, {1.0, 3.0, 7.0});
    EXPECT_DOUBLE_EQ(s(400.0), 1.0);
    EXPECT_DOUBLE_EQ(s(405.0), 2.0);
    EXPECT_DOUBLE_EQ(s(430.0), 5.0);
    EXPECT_DOUBLE_EQ(s(450.0), 7.0);
}

TEST(Tabulated, OutsideIsZeroOrClamped) {
    const iris::tabulated_spectrum zero({400.0, 500.0}, {2.0, 4.0});
    EXPECT_EQ(zero(399.0), 0.0);
    EXPECT_EQ(zero(501.0), 0.0);
    const iris::tabulated_spectrum clamp({400.0, 500.0}, {2.0, 4.0}, iris::outside::clamp);
    EXPECT_EQ(clamp(300.0), 2.0);
    EXPECT_EQ(clamp(900.0), 4.0);
    EXPECT_EQ(clamp(std::numeric_limits<double>::quiet_NaN()), 0.0);
}

TEST(Tabulated, UniformFastPathAgreesWithSearch) {
    const auto d65 = iris::find_illuminant("D65")->spectrum();
    const std::vector<double> l(d65.wavelengths().begin(), d65.wavelengths().end());
    std::vector<double> v(d65.values().begin(), d65.values().end());
    // perturb one wavelength so the table is no longer uniform: search path
    std::vector<double> l2 = l;
    l2[0] -= 0.5;
    const iris::tabulated_spectrum searched(l2, v);
    for (double x = 301.0; x < 830.0; x += 0.37) EXPECT_NEAR(d65(x), searched(x), 1e-9) << x;
}

// Found by fuzzing (fuzz_tabulated_spectrum): a step so small that its inverse overflows
// made the uniform path convert an infinite index (undefined behaviour, then values
// outside the table's range); points 1e308 apart made the searching path divide inf by
// inf. Both must interpolate like any table.
TEST(Tabulated, ExtremeSpacingsStayInsideTheTablesValues) {
    const iris::tabulated_spectrum tiny({0.0, 1e-310, 2e-310}, {1.0, 2.0, 3.0});
    EXPECT_NEAR(tiny(1.5e-310), 2.5, 1e-6);
    const iris::tabulated_spectrum wide({-1.7e308, 1.7e308}, {1.0, 3.0});
    EXPECT_DOUBLE_EQ(wide(0.0), 2.0);
    EXPECT_NEAR(wide(1e308), 1.0 + 2.0 * (2.7 / 3.4), 1e-12);
}

TEST(Tabulated, RejectsBadTables) {
    EXPECT_THROW(iris::tabulated_spectrum({400.0}, {1.0}), std::invalid_argument);
    EXPECT_THROW(iris::tabulated_spectrum({400.0, 500.0}, {1.0}), std::invalid_argument);
    EXPECT_THROW(iris::tabulated_spectrum({500.0, 400.0}, {1.0, 2.0}), std::invalid_argument);
    EXPECT_THROW(iris::tabulated_spectrum({400.0, 400.0}, {1.0, 2.0}), std::invalid_argument);
    EXPECT_THROW(iris::tabulated_spectrum({400.0, 500.0}, {1.0, std::nan("")}), std::invalid_argument);
    const std::vector<double> vals{1.0, 2.0};
    EXPECT_THROW(iris::tabulated_spectrum::uniform(400.0, 0.0, vals), std::invalid_argument);
}

TEST(Tabulated, IlluminantTablesAreWhereTheCieTabulatesThem) {
    for (const auto& ill : iris::illuminants) {
        const auto s = ill.spectrum();
        EXPECT_LE(s.min_wavelength(), 380.0) << ill.name;
        EXPECT_GE(s.max_wavelength(), 780.0) << ill.name;
        for (double v : s.values()) EXPECT_GE(v, 0.0) << ill.name;
    }
    EXPECT_FALSE(iris::find_illuminant("d65").has_value());
}

TEST(Blackbody, PeakIsOneAtWienWavelength) {
    for (double t : {1000.0, 2856.0, 6504.0, 10000.0}) {
        const iris::blackbody_spectrum b(t);
        const double peak = iris::blackbody_spectrum::peak_wavelength(t);
        EXPECT_NEAR(b(peak), 1.0, 1e-12) << t;
        for (double l = 100.0; l < 5000.0; l += 7.0) EXPECT_LE(b(l), 1.0 + 1e-12) << t << " K at " << l;
        // Planck ratios are preserved by the normalisation
        EXPECT_NEAR(b(500.0) / b(600.0), iris::planck(500.0, t) / iris::planck(600.0, t), 1e-12);
    }
    EXPECT_NEAR(iris::blackbody_spectrum::peak_wavelength(5778.0), 501.5, 0.1);  // the Sun
}

TEST(Blackbody, Planck2856KIsIlluminantAShape) {
    // Illuminant A is by definition Planckian at 2848 K with the old c2 (= 2856 K now).
    const auto a = iris::find_illuminant("A")->spectrum();
    const iris::blackbody_spectrum b(2856.0);
    for (double l = 400.0; l <= 700.0; l += 50.0)
        EXPECT_NEAR(a(l) / a(560.0), b(l) / b(560.0), 2e-3) << l;
}

TEST(Blackbody, DegenerateInputsGiveZero) {
    EXPECT_EQ(iris::planck(500.0, 0.0), 0.0);
    EXPECT_EQ(iris::planck(-1.0, 5000.0), 0.0);
}

}  // namespace
