// sRGB → reflectance upsampling (include/iris/spectrum/rgb_upsampling.hpp): white is flat
// 1, greys are flat, every colour of the sRGB cube comes back through XYZ under D65.
#include <gtest/gtest.h>

#include <iris/spectrum/color.hpp>
#include <iris/spectrum/rgb_upsampling.hpp>

namespace {

// The round trip's only error is the ~1e-4 rescaling of the sRGB matrix to the tabulated
// D65 white (see the header), so 1e-3 per component is a stated, generous bound.
constexpr double round_trip_tolerance = 1e-3;

iris::rgb round_trip(const iris::rgb& c) {
    return iris::xyz_to_linear_srgb(iris::reflectance_xyz_d65(iris::reflectance_from_linear_srgb(c)));
}

TEST(RgbUpsampling, BasisIsAPartitionOfUnity) {
    using namespace iris::rgb_upsampling;
    for (double l = 360.0; l <= 830.0; l += 0.5) {
        EXPECT_GE(red_basis(l), 0.0);
        EXPECT_GE(green_basis(l), 0.0);
        EXPECT_GE(blue_basis(l), 0.0);
        EXPECT_NEAR(red_basis(l) + green_basis(l) + blue_basis(l), 1.0, 1e-12) << l;
    }
}

TEST(RgbUpsampling, EverySrgbColourMapsInsideTheUnitCube) {
    // all entries of A = M⁻¹T are ≥ 0 and rows sum to 1: [0,1]³ → [0,1]³, nothing is clipped
    const auto& a = iris::detail::rgb_upsampling_matrix();
    for (const auto& row : a) {
        for (double v : row) EXPECT_GE(v, 0.0);
        EXPECT_NEAR(row[0] + row[1] + row[2], 1.0, 1e-12);
    }
}

TEST(RgbUpsampling, WhiteIsFlatOneAndGreysAreFlat) {
    for (double g : {1.0, 0.5, 0.18, 0.0}) {
        const auto s = iris::reflectance_from_linear_srgb({g, g, g});
        for (double l = 360.0; l <= 830.0; l += 1.0) EXPECT_NEAR(s(l), g, 1e-12) << "grey " << g << " at " << l;
    }
}

TEST(RgbUpsampling, ColoursRoundTripThroughXyzUnderD65) {
    const iris::rgb colours[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1},
                                 {0.63, 0.065, 0.05}, {0.14, 0.45, 0.091}, {0.5, 0.5, 0.5}, {0.9, 0.6, 0.2}, {0.02, 0.03, 0.6}};
    for (const auto& c : colours) {
        const auto r = round_trip(c);
        EXPECT_NEAR(r.r, c.r, round_trip_tolerance) << c.r << " " << c.g << " " << c.b;
        EXPECT_NEAR(r.g, c.g, round_trip_tolerance) << c.r << " " << c.g << " " << c.b;
        EXPECT_NEAR(r.b, c.b, round_trip_tolerance) << c.r << " " << c.g << " " << c.b;
    }
}

TEST(RgbUpsampling, ReflectancesStayInTheUnitIntervalAndAreSmooth) {
    for (const iris::rgb c : {iris::rgb{1, 0, 0}, iris::rgb{0, 0, 1}, iris::rgb{0, 1, 0}, iris::rgb{2, -1, 0.5}}) {
        const auto s = iris::reflectance_from_linear_srgb(c);
        double prev = s(360.0);
        for (double l = 360.0; l <= 830.0; l += 1.0) {
            const double v = s(l);
            EXPECT_GE(v, 0.0);
            EXPECT_LE(v, 1.0);
            // the steepest logistic edge (scale 5 nm) rises by at most 1/20 per nm
            EXPECT_LE(std::fabs(v - prev), 0.051) << l;
            prev = v;
        }
    }
}

TEST(RgbUpsampling, EncodedSrgbIsDecodedFirst) {
    const auto a = iris::reflectance_from_srgb({0.5, 0.5, 0.5});
    EXPECT_NEAR(a(550.0), iris::srgb_decode(0.5), 1e-12);  // 0.214
}

}  // namespace
