// Colorimetry against published figures: the CIE's own tristimulus values and
// chromaticities (CIE 015:2018), to the tolerances the issue states.
#include <gtest/gtest.h>

#include <iris/spectrum/blackbody.hpp>
#include <iris/spectrum/color.hpp>
#include <iris/spectrum/named.hpp>

namespace {

iris::xyz white_of(std::string_view name) {
    const auto ill = iris::find_illuminant(name);
    EXPECT_TRUE(ill.has_value()) << name;
    return iris::normalise_y(iris::spectrum_to_xyz(ill->spectrum()));
}

TEST(Color, YBarIntegral) {
    EXPECT_NEAR(iris::cie::y_integral, 106.857, 1e-3);
    static_assert(iris::cie::y_integral > 106.8 && iris::cie::y_integral < 106.9);
}

TEST(Color, CmfInterpolationHitsTableAndVanishesOutside) {
    EXPECT_DOUBLE_EQ(iris::cie::y_bar(555.0), 1.0);
    EXPECT_EQ(iris::cie::y_bar(359.9), 0.0);
    EXPECT_EQ(iris::cie::y_bar(830.1), 0.0);
    EXPECT_EQ(iris::cie::x_bar(std::numeric_limits<double>::quiet_NaN()), 0.0);
    const double mid = iris::cie::y_bar(555.5);
    EXPECT_NEAR(mid, 0.5 * (iris::cie::y_bar(555.0) + iris::cie::y_bar(556.0)), 1e-12);
}

TEST(Color, D65TristimulusIsTheCieWhite) {
    const iris::xyz c = white_of("D65");
    EXPECT_NEAR(c.x, 0.95047, 2e-4);
    EXPECT_DOUBLE_EQ(c.y, 1.0);
    EXPECT_NEAR(c.z, 1.08883, 2e-4);
}

TEST(Color, D65IsWhiteInLinearSrgb) {
    const iris::rgb c = iris::xyz_to_linear_srgb(white_of("D65"));
    EXPECT_NEAR(c.r, 1.0, 1e-3);
    EXPECT_NEAR(c.g, 1.0, 1e-3);
    EXPECT_NEAR(c.b, 1.0, 1e-3);
}

TEST(Color, IlluminantAChromaticity) {
    const auto xy = iris::chromaticity(white_of("A"));
    EXPECT_NEAR(xy.x, 0.44757, 1e-5);
    EXPECT_NEAR(xy.y, 0.40744, 1e-5);
}

struct led_case {
    const char* name;
    double x, y;  // CIE 015:2018, Table 10.4
};

class LedChromaticity : public ::testing::TestWithParam<led_case> {};

TEST_P(LedChromaticity, MatchesCie015) {
    const auto& p = GetParam();
    const auto xy = iris::chromaticity(white_of(p.name));
    EXPECT_NEAR(xy.x, p.x, 1e-4) << p.name;
    EXPECT_NEAR(xy.y, p.y, 1e-4) << p.name;
}

INSTANTIATE_TEST_SUITE_P(Cie015, LedChromaticity,
                         ::testing::Values(led_case{"LED-B1", 0.4560, 0.4078}, led_case{"LED-B2", 0.4357, 0.4012},
                                           led_case{"LED-B3", 0.3756, 0.3723}, led_case{"LED-B4", 0.3422, 0.3502},
                                           led_case{"LED-B5", 0.3118, 0.3236}, led_case{"LED-BH1", 0.4474, 0.4066},
                                           led_case{"LED-RGB1", 0.4557, 0.4211}, led_case{"LED-V1", 0.4548, 0.4044},
                                           led_case{"LED-V2", 0.3781, 0.3775}),
                         [](const auto& param_info) {
                             std::string n = param_info.param.name;
                             std::erase(n, '-');
                             return n;
                         });

TEST(Color, SrgbMatrixPairIsInverse) {
    const iris::rgb in{0.2, 0.5, 0.9};
    const iris::rgb out = iris::xyz_to_linear_srgb(iris::linear_srgb_to_xyz(in));
    EXPECT_NEAR(out.r, in.r, 1e-6);
    EXPECT_NEAR(out.g, in.g, 1e-6);
    EXPECT_NEAR(out.b, in.b, 1e-6);
}

TEST(Color, SrgbTransferFunction) {
    EXPECT_EQ(iris::srgb_encode(0.0), 0.0);
    EXPECT_EQ(iris::srgb_encode(1.0), 1.0);
    EXPECT_EQ(iris::srgb_encode(-1.0), 0.0);
    EXPECT_EQ(iris::srgb_encode(std::numeric_limits<double>::quiet_NaN()), 0.0);
    EXPECT_NEAR(iris::srgb_encode(0.18), 0.46135612950044164, 1e-12);  // middle grey
    for (double v = 0.0; v <= 1.0; v += 0.01) EXPECT_NEAR(iris::srgb_decode(iris::srgb_encode(v)), v, 1e-12);
    // continuous at the linear/power switch
    EXPECT_NEAR(iris::srgb_encode(0.0031308), 12.92 * 0.0031308, 1e-6);
}

TEST(Color, WhiteNormalisationMapsLuminanceToOne) {
    const auto a = iris::find_illuminant("A")->spectrum();
    const double k = iris::white_normalisation(a);
    EXPECT_GT(k, 0.0);
    EXPECT_NEAR(iris::luminance(a.scaled(k)), 1.0, 1e-12);
    EXPECT_DOUBLE_EQ(iris::luminance(iris::constant_spectrum{1.0}), 1.0);
    EXPECT_EQ(iris::white_normalisation(iris::constant_spectrum{0.0}), 0.0);
}

TEST(Color, SampledToXyzOfFlatSpectrumIsUnbiased) {
    // A flat unit spectrum sampled uniformly on the CMF range: the estimator's mean over a
    // stratified sweep of λ equals the flat spectrum's XYZ / ∫ȳ, i.e. Y = 1.
    constexpr int n = 47000;
    double y = 0.0;
    const float pdf = 1.0f / 470.0f;
    for (int i = 0; i < n; ++i) {
        const float l = 360.0f + 470.0f * (static_cast<float>(i) + 0.5f) / static_cast<float>(n);
        y += iris::sampled_to_xyz(iris::sampled_spectrum<1>(1.0f), iris::sampled_wavelengths<1>({l}, {pdf})).y;
    }
    EXPECT_NEAR(y / n, 1.0, 1e-4);
}

}  // namespace
