// The bias fade (iris/render/fade.hpp, the film's fade layer): exact second moments, the
// MSE-optimal weight, and on synthetic films whose truth is known — early samples biased
// and quiet, late ones unbiased and noisy — that the blend beats both the running mean and
// the unbiased mean, reduces to the running mean without bias, and converges (consistency).
// Synthetic pixels are i.i.d. N(μ + δ, σ_b²) before the split and N(μ, σ_u²) after, in X,
// Y and Z alike; fixed seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

#include <iris/render/fade.hpp>
#include <iris/render/film.hpp>

namespace {

using iris::fade::exact_uint;

// The fixed-point square is the correctly rounded v² scaled by 2^48 and truncated: the
// compiler's own double → unsigned __int128 conversion is the oracle, over 2^-30 … 2^39.
TEST(Fade, FixedPointSquaresAreExact) {
    EXPECT_EQ(iris::fade::to_fixed_square(1.0), exact_uint{1} << 48);
    EXPECT_EQ(iris::fade::to_fixed_square(-3.0), exact_uint{9} << 48);
    EXPECT_EQ(iris::fade::to_fixed_square(0.0), exact_uint{0});
    std::mt19937_64 gen(3);
    std::uniform_real_distribution<double> exponent(-30.0, 38.99), unit(0.5, 1.0);
    for (int k = 0; k < 100'000; ++k) {
        const double v = unit(gen) * std::exp2(exponent(gen)) * (k % 2 ? -1 : 1);
        ASSERT_EQ(iris::fade::to_fixed_square(v), static_cast<exact_uint>(v * v * 0x1p48)) << v;
    }
}

// The 192-bit sum carries: two squares of 2^127 make 2^128 (high part 1), and adding the
// same squares in two orders gives the same sum.
TEST(Fade, SquareSumsCarryAndDoNotDependOnOrder) {
    iris::fade::square_sum s;
    s.add(exact_uint{1} << 127);
    s.add(exact_uint{1} << 127);
    EXPECT_EQ(s.low, exact_uint{0});
    EXPECT_EQ(s.high, 1u);
    EXPECT_EQ(s.value(), 0x1p80);  // 2^128 · 2^-48
    std::vector<exact_uint> v;
    std::mt19937_64 gen(5);
    for (int k = 0; k < 1000; ++k) v.push_back(iris::fade::to_fixed_square(static_cast<double>(gen() >> 26)));
    iris::fade::square_sum forward, backward;
    for (auto x : v) forward.add(x);
    for (auto it = v.rbegin(); it != v.rend(); ++it) backward.add(*it);
    EXPECT_EQ(forward, backward);
    EXPECT_GT(forward.high, 0u);  // the test exercised the carry
}

// w* = V_u / (β² + V_b + V_u) with the expectations plugged in: n_b / (n_b + n_u) for equal
// per-sample variances and no bias (the running mean); smaller with a bias; 0 with no late
// noise; the running mean's weight for a neighbourhood without noise or bias.
TEST(Fade, WeightIsTheMseOptimumOfItsInputs) {
    const auto sums = [](double nb, double nu, double sigma2, double bias2) {
        iris::fade::weight_sums s;
        s.var_late = sigma2 / nu;
        s.var_both = sigma2 / nb + sigma2 / nu;
        s.diff_sq = bias2 + s.var_both;
        return s;
    };
    EXPECT_NEAR(iris::fade::weight(sums(16, 48, 1.0, 0.0), -1), 16.0 / 64.0, 1e-12);
    EXPECT_NEAR(iris::fade::weight(sums(512, 512, 2.0, 0.0), -1), 0.5, 1e-12);
    const double w = iris::fade::weight(sums(16, 48, 1.0, 0.1), -1);
    EXPECT_NEAR(w, (1.0 / 48) / (0.1 + 1.0 / 16 + 1.0 / 48), 1e-12);
    // the minimum of MSE(w) = w²(β² + V_b) + (1 − w)² V_u
    const auto mse = [](double x) { return x * x * (0.1 + 1.0 / 16) + (1 - x) * (1 - x) / 48; };
    EXPECT_LT(mse(w), mse(w + 1e-3));
    EXPECT_LT(mse(w), mse(w - 1e-3));
    EXPECT_EQ(iris::fade::weight(iris::fade::weight_sums{}, 0.25), 0.25);
    // the denominator is never below the noise: a difference smaller than V_b + V_u
    iris::fade::weight_sums quiet{1.0, 2.0, 0.5};
    EXPECT_EQ(iris::fade::weight(quiet, -1), 0.5);
}

/// \brief A synthetic fading film: W × H pixels, n_b early samples N(μ + δ, σ_b²) and n_u
/// late ones N(μ, σ_u²) per pixel and channel; `order` 1 adds them pixel by pixel with the
/// late samples first (exact sums make it the same film).
iris::film synthetic(int w, int h, int nb, int nu, double mu, double delta, double sb, double su, std::uint64_t seed,
                     int order = 0) {
    iris::film f(w, h);
    f.enable_fade(static_cast<std::uint32_t>(nb));
    std::mt19937_64 gen(seed);
    std::normal_distribution<double> unit;
    const auto n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    // the values depend on (pixel, sample) only: drawn in one order, added in another
    std::vector<std::vector<iris::xyz>> v(n, std::vector<iris::xyz>(static_cast<std::size_t>(nb + nu)));
    for (int s = 0; s < nb + nu; ++s)
        for (std::size_t i = 0; i < n; ++i) {
            const double m = s < nb ? mu + delta : mu, sd = s < nb ? sb : su;
            v[i][static_cast<std::size_t>(s)] = {m + sd * unit(gen), m + sd * unit(gen), m + sd * unit(gen)};
        }
    for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < nb + nu; ++k) {
            const int s = order == 1 ? nb + nu - 1 - k : k;
            f.add(i, v[i][static_cast<std::size_t>(s)], static_cast<std::uint64_t>(s));
        }
    return f;
}

