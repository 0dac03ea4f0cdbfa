// Unit tests of the image metrics against hand-computed values and an independent
// brute-force SSIM. Exact comparisons (EXPECT_EQ) are used only where the arithmetic is
// exact by construction; the reason is stated next to each.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <iris/iris.hpp>
#include <iris/metrics/metrics.hpp>

namespace {

using iris::image;

/// Uniform float in [lo, hi) from mt19937's 32-bit output (the engine's sequence is fixed
/// by the standard, unlike std::uniform_real_distribution's).
float uniform(std::mt19937& rng, float lo, float hi) {
    return lo + (hi - lo) * static_cast<float>(rng() >> 8) * 0x1p-24f;
}

image random_image(int w, int h, std::uint32_t seed, float lo = 0.0f, float hi = 1.0f) {
    std::mt19937 rng(seed);
    image img(w, h);
    for (auto& p : img.pixels()) p = {uniform(rng, lo, hi), uniform(rng, lo, hi), uniform(rng, lo, hi)};
    return img;
}

image constant_image(int w, int h, iris::rgb_pixel v) {
    image img(w, h);
    std::fill(img.pixels().begin(), img.pixels().end(), v);
    return img;
}

/// `base` plus `scale` times a fixed pattern of uniform noise in [−1, 1).
image add_noise(const image& base, float scale, std::uint32_t seed) {
    std::mt19937 rng(seed);
    image out = base;
    for (auto& p : out.pixels()) {
        p.r += scale * uniform(rng, -1.0f, 1.0f);
        p.g += scale * uniform(rng, -1.0f, 1.0f);
        p.b += scale * uniform(rng, -1.0f, 1.0f);
    }
    return out;
}

std::string message_of(auto&& f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "(no std::invalid_argument thrown)";
}

// Centre weight of the 2-D window, computed here independently of iris::ssim_weights:
// g_5 = 1 / Σ_{k=−5..5} exp(−k² / (2 · 1.5²)), and the 2-D weight is g_5².
double centre_weight() {
    double s = 0.0;
    for (int k = -5; k <= 5; ++k) s += std::exp(-static_cast<double>(k * k) / 4.5);
    return 1.0 / (s * s);
}

// ---- MSE, relMSE, max_abs --------------------------------------------------------------

TEST(Mse, IdenticalImagesHaveZeroError) {
    const image a = random_image(32, 24, 1, -0.5f, 3.0f);
    EXPECT_EQ(iris::mse(a, a), 0.0);
    EXPECT_EQ(iris::relmse(a, a), 0.0);
    EXPECT_EQ(iris::max_abs(a, a), 0.0);
}

TEST(Mse, ConstantOffsetGivesOffsetSquaredExactly) {
    // Values on a 1/64 grid below 4 plus an offset of 1/8 are exact in float, so every
    // difference is exactly 0.125 and the mean of equal squares is exactly 0.125².
    image a(13, 7);
    int k = 0;
    for (auto& p : a.pixels()) {
        p = {static_cast<float>(k % 256) / 64.0f, static_cast<float>((k * 7) % 256) / 64.0f,
             static_cast<float>((k * 13) % 256) / 64.0f};
        ++k;
    }
    image b = a;
    for (auto& p : b.pixels()) p = {p.r + 0.125f, p.g + 0.125f, p.b + 0.125f};
    EXPECT_EQ(iris::mse(a, b), 0.125 * 0.125);
    EXPECT_EQ(iris::mse(b, a), 0.125 * 0.125);
    EXPECT_EQ(iris::max_abs(a, b), 0.125);
}

TEST(Mse, HandComputedTwoPixels) {
    image a(2, 1), b(2, 1);
    a(0, 0) = {1, 2, 3};
    b(1, 0) = {0.5f, 0, -0.5f};
    // (1 + 4 + 9 + 0.25 + 0 + 0.25) / 6
    EXPECT_DOUBLE_EQ(iris::mse(a, b), 14.5 / 6.0);
    EXPECT_EQ(iris::max_abs(a, b), 3.0);
}

TEST(Relmse, HandComputedTwoPixels) {
    image a(2, 1), ref(2, 1);
    a(0, 0) = {1, 0, 0};
    ref(0, 0) = {0, 0, 0};
    a(1, 0) = {0.5f, 0.5f, 0.5f};
    ref(1, 0) = {1, 1, 1};
    // (a − r)² / (r² + ε) per channel: 1 / (0 + ε), 0, 0 and three times 0.25 / (1 + ε).
    for (const double eps : {1e-2, 0.5}) {
        const double expected = (1.0 / eps + 3.0 * 0.25 / (1.0 + eps)) / 6.0;
        EXPECT_NEAR(iris::relmse(a, ref, eps), expected, 1e-15 * expected) << "eps " << eps;
    }
    EXPECT_EQ(iris::relmse_default_epsilon, 1e-2);
    EXPECT_DOUBLE_EQ(iris::relmse(a, ref), (100.0 + 0.75 / 1.01) / 6.0);
    // The second argument is the reference: swapped, the denominators are 1² + ε for the
    // first pixel's red channel and 0.5² + ε for the second pixel.
    EXPECT_DOUBLE_EQ(iris::relmse(ref, a), (1.0 / 1.01 + 3.0 * 0.25 / 0.26) / 6.0);
}

TEST(Relmse, RejectsNonPositiveEpsilon) {
    const image a = random_image(3, 3, 2);
    EXPECT_THROW((void)iris::relmse(a, a, 0.0), std::invalid_argument);
    EXPECT_THROW((void)iris::relmse(a, a, -1e-3), std::invalid_argument);
    EXPECT_THROW((void)iris::relmse(a, a, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
    EXPECT_THROW((void)iris::relmse(a, a, std::numeric_limits<double>::infinity()), std::invalid_argument);
}

TEST(Metrics, SizeMismatchNamesBothSizes) {
    const image a(4, 3), b(5, 3);
    const std::vector<std::string> messages = {
        message_of([&] { (void)iris::mse(a, b); }),     message_of([&] { (void)iris::relmse(a, b); }),
        message_of([&] { (void)iris::max_abs(a, b); }), message_of([&] { (void)iris::ssim(a, b); }),
        message_of([&] { (void)iris::compare(a, b); }),
    };
    for (const auto& m : messages) {
        EXPECT_NE(m.find("4x3"), std::string::npos) << m;
        EXPECT_NE(m.find("5x3"), std::string::npos) << m;
    }
}

TEST(Metrics, EmptyImagesAreAnError) {
    const image e;
    EXPECT_THROW((void)iris::mse(e, e), std::invalid_argument);
    EXPECT_THROW((void)iris::relmse(e, e), std::invalid_argument);
    EXPECT_THROW((void)iris::max_abs(e, e), std::invalid_argument);
    EXPECT_THROW((void)iris::ssim(e, e), std::invalid_argument);
    EXPECT_THROW((void)iris::compare(e, e), std::invalid_argument);
}

TEST(Metrics, NonFiniteValuesAreAnErrorNamingThePixel) {
    const image good = random_image(16, 12, 3);
    for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity()}) {
        image b = good;
        b(2, 1).g = bad;
        for (const auto& m : {message_of([&] { (void)iris::mse(good, b); }),
                              message_of([&] { (void)iris::relmse(b, good); }),
                              message_of([&] { (void)iris::max_abs(good, b); }),
                              message_of([&] { (void)iris::ssim(b, good); }),
                              message_of([&] { (void)iris::compare(good, b); })})
            EXPECT_NE(m.find("(2, 1)"), std::string::npos) << m;
    }
}

// ---- SSIM --------------------------------------------------------------------------------

TEST(Ssim, WindowIsTheNormalisedTruncatedGaussian) {
    const auto g = iris::ssim_weights();
    static_assert(iris::ssim_window == 11);
    double sum = 0.0;
    for (double v : g) sum += v;
    EXPECT_NEAR(sum, 1.0, 1e-15);
    for (int k = 0; k < 11; ++k) {
        EXPECT_EQ(g[static_cast<std::size_t>(k)], g[static_cast<std::size_t>(10 - k)]);
        // ratio to the centre is exp(−d² / (2σ²)) with σ = 1.5
        const double d = k - 5;
        EXPECT_NEAR(g[static_cast<std::size_t>(k)] / g[5], std::exp(-d * d / 4.5), 1e-15);
    }
    EXPECT_NEAR(g[5] * g[5], centre_weight(), 1e-16);
    EXPECT_EQ(iris::ssim_c1, 1e-4);
    EXPECT_DOUBLE_EQ(iris::ssim_c2, 9e-4);
}

TEST(Ssim, IdenticalImagesScoreExactlyOne) {
    // Exact: for a == b numerator and denominator are the same floating-point expression
    // (see ssim_from_moments), so each window is 1.0 and so is every mean of ones.
    const image a = random_image(40, 31, 4, -0.3f, 1.6f);
    EXPECT_EQ(iris::ssim(a, a), 1.0);
    for (double c : iris::ssim_channels(a, a)) EXPECT_EQ(c, 1.0);
    const image b = a;
    EXPECT_EQ(iris::ssim(a, b), 1.0);
}

TEST(Ssim, NeedsOneWholeWindow) {
    const image small_w = random_image(10, 11, 5), small_h = random_image(11, 10, 5);
    EXPECT_NE(message_of([&] { (void)iris::ssim(small_w, small_w); }).find("at least 11x11"), std::string::npos);
    EXPECT_NE(message_of([&] { (void)iris::ssim(small_h, small_h); }).find("11x10"), std::string::npos);
    const image ok = random_image(11, 11, 5);
    EXPECT_EQ(iris::ssim(ok, ok), 1.0);
    // compare() keeps the pixel-wise metrics of small images and reports SSIM as NaN.
    const auto m = iris::compare(small_w, add_noise(small_w, 0.1f, 6));
    EXPECT_TRUE(std::isnan(m.ssim));
    EXPECT_GT(m.mse, 0.0);
    EXPECT_EQ(m.pixels, 110u);
}

TEST(Ssim, ClosedFormOnOneWindowAgainstConstantImages) {
    // 11 × 11 images have exactly one window, the whole image. Let a be 0 except the centre
    // pixel, which is 1 (linear 1 encodes to 1), and let b be constant β (encoded). With the
    // centre weight w = g_5² the weighted moments are
    //   μa = w,  E[a²] = w (a² = a)  ⇒  σa² = w − w² = w(1 − w),
    //   μb = β,  σb² = 0,  σab = E[a]β − μaβ = 0,
    // so SSIM = (2wβ + C1) · C2 / ((w² + β² + C1) · (w(1 − w) + C2)).
    // Channels: R against β = 0, G against β = 1, B against β = encode(0.2).
    image a(11, 11);
    a(5, 5) = {1, 1, 1};
    const image b = constant_image(11, 11, {0.0f, 1.0f, 0.2f});
    const double w = centre_weight();
    const double c1 = 1e-4, c2 = 9e-4;
    auto closed = [&](double beta) {
        return (2 * w * beta + c1) * c2 / ((w * w + beta * beta + c1) * (w * (1 - w) + c2));
    };
    const std::array<double, 3> expected = {closed(0.0), closed(1.0), closed(iris::srgb_encode(0.2f))};
    const auto got = iris::ssim_channels(a, b);
    for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-12) << "channel " << c;
    EXPECT_NEAR(iris::ssim(a, b), (expected[0] + expected[1] + expected[2]) / 3.0, 1e-12);
    // Sanity of the closed form itself, by hand: g_5 ≈ 1 / 3.76, w ≈ 0.0707, so R is
    // C1·C2 / ((w² + C1)(w(1−w) + C2)) ≈ 9e-8 / (0.00510 · 0.0666) ≈ 2.6e-4.
    EXPECT_GT(expected[0], 2.5e-4);
    EXPECT_LT(expected[0], 2.8e-4);
}

