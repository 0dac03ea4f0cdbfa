// The error-map colour ramp of iris-image (apps/iris-image/error_ramp.hpp) keeps its
// documented promises: lightness linear in the error, every colour inside sRGB.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "error_ramp.hpp"

namespace {

/// CIE L* of a linear sRGB colour (D65, Y_n = 1), computed the forward way (XYZ → L*),
/// independently of the ramp's Lab → RGB conversion.
double lightness(const iris::rgb& c) {
    const double y = iris::linear_srgb_to_xyz(c).y;
    constexpr double delta = 6.0 / 29.0;
    const double f = y > delta * delta * delta ? std::cbrt(y) : y / (3.0 * delta * delta) + 4.0 / 29.0;
    return 116.0 * f - 16.0;
}

TEST(ErrorRamp, LightnessIsLinearInTheError) {
    // 1e-4 in L*: the XYZ ↔ sRGB matrices are inverses to ~7 digits.
    double previous = -1.0;
    for (int i = 0; i <= 400; ++i) {
        const double t = i / 400.0;
        const double l = lightness(iris::app::lab_to_linear_srgb(iris::app::error_ramp_lab(t)));
        EXPECT_NEAR(l, 15.0 + 76.0 * t, 1e-4) << "t = " << t;
        EXPECT_GT(l, previous) << "t = " << t;
        previous = l;
    }
}

TEST(ErrorRamp, StaysInsideTheSrgbGamut) {
    for (int i = 0; i <= 400; ++i) {
        const double t = i / 400.0;
        const iris::rgb c = iris::app::lab_to_linear_srgb(iris::app::error_ramp_lab(t));
        for (double v : {c.r, c.g, c.b}) {
            EXPECT_GE(v, 0.0) << "t = " << t;
            EXPECT_LE(v, 1.0) << "t = " << t;
        }
    }
}

TEST(ErrorRamp, ClampsItsArgument) {
    EXPECT_EQ(iris::app::error_ramp(-3.0), iris::app::error_ramp(0.0));
    EXPECT_EQ(iris::app::error_ramp(std::numeric_limits<double>::quiet_NaN()), iris::app::error_ramp(0.0));
    EXPECT_EQ(iris::app::error_ramp(7.0), iris::app::error_ramp(1.0));
    // the ends are the first and last control points: dark violet, bright yellow
    const iris::rgb lo = iris::app::error_ramp(0.0), hi = iris::app::error_ramp(1.0);
    EXPECT_GT(lo.b, lo.g);
    EXPECT_GT(hi.r, hi.b);
    EXPECT_GT(hi.g, hi.b);
}

}  // namespace