/// \brief Squared errors of X against μ, per pixel: of the fade, the running mean and the
/// late samples' mean.
struct errors {
    std::vector<double> fade, running, late;
};
errors errors_of(const iris::film& f, double mu) {
    errors e;
    const auto blend = f.faded();
    for (std::size_t i = 0; i < blend.size(); ++i) {
        const auto sides = f.fade_sides(i);
        e.fade.push_back((blend[i].x - mu) * (blend[i].x - mu));
        e.running.push_back((f.mean(i).x - mu) * (f.mean(i).x - mu));
        e.late.push_back((sides[0].second.mean - mu) * (sides[0].second.mean - mu));
    }
    return e;
}

/// \brief Mean of a − b over the pixels and its standard error from the means of 8 × 8
/// blocks (the fade's weights are shared over 5 × 5 neighbourhoods, so single pixels are
/// not independent; blocks nearly are).
std::pair<double, double> block_mean_se(const std::vector<double>& a, const std::vector<double>& b, int w, int h) {
    std::vector<double> blocks;
    for (int by = 0; by + 8 <= h; by += 8)
        for (int bx = 0; bx + 8 <= w; bx += 8) {
            double s = 0;
            for (int y = by; y < by + 8; ++y)
                for (int x = bx; x < bx + 8; ++x) {
                    const auto i = static_cast<std::size_t>(y * w + x);
                    s += a[i] - b[i];
                }
            blocks.push_back(s / 64);
        }
    double m = 0, m2 = 0;
    for (double v : blocks) m += v, m2 += v * v;
    const double n = static_cast<double>(blocks.size());
    m /= n;
    return {m, std::sqrt((m2 / n - m * m) / (n - 1))};
}

// Early samples biased (δ = 0.05) and quiet (σ_b = 0.1), late ones unbiased and noisy
// (σ_u = 0.5), 16 + 48 samples: the optimum weight is 0.625 (MSE 1.95·10^-3, against the
// running mean's 3.13·10^-3 at w = 0.25 and the late mean's 5.21·10^-3). The fade's MSE must be below both
// in a one-sided test at α = 0.001 each (z = 3.09; Bonferroni over the two: family 0.002),
// on 64 × 64 pixels (64 blocks).
TEST(Fade, BlendBeatsTheRunningMeanAndTheUnbiasedMeanUnderBias) {
    const int w = 64, h = 64;
    const auto e = errors_of(synthetic(w, h, 16, 48, 1.0, 0.05, 0.1, 0.5, 11), 1.0);
    for (const auto* other : {&e.running, &e.late}) {
        const auto [d, se] = block_mean_se(*other, e.fade, w, h);
        EXPECT_GT(d / se, 3.09) << (other == &e.running ? "running mean" : "late mean") << ": MSE gain " << d << " ± " << se;
    }
}

// No bias, one variance (σ = 0.3), 16 + 48 samples: the running mean is optimal (w = 1/4)
// and the fade must come close. With the weight estimated from 75 squared differences its
// expected excess is about 0.5 % (w ≈ 0.22 instead of 0.25); the bound 5 % is a property
// bound (a swapped weight, w = V_b / (…) ≈ 0.75, costs +130 %), checked against the
// running mean's own MSE on the same pixels.
TEST(Fade, WithoutBiasTheBlendIsTheRunningMean) {
    const int w = 64, h = 64;
    const auto e = errors_of(synthetic(w, h, 16, 48, 1.0, 0.0, 0.3, 0.3, 13), 1.0);
    double fade = 0, running = 0;
    for (std::size_t i = 0; i < e.fade.size(); ++i) fade += e.fade[i], running += e.running[i];
    const auto n = static_cast<double>(e.fade.size());
    EXPECT_LT(fade, 1.05 * running) << "fade MSE " << fade / n << ", running mean " << running / n;
}

