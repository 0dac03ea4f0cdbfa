// ꟻLIP (iris/metrics/flip.hpp) against values of the reference implementation
// (NVlabs/flip v1.6, its C++ tool, built beside iris; docs/metrics.md) on the image pairs
// of flip_images.hpp, and its properties.
//
// The tool prints 6 decimals and computes in float; iris computes in double. Over these
// images the two agree to 1e-6 (measured), so each mean is checked to ±2e-6: a change of
// any constant of the method (q_c, p_c, p_t, q_f, the kernels' widths, the Hunt
// adjustment) moves the means by more than 1e-4 (scripts/mutate.py's flip mutations).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <iris/metrics/flip.hpp>
#include <iris/spectrum/color.hpp>

#include "flip_images.hpp"

namespace {

using iris::image;

/// The LDR pair as the reference tool reads it: 8-bit sRGB codes, decoded to linear.
image ldr(bool test) {
    image img(64, 48);
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            float c[3];
            for (int k = 0; k < 3; ++k)
                c[k] = static_cast<float>(iris::srgb_decode(iris::test::flip_ldr_code(x, y, k, test) / 255.0));
            img.pixels()[static_cast<std::size_t>(y * 64 + x)] = {c[0], c[1], c[2]};
        }
    return img;
}

constexpr double tolerance = 2e-6;

TEST(Flip, LdrMatchesTheReferenceImplementation) {
    const image ref = ldr(false), test = ldr(true);
    EXPECT_NEAR(iris::flip(test, ref), 0.223077, tolerance);        // flip -r ldr_ref.png -t ldr_test.png
    EXPECT_NEAR(iris::flip(test, ref, 30.0), 0.311950, tolerance);  // the same with -ppd 30
    const auto map = iris::flip_map(test, ref);
    EXPECT_NEAR(*std::min_element(map.begin(), map.end()), 0.019652, tolerance);
    EXPECT_NEAR(*std::max_element(map.begin(), map.end()), 0.963995, tolerance);
}

TEST(Flip, HdrMatchesTheReferenceImplementation) {
    const image ref = iris::test::flip_hdr_reference(96, 64);
    const auto e = iris::flip_exposure_range(ref);
    EXPECT_NEAR(e.start, -4.0947, 1e-4);  // the tool prints 4 decimals
    EXPECT_NEAR(e.stop, 3.1174, 1e-4);
    EXPECT_EQ(e.count, 8);
    EXPECT_NEAR(iris::flip_hdr(iris::test::flip_hdr_noisy(ref, 0.3f, 1), ref), 0.138975, tolerance);
    EXPECT_NEAR(iris::flip_hdr(iris::test::flip_hdr_noisy(ref, 0.05f, 2), ref), 0.076638, tolerance);
}

TEST(Flip, DefaultViewingConditionIsThePapers) {
    EXPECT_NEAR(iris::flip_default_ppd, 67.0206, 1e-4);  // 0.7 m from a 0.7 m wide monitor of 3840 pixels
}

TEST(Flip, IdenticalImagesHaveNoErrorAndErrorsLieInZeroOne) {
    const image ref = iris::test::flip_hdr_reference(40, 30);
    for (float v : iris::flip_hdr_map(ref, ref)) EXPECT_EQ(v, 0.0f);
    for (float v : iris::flip_map(ref, ref)) EXPECT_EQ(v, 0.0f);
    for (float v : iris::flip_hdr_map(iris::test::flip_hdr_noisy(ref, 1.0f, 5), ref)) {
        EXPECT_GE(v, 0.0f);
        EXPECT_LE(v, 1.0f);
    }
}

TEST(Flip, MoreNoiseIsAMoreVisibleError) {
    const image ref = iris::test::flip_hdr_reference(48, 32);
    double last = 0.0;
    for (float amount : {0.02f, 0.1f, 0.3f, 0.8f}) {
        const double f = iris::flip_hdr(iris::test::flip_hdr_noisy(ref, amount, 3), ref);
        EXPECT_GT(f, last) << "noise " << amount;
        last = f;
    }
}

TEST(Flip, LdrIsSymmetricAndClampsItsInput) {
    const image a = ldr(false), b = ldr(true);
    EXPECT_DOUBLE_EQ(iris::flip(a, b), iris::flip(b, a));
    image brighter = a;
    for (auto& p : brighter.pixels()) p.r = p.r > 0.5f ? p.r + 10.0f : p.r;  // beyond 1: clamped, no difference
    image clamped = brighter;
    for (auto& p : clamped.pixels()) p.r = std::min(p.r, 1.0f);
    EXPECT_DOUBLE_EQ(iris::flip(brighter, b), iris::flip(clamped, b));
}

TEST(Flip, BadInputIsRefused) {
    const image a(16, 16), b(16, 17);
    EXPECT_THROW(iris::flip(a, b), std::invalid_argument);
    EXPECT_THROW(iris::flip(a, a, 0.0), std::invalid_argument);
    EXPECT_THROW(iris::flip(a, a, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
    image nan = a;
    nan.pixels()[3].g = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(iris::flip(nan, a), std::invalid_argument);
    // HDR-FLIP's exposures end at the reference's median luminance: a mostly black one has none
    EXPECT_THROW(iris::flip_hdr(a, a), std::invalid_argument);
    EXPECT_THROW(iris::flip_exposure_range(a), std::invalid_argument);
}

}  // namespace