TEST(Ssim, ConstantImagesScoreTheLuminanceTerm) {
    // Two constant images: every window has σ = 0, so SSIM = (2αβ + C1) / (α² + β² + C1)
    // in encoded values, for every window of a 20 × 15 image.
    const image a = constant_image(20, 15, {0.3f, 0.3f, 0.3f});
    const image b = constant_image(20, 15, {0.6f, 0.6f, 0.6f});
    const double al = iris::srgb_encode(0.3f), be = iris::srgb_encode(0.6f);
    EXPECT_NEAR(iris::ssim(a, b), (2 * al * be + 1e-4) / (al * al + be * be + 1e-4), 1e-12);
    // MSE of a constant offset d is d² (d is the float difference; 0.3 and 0.6 are not
    // exact in float). Relative 1e-13: the mean of 900 equal terms rounds ≤ 900 ulp.
    const double d = static_cast<double>(0.6f) - static_cast<double>(0.3f);
    EXPECT_NEAR(iris::mse(a, b), d * d, 1e-13 * d * d);
}

TEST(Ssim, IsSymmetric) {
    // Exact: every expression in the SSIM formula is commutative in a and b.
    const image a = random_image(33, 17, 7);
    const image b = add_noise(a, 0.2f, 8);
    EXPECT_EQ(iris::ssim(a, b), iris::ssim(b, a));
    EXPECT_LT(iris::ssim(a, b), 1.0);
}