// Consistency: 8 biased samples (δ = 0.5) then 8000 unbiased ones (σ_u = 0.2), 32 × 32
// pixels. The running mean keeps a bias of 8·δ/8008 = 5.0·10^-4, about 7 standard errors
// of the pixels' average (the power control: it must be detected, |z| > 3.29); the fade's
// weight is ~ V_u / δ² ≈ 2·10^-5, so its average error must be within 3.29 standard errors
// of 0 (two-sided, α = 0.001).
TEST(Fade, TheBlendConvergesToTheUnbiasedValue) {
    const int w = 32, h = 32;
    const double mu = 2.0;
    const auto f = synthetic(w, h, 8, 8000, mu, 0.5, 0.05, 0.2, 17);
    const auto blend = f.faded();
    const auto mean_se = [&](auto value) {
        double m = 0, m2 = 0;
        for (std::size_t i = 0; i < blend.size(); ++i) {
            const double v = value(i) - mu;
            m += v, m2 += v * v;
        }
        const double n = static_cast<double>(blend.size());
        m /= n;
        return std::pair{m, std::sqrt((m2 / n - m * m) / (n - 1))};
    };
    const auto [bias_fade, se_fade] = mean_se([&](std::size_t i) { return blend[i].y; });
    const auto [bias_running, se_running] = mean_se([&](std::size_t i) { return f.mean(i).y; });
    EXPECT_GT(std::fabs(bias_running) / se_running, 3.29) << "the running mean's bias " << bias_running << " ± " << se_running;
    EXPECT_LT(std::fabs(bias_fade) / se_fade, 3.29) << "the fade's bias " << bias_fade << " ± " << se_fade;
}

// Before the split (no late samples) and with a single late sample the image is the
// running mean, bit for bit: the fade starts from exactly what `paper` shows.
TEST(Fade, BeforeTwoLateSamplesTheImageIsTheRunningMean) {
    for (int nu : {0, 1}) {
        const auto f = synthetic(9, 7, 16, nu, 1.0, 0.3, 0.2, 0.4, 19);
        for (std::size_t i = 0; i < 63; ++i) EXPECT_EQ(f.faded()[i].x, f.mean(i).x);
        const auto a = f.to_image();
        EXPECT_EQ(a.pixels()[5].r, static_cast<float>(iris::xyz_to_linear_srgb(f.mean(5)).r));
    }
}

// Exactness: the same samples added in another order, or split over two films and merged,
// give the same faded image, bit for bit; a fading and a plain film do not merge.
TEST(Fade, TheImageDependsOnWhichSamplesNotTheirOrder) {
    const auto a = synthetic(16, 12, 8, 24, 1.0, 0.2, 0.1, 0.3, 23, 0);
    const auto b = synthetic(16, 12, 8, 24, 1.0, 0.2, 0.1, 0.3, 23, 1);
    const auto fa = a.faded(), fb = b.faded();
    for (std::size_t i = 0; i < fa.size(); ++i) ASSERT_EQ(fa[i].x, fb[i].x) << i;
    // split: samples 0..19 in one film, 20..31 in another
    iris::film first(1, 1), second(1, 1);
    first.enable_fade(8);
    second.enable_fade(8);
    std::mt19937_64 gen(29);
    std::normal_distribution<double> unit;
    iris::film whole(1, 1);
    whole.enable_fade(8);
    for (int s = 0; s < 32; ++s) {
        const iris::xyz v{1 + unit(gen), 1 + unit(gen), 1 + unit(gen)};
        whole.add(0, v, static_cast<std::uint64_t>(s));
        (s < 20 ? first : second).add(0, v, static_cast<std::uint64_t>(s));
    }
    first.merge(second);
    EXPECT_EQ(first.faded()[0].x, whole.faded()[0].x);
    EXPECT_EQ(first.fade_sides(0)[1].first.var_mean, whole.fade_sides(0)[1].first.var_mean);
    EXPECT_THROW(first.merge(iris::film(1, 1)), std::invalid_argument);
    iris::film other(1, 1);
    other.enable_fade(9);
    EXPECT_THROW(first.merge(other), std::invalid_argument);
    EXPECT_THROW(whole.enable_fade(4), std::logic_error);  // it has samples
}

// A NaN or out-of-range sample is dropped and counted; it enters neither side's sums or
// squares (a dropped late sample is a zero, as in the mean): the image stays finite.
TEST(Fade, NonFiniteSamplesStayOut) {
    iris::film f(1, 1);
    f.enable_fade(2);
    const double nan = std::nan("");
    const iris::xyz values[] = {{1, 1, 1}, {2, 2, 2}, {nan, 1, 1}, {3, 3, 3}, {1e300, 0, 0}, {4, 4, 4}};
    for (std::uint64_t s = 0; s < 6; ++s) f.add(0, values[s], s);
    EXPECT_EQ(f.dropped(), 2u);
    const auto sides = f.fade_sides(0);
    EXPECT_EQ(sides[0].second.n, 4);
    EXPECT_DOUBLE_EQ(sides[0].second.mean, (0 + 3 + 0 + 4) / 4.0);
    EXPECT_TRUE(std::isfinite(f.faded()[0].x));
    EXPECT_TRUE(std::isfinite(f.to_image().pixels()[0].r));
}

}  // namespace
