// Automatic window placement (iris/sampling/placement.hpp): the windows it chooses for every
// built-in illuminant, blackbodies and 100 random tabulated spectra (fixed seed) obey the
// laws of docs/method.md §1 and the placement's own constraints; narrow emission lines end up inside
// windows; the hand placement never scores better on a built-in illuminant; the result is a
// local optimum of J; degenerate spectra (no signal, one channel dark) are handled.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <iris/sampling/placement.hpp>
#include <iris/sampling/restricted_distribution.hpp>
#include <iris/sampling/restriction.hpp>
#include <iris/sampling/spectral_pdf.hpp>
#include <iris/spectrum/blackbody.hpp>
#include <iris/spectrum/named.hpp>

namespace {

using namespace iris;
using placed = placement::placed_windows<3>;

const restriction::multi_box<3> hand{};

placed place(const std::function<double(double)>& e, const spectral_domain& d = {}) {
    const auto s = placement::channel_signals(e, d);
    return placement::place_windows<3>(s, d, hand.centres_nm, hand.widths_nm);
}

/// \brief A narrow emission line: a Gaussian of σ nm at c nm.
double line(double l, double c, double sigma) { return std::exp(-0.5 * (l - c) * (l - c) / (sigma * sigma)); }

/// \brief The placement's constraints and the laws of docs/method.md §1 for the multi_box it gives.
void check_windows(const placed& w, const spectral_domain& d, const std::string& what) {
    SCOPED_TRACE(what);
    const double cell = (static_cast<double>(d.max_nm) - d.min_nm) / placement::cells;
    double total = 0.0, last_hi = d.min_nm - 1.0;
    for (std::size_t k = 0; k < 3; ++k) {
        const double lo = w.centres_nm[k] - 0.5 * w.widths_nm[k], hi = w.centres_nm[k] + 0.5 * w.widths_nm[k];
        EXPECT_GE(lo, d.min_nm - 1e-3);
        EXPECT_LE(hi, d.max_nm + 1e-3);
        EXPECT_GE(lo, last_hi - 1e-3) << "windows overlap or are out of order";
        last_hi = hi;
        const double cells = w.widths_nm[k] / cell;
        EXPECT_NEAR(cells, std::round(cells / 5) * 5, 1e-3) << "width not a multiple of 5 cells";
        EXPECT_GE(cells, placement::min_width_cells - 1e-3);
        EXPECT_LE(cells, placement::max_width_cells + 1e-3);
        total += cells;
    }
    EXPECT_NEAR(total, 60.0, 1e-3);
    for (double c : w.captured)
        if (!std::isnan(c)) {
            EXPECT_GE(c, -1e-12);
            EXPECT_LE(c, 1.0 + 1e-12);
        }
    // docs/method.md §1: r_1 ≡ 1 on Λ, r_α non-decreasing in α, ∫ p r_α > 0 (a distribution that
    // puts its mass inside the windows at α = 0)
    restriction::multi_box<3> k;
    k.centres_nm = w.centres_nm;
    k.widths_nm = w.widths_nm;
    std::vector<float> previous(801, 0.0f);
    for (float a : {0.0f, 0.01f, 0.1f, 0.5f, 0.99f, 1.0f}) {
        const auto b = k.bind(a, d);
        for (int i = 0; i <= 800; ++i) {
            const float l = d.min_nm + (d.max_nm - d.min_nm) * static_cast<float>(i) / 800.0f;
            const float r = b(l);
            ASSERT_TRUE(r >= 0.0f && r <= 1.0f);
            if (a == 1.0f) {
                ASSERT_EQ(r, 1.0f) << "law 1 at " << l;
            }
            ASSERT_GE(r, previous[static_cast<std::size_t>(i)]) << "law 2 at " << l << ", α = " << a;
            previous[static_cast<std::size_t>(i)] = r;
        }
    }
    const restricted_distribution dist(spectral_pdf::uniform{}, k, 0.0f, d);
    for (std::size_t j = 0; j < 3; ++j) EXPECT_GT(dist.pdf(w.centres_nm[j]), 0.0f) << "law 3: no mass in window " << j;
    EXPECT_EQ(dist.pdf(d.min_nm + 0.37f * (d.max_nm - d.min_nm)) > 0.0f,
              k.bind(0.0f, d)(d.min_nm + 0.37f * (d.max_nm - d.min_nm)) > 0.0f);
}

/// \brief No single move — a window's start by ±1…5 cells, or 5 cells of width handed from
/// one window to another — raises J: the placement is a local optimum of the lattice it
/// was refined on.
void check_local_optimum(const std::function<double(double)>& e, const placed& w) {
    const spectral_domain d{};
    const auto s = placement::channel_signals(e, d);
    const auto score = [&](std::array<float, 3> c, std::array<float, 3> wd) -> double {
        for (std::size_t k = 0; k < 3; ++k) {
            const double lo = c[k] - 0.5 * wd[k], hi = c[k] + 0.5 * wd[k];
            if (lo < d.min_nm - 1e-3 || hi > d.max_nm + 1e-3 || wd[k] < 10 - 1e-3 || wd[k] > 40 + 1e-3) return -std::numeric_limits<double>::infinity();
            if (k > 0 && lo < c[k - 1] + 0.5 * wd[k - 1] - 1e-3) return -std::numeric_limits<double>::infinity();
        }
        return placement::evaluate_windows<3>(s, d, c, wd).score;
    };
    const double j = score(w.centres_nm, w.widths_nm);
    EXPECT_NEAR(j, w.score, 1e-9) << "evaluate_windows and place_windows disagree on J";
    for (std::size_t k = 0; k < 3; ++k)
        for (int dl = -5; dl <= 5; ++dl) {
            if (dl == 0) continue;
            auto c = w.centres_nm;
            c[k] += static_cast<float>(dl);
            EXPECT_LE(score(c, w.widths_nm), j + 1e-9) << "moving window " << k << " by " << dl << " nm is better";
        }
    for (std::size_t from = 0; from < 3; ++from)
        for (std::size_t to = 0; to < 3; ++to) {
            if (from == to) continue;
            for (float lo_shift : {0.0f, 5.0f}) {  // the shrunk window keeps its start or its end
                auto c = w.centres_nm;
                auto wd = w.widths_nm;
                wd[from] -= 5.0f;
                c[from] += lo_shift == 0.0f ? -2.5f : 2.5f;
                wd[to] += 5.0f;
                for (float grow : {-2.5f, 2.5f}) {
                    auto c2 = c;
                    c2[to] += grow;
                    EXPECT_LE(score(c2, wd), j + 1e-9) << "5 nm from window " << from << " to " << to << " is better";
                }
            }
        }
}

/// \brief J of the best placement on the 5-cell lattice, by brute force written here
/// independently of the library's search: the placement found (the lattice's best, then
/// refined) must score at least this.
double lattice_optimum(const std::function<double(double)>& e) {
    const spectral_domain d{};
    const auto s = placement::channel_signals(e, d);
    std::array<double, 3> total{};
    for (const auto& c : s)
        for (std::size_t k = 0; k < 3; ++k) total[k] += c[k];
    const double biggest = std::max({total[0], total[1], total[2]});
    std::vector<std::array<double, 3>> prefix(s.size() + 1);
    for (std::size_t i = 0; i < s.size(); ++i)
        for (std::size_t k = 0; k < 3; ++k)
            prefix[i + 1][k] = prefix[i][k] + (total[k] > 1e-9 * biggest ? s[i][k] / total[k] : 0.0);
    const auto share = [&](int lo, int w, std::size_t k) { return prefix[std::size_t(lo + w)][k] - prefix[std::size_t(lo)][k]; };
    double best = -std::numeric_limits<double>::infinity();
    for (int w0 = 10; w0 <= 40; w0 += 5)
        for (int w1 = 10; w1 <= 40; w1 += 5) {
            const int w2 = 60 - w0 - w1;
            if (w2 < 10 || w2 > 40) continue;
            for (int a = 0; a + 60 <= 400; a += 5)
                for (int b = a + w0; b + w1 + w2 <= 400; b += 5)
                    for (int c = b + w1; c + w2 <= 400; c += 5) {
                        double j = 0.0;
                        for (std::size_t k = 0; k < 3; ++k)
                            if (total[k] > 1e-9 * biggest) j += std::log(share(a, w0, k) + share(b, w1, k) + share(c, w2, k));
                        best = std::max(best, j);
                    }
        }
    return best;
}

TEST(Placement, EveryBuiltInIlluminantAndBlackbody) {
    for (const auto& ill : illuminants) {
        const auto spd = ill.spectrum();
        const auto e = [&](double l) { return spd(l); };
        const auto w = place(e);
        const std::string name(ill.name);
        ASSERT_TRUE(w.placed) << name;
        check_windows(w, {}, name);
        check_local_optimum(e, w);
        // the hand placement is inside the search space up to the 1-nm lattice, so it must
        // not beat the automatic one
        const auto s = placement::channel_signals(e, spectral_domain{});
        const auto by_hand = placement::evaluate_windows<3>(s, {}, hand.centres_nm, hand.widths_nm);
        EXPECT_GE(w.score, by_hand.score - 1e-9) << name << ": the hand-placed windows score higher";
        for (double c : w.captured) EXPECT_FALSE(std::isnan(c)) << name << ": a channel without signal";
        if (name == "D65" || name == "A" || name == "LED-B1" || name == "LED-RGB1") {  // (each brute force takes ~0.1 s)
            EXPECT_GE(w.score, lattice_optimum(e) - 1e-9) << name << ": a better placement on the 5-cell lattice exists";
        }
    }
    for (double kelvin : {1000.0, 2700.0, 6500.0, 20000.0}) {
        const blackbody_spectrum b(kelvin);
        const auto e = [&](double l) { return b(l); };
        const auto w = place(e);
        check_windows(w, {}, "blackbody " + std::to_string(kelvin));
        check_local_optimum(e, w);
    }
}

TEST(Placement, NarrowLinesFallInsideWindows) {
    // an RGB laser projector: 447, 520, 638 nm; the hand windows (454–474, 539–559,
    // 601–621) miss all three
    const auto laser = [](double l) { return line(l, 447, 1.5) + line(l, 520, 1.5) + line(l, 638, 1.5); };
    const auto w = place(laser);
    check_windows(w, {}, "laser");
    for (double peak : {447.0, 520.0, 638.0}) {
        bool inside = false;
        for (std::size_t k = 0; k < 3; ++k)
            inside |= std::abs(peak - w.centres_nm[k]) + 3.0 <= 0.5 * w.widths_nm[k];  // ±2σ inside
        EXPECT_TRUE(inside) << "the line at " << peak << " nm is outside every window";
    }
    for (double c : w.captured) EXPECT_GT(c, 0.9);
    // CIE LED-RGB1: its three peaks (found here, not assumed) are inside windows
    const auto rgb = find_illuminant("LED-RGB1")->spectrum();
    const auto wr = place([&](double l) { return rgb(l); });
    std::vector<double> peaks;
    for (double l = 381; l < 779; l += 1)
        if (rgb(l) > rgb(l - 1) && rgb(l) >= rgb(l + 1) && rgb(l) > 0.3 * rgb(l)) {
            double local_max = 0;
            for (double m = l - 30; m <= l + 30; m += 1) local_max = std::max(local_max, rgb(m));
            if (rgb(l) == local_max) peaks.push_back(l);
        }
    ASSERT_EQ(peaks.size(), 3u) << "LED-RGB1 should have three peaks";
    for (double peak : peaks) {
        bool inside = false;
        for (std::size_t k = 0; k < 3; ++k) inside |= std::abs(peak - wr.centres_nm[k]) <= 0.5 * wr.widths_nm[k];
        EXPECT_TRUE(inside) << "LED-RGB1's peak at " << peak << " nm is outside every window";
    }
}

TEST(Placement, RandomTabulatedSpectra) {
    std::mt19937_64 rng(20261204);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int trial = 0; trial < 100; ++trial) {
        // 1–6 bumps of random width (0.5–80 nm) and height on a random floor (0 for half)
        std::vector<std::array<double, 3>> bumps(1 + static_cast<std::size_t>(u(rng) * 6));
        for (auto& b : bumps) b = {360 + 440 * u(rng), 0.5 + 80 * u(rng) * u(rng), u(rng)};
        const double floor = trial % 2 ? 0.0 : 0.05 * u(rng);
        std::vector<double> lambda, value;
        for (double l = 360; l <= 830; l += 0.5) {
            double v = floor;
            for (const auto& b : bumps) v += b[2] * line(l, b[0], b[1]);
            lambda.push_back(l);
            value.push_back(v);
        }
        const tabulated_spectrum t(lambda, value);
        const auto e = [&](double l) { return t(l); };
        const auto w = place(e);
        if (!w.placed) continue;  // all bumps outside Λ: tested below
        check_windows(w, {}, "random spectrum " + std::to_string(trial));
        if (trial % 10 == 0) check_local_optimum(e, w);
        if (trial % 10 == 0) {  // deterministic
            const auto again = place(e);
            EXPECT_EQ(again.centres_nm, w.centres_nm);
            EXPECT_EQ(again.widths_nm, w.widths_nm);
        }
    }
}

