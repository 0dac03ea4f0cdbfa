#include <gtest/gtest.h>

#include <limits>

#include <iris/spectrum/sampled.hpp>
#include <iris/spectrum/spectrum.hpp>
#include <iris/spectrum/tabulated.hpp>

namespace {

TEST(SampledSpectrum, ArithmeticIsElementWise) {
    const iris::sampled_spectrum<4> a({1, 2, 3, 4});
    const iris::sampled_spectrum<4> b({2, 2, 2, 2});
    EXPECT_EQ(a + b, iris::sampled_spectrum<4>({3, 4, 5, 6}));
    EXPECT_EQ(a - b, iris::sampled_spectrum<4>({-1, 0, 1, 2}));
    EXPECT_EQ(a * b, iris::sampled_spectrum<4>({2, 4, 6, 8}));
    EXPECT_EQ(a / b, iris::sampled_spectrum<4>({0.5f, 1, 1.5f, 2}));
    EXPECT_EQ(2.0f * a, a * 2.0f);
    EXPECT_EQ(-a, iris::sampled_spectrum<4>({-1, -2, -3, -4}));
    EXPECT_FLOAT_EQ(a.sum(), 10.0f);
    EXPECT_FLOAT_EQ(a.average(), 2.5f);
    EXPECT_FLOAT_EQ(a.max_value(), 4.0f);
    EXPECT_FLOAT_EQ(a.min_value(), 1.0f);
    EXPECT_TRUE(iris::sampled_spectrum<3>().is_zero());
}

TEST(SampledSpectrum, SafeDivAndFiniteness) {
    const iris::sampled_spectrum<3> a({1, 2, 3});
    const iris::sampled_spectrum<3> d({0, 2, 0});
    EXPECT_EQ(safe_div(a, d), iris::sampled_spectrum<3>({0, 1, 0}));
    EXPECT_TRUE(a.all_finite());
    auto bad = a;
    bad[1] = std::numeric_limits<float>::infinity();
    EXPECT_FALSE(bad.all_finite());
}

TEST(SampledWavelengths, SampleEvaluatesASpectrumAtEachWavelength) {
    const iris::tabulated_spectrum s({400.0, 700.0}, {0.0, 3.0});
    const iris::sampled_wavelengths<3> wl({400, 500, 700}, {1, 1, 1});
    EXPECT_EQ(iris::sample(s, wl), iris::sampled_spectrum<3>({0, 1, 3}));
}

TEST(SampledWavelengths, WideWidthsWork) {
    iris::sampled_spectrum<32> s(1.0f);
    EXPECT_FLOAT_EQ(s.sum(), 32.0f);
    const iris::sampled_wavelengths<32> wl;
    EXPECT_EQ(wl.pdf(31), 0.0f);
}

}  // namespace