TEST(Ssim, DecreasesWithMoreNoise) {
    // One fixed noise pattern at growing amplitude: the structure term falls with every step.
    const image a = random_image(48, 40, 9, 0.05f, 0.95f);
    double previous = iris::ssim(a, a);
    for (const float s : {0.005f, 0.02f, 0.05f, 0.1f, 0.3f}) {
        const double v = iris::ssim(a, add_noise(a, s, 10));
        EXPECT_LT(v, previous) << "noise " << s;
        EXPECT_GT(v, -1.0);
        previous = v;
    }
    EXPECT_LT(previous, 0.9);
}

TEST(Ssim, ClampsToTheDisplayRangeBeforeEncoding) {
    // Values above 1 and below 0 are clamped, so an image equals its clamped copy under SSIM
    // (exactly, by the identical-input argument) while MSE still sees the difference.
    const image a = random_image(16, 16, 11, -1.0f, 2.0f);
    image clamped = a;
    for (auto& p : clamped.pixels())
        p = {std::clamp(p.r, 0.0f, 1.0f), std::clamp(p.g, 0.0f, 1.0f), std::clamp(p.b, 0.0f, 1.0f)};
    EXPECT_EQ(iris::ssim(a, clamped), 1.0);
    EXPECT_GT(iris::mse(a, clamped), 0.1);
    EXPECT_EQ(iris::ssim(constant_image(12, 12, {5, -2, 1}), constant_image(12, 12, {1, 0, 70})), 1.0);
}