TEST(Placement, DegenerateSpectra) {
    // nothing emitted in Λ: the kernel's windows, `placed` false
    const auto none = place([](double) { return 0.0; });
    EXPECT_FALSE(none.placed);
    EXPECT_EQ(none.centres_nm, hand.centres_nm);
    EXPECT_EQ(none.widths_nm, hand.widths_nm);
    const auto outside = place([](double l) { return l > 800 ? 1.0 : 0.0; });
    EXPECT_FALSE(outside.placed);
    // NaN and negative values count as nothing
    const auto nan = place([](double l) { return l < 500 ? std::numeric_limits<double>::quiet_NaN() : -1.0; });
    EXPECT_FALSE(nan.placed);
    // one line at 700 nm: z̄ receives nothing (it is not a channel of J), a window holds the line
    const auto red = place([](double l) { return line(l, 700, 2); });
    ASSERT_TRUE(red.placed);
    EXPECT_TRUE(std::isnan(red.captured[2]));
    check_windows(red, {}, "a line at 700 nm");
    bool inside = false;
    for (std::size_t k = 0; k < 3; ++k) inside |= std::abs(700.0 - red.centres_nm[k]) <= 0.5 * red.widths_nm[k];
    EXPECT_TRUE(inside);
    // other domains: 400–700 nm, and a narrow 500–560 nm one (the windows' 15 % of Λ)
    for (const spectral_domain d : {spectral_domain{400.0f, 700.0f}, spectral_domain{500.0f, 560.0f}}) {
        const auto d65 = find_illuminant("D65")->spectrum();
        const auto w = place([&](double l) { return d65(l); }, d);
        ASSERT_TRUE(w.placed);
        check_windows(w, d, "D65 on " + std::to_string(d.min_nm) + "-" + std::to_string(d.max_nm));
    }
}

}  // namespace