/// Brute-force SSIM of one channel: for every window position a direct 11 × 11 weighted
/// sum with two-pass (centred) moments — no separability, no E[x²] − μ² shortcut.
double brute_force_ssim(const image& a, const image& b, float iris::rgb_pixel::*c) {
    std::array<double, 11> e{};
    double s = 0.0;
    for (int k = 0; k < 11; ++k) s += e[static_cast<std::size_t>(k)] = std::exp(-(k - 5.0) * (k - 5.0) / 4.5);
    auto enc = [&](const image& img, int x, int y) {
        return iris::srgb_encode(std::clamp(static_cast<double>(img(x, y).*c), 0.0, 1.0));
    };
    const double c1 = 1e-4, c2 = 9e-4;
    double total = 0.0;
    int windows = 0;
    for (int y0 = 0; y0 + 11 <= a.height(); ++y0)
        for (int x0 = 0; x0 + 11 <= a.width(); ++x0) {
            double ma = 0, mb = 0;
            for (int j = 0; j < 11; ++j)
                for (int i = 0; i < 11; ++i) {
                    const double w = e[static_cast<std::size_t>(i)] * e[static_cast<std::size_t>(j)] / (s * s);
                    ma += w * enc(a, x0 + i, y0 + j);
                    mb += w * enc(b, x0 + i, y0 + j);
                }
            double va = 0, vb = 0, cab = 0;
            for (int j = 0; j < 11; ++j)
                for (int i = 0; i < 11; ++i) {
                    const double w = e[static_cast<std::size_t>(i)] * e[static_cast<std::size_t>(j)] / (s * s);
                    const double da = enc(a, x0 + i, y0 + j) - ma, db = enc(b, x0 + i, y0 + j) - mb;
                    va += w * da * da;
                    vb += w * db * db;
                    cab += w * da * db;
                }
            total += (2 * ma * mb + c1) * (2 * cab + c2) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
            ++windows;
        }
    return total / windows;
}

TEST(Ssim, MatchesBruteForceOnRandomImages) {
    // Values partly outside [0, 1] exercise the clamp; the noise makes all terms non-trivial.
    // 1e-12: both sides are double sums of ~10³ terms of size ≤ 1 (rounding ~1e-14).
    const image a = random_image(32, 24, 12, -0.1f, 1.1f);
    const image b = add_noise(a, 0.15f, 13);
    const auto got = iris::ssim_channels(a, b);
    double mean = 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
        const double expected = brute_force_ssim(a, b, iris::detail::rgb_channels[c]);
        EXPECT_NEAR(got[c], expected, 1e-12) << "channel " << c;
        mean += expected / 3.0;
    }
    EXPECT_NEAR(iris::ssim(a, b), mean, 1e-12);
    // Unrelated images: SSIM near 0, still matching.
    const image u = random_image(32, 24, 14);
    EXPECT_NEAR(iris::ssim_channels(a, u)[1], brute_force_ssim(a, u, &iris::rgb_pixel::g), 1e-12);
}

// ---- compare ---------------------------------------------------------------------------

TEST(Compare, BundlesTheIndividualMetrics) {
    const image ref = random_image(20, 14, 15);
    const image img = add_noise(ref, 0.05f, 16);
    const iris::image_metrics m = iris::compare(img, ref);
    EXPECT_EQ(m.mse, iris::mse(img, ref));
    EXPECT_EQ(m.relmse, iris::relmse(img, ref));
    EXPECT_EQ(m.ssim, iris::ssim(img, ref));
    EXPECT_EQ(m.max_abs, iris::max_abs(img, ref));
    EXPECT_EQ(m.pixels, 280u);
    EXPECT_GT(m.mse, 0.0);
    EXPECT_LE(m.max_abs, 0.05 + 1e-7);  // noise amplitude (plus float rounding)
}

}  // namespace

// ---- bias_variance ----------------------------------------------------------------------

namespace {

// Exact by construction (every value a multiple of 2^-3): two runs at ±0.25 around the
// reference have no bias and variance 2 · 0.25² = 0.125, so bias_sq = 0 − 0.125 / 2; two
// equal runs 0.25 off have no variance and bias_sq = mse = 0.0625.
TEST(BiasVariance, HandComputedRuns) {
    const image ref = constant_image(16, 12, {0.5f, 0.5f, 0.5f});
    const std::vector<image> spread{constant_image(16, 12, {0.75f, 0.75f, 0.75f}), constant_image(16, 12, {0.25f, 0.25f, 0.25f})};
    const auto a = iris::bias_variance(spread, ref);
    EXPECT_EQ(a.runs, 2u);
    EXPECT_EQ(a.mse, 0.0625);
    EXPECT_EQ(a.variance, 0.125);
    EXPECT_EQ(a.bias_sq, -0.0625);
    EXPECT_EQ(a.bias_sq_se, 0.0);
    const std::vector<image> offset{constant_image(16, 12, {0.75f, 0.75f, 0.75f}), constant_image(16, 12, {0.75f, 0.75f, 0.75f})};
    const auto b = iris::bias_variance(offset, ref);
    EXPECT_EQ(b.variance, 0.0);
    EXPECT_EQ(b.bias_sq, 0.0625);
    EXPECT_EQ(b.mse, 0.0625);
}

// Statistical, fixed seeds: 4 runs = reference + β + uniform noise of half-width 0.3
// (variance 0.03) on 120 × 100 pixels. bias_sq must be within 4 of its own standard errors
// of β² (two-sided, 99.994 % under normality; 3·12000 values) for β = 0 and β = 0.05, and
// variance within 2 % of 0.03 (its standard error here is ~0.4 %). Would catch the
// variance divided by k instead of k − 1 (bias_sq off by 0.03 / 16 ≈ 0.0019, ~30 standard
// errors) or the s²/k correction left out (off by 0.0075).
TEST(BiasVariance, RecoversAKnownBiasFromNoisyRuns) {
    const image ref = random_image(120, 100, 11, 0.5f, 1.5f);
    for (float beta : {0.0f, 0.05f}) {
        SCOPED_TRACE(beta);
        std::vector<image> runs;
        for (std::uint32_t s = 0; s < 4; ++s) {
            image r = add_noise(ref, 0.3f, 100 + s);
            for (auto& p : r.pixels()) p = {p.r + beta, p.g + beta, p.b + beta};
            runs.push_back(std::move(r));
        }
        const auto bv = iris::bias_variance(runs, ref);
        EXPECT_NEAR(bv.bias_sq, double(beta) * beta, 4 * bv.bias_sq_se) << "se " << bv.bias_sq_se;
        EXPECT_LT(bv.bias_sq_se, 2e-4);
        EXPECT_NEAR(bv.variance, 0.03, 0.02 * 0.03);
        EXPECT_NEAR(bv.mse, bv.variance + bv.bias_sq, 1e-12);
    }
}

TEST(BiasVariance, NeedsTwoRunsOfTheReferencesSize) {
    const image ref = constant_image(8, 8, {0.5f, 0.5f, 0.5f});
    const std::vector<image> one{ref}, mixed{ref, constant_image(8, 9, {0.5f, 0.5f, 0.5f})};
    EXPECT_NE(message_of([&] { (void)iris::bias_variance(one, ref); }).find("at least 2 runs"), std::string::npos);
    EXPECT_NE(message_of([&] { (void)iris::bias_variance(mixed, ref); }).find("8x9"), std::string::npos);
}

}  // namespace
