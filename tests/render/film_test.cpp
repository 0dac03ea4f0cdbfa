// The film's exact accumulation (iris/render/film.hpp): sums that do not depend on the
// order of the samples, the resolution and range it states, and out-of-range samples dropped
// and counted like NaNs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include <iris/render/film.hpp>

namespace {

// 10 000 samples over 24 orders of magnitude (fireflies among tiny values), added in
// order, reversed and shuffled: the sums are bit-identical, and so are the means. The
// control: a double running sum of the same values in the same three orders differs, so
// this test would fail for the film before exact accumulation.
TEST(Film, SumsDoNotDependOnTheOrderOfTheSamples) {
    std::mt19937_64 gen(7);
    std::uniform_real_distribution<double> exponent(-12.0, 11.0), unit(0.0, 1.0);
    std::vector<iris::xyz> v(10'000);
    for (auto& s : v)
        s = {unit(gen) * std::pow(10.0, exponent(gen)), unit(gen) * std::pow(10.0, exponent(gen)), unit(gen)};
    auto orders = std::vector<std::vector<iris::xyz>>{v, v, v};
    std::reverse(orders[1].begin(), orders[1].end());
    std::shuffle(orders[2].begin(), orders[2].end(), gen);
    std::vector<iris::exact_xyz> sums;
    std::vector<double> means, naive;
    for (const auto& o : orders) {
        iris::film f(1, 1);
        double d = 0;
        for (const auto& s : o) f.add(0, s), d += s.x;
        sums.push_back(f.sum(0));
        means.push_back(f.mean(0).x);
        naive.push_back(d);
    }
    EXPECT_EQ(sums[0], sums[1]);
    EXPECT_EQ(sums[0], sums[2]);
    EXPECT_EQ(means[0], means[1]);
    EXPECT_EQ(means[0], means[2]);
    EXPECT_TRUE(naive[0] != naive[1] || naive[0] != naive[2]) << "the control: a double sum depends on the order";
}

// Resolution: a sample loses less than 2^-56 (rounded toward zero); the mean of one sample
// is the sample to 2^-56 absolute. Range: |v| < 2^39 is summed, 2^39 and beyond (or NaN) is
// dropped, counted and still counts as a sample; 2^32 − 1 samples of the largest value
// cannot overflow (checked by summing its fixed-point value that often in 128 bits).
TEST(Film, ResolutionAndRangeAreTheStatedOnes) {
    iris::film f(4, 1);
    const double tiny = 3.0 * 0x1p-58;  // below the resolution: 3/4 of a unit, rounds to 0
    f.add(0, {1.0 / 3.0, 7.77e-5, tiny});
    EXPECT_NEAR(f.mean(0).x, 1.0 / 3.0, 0x1p-56);
    EXPECT_NEAR(f.mean(0).y, 7.77e-5, 0x1p-56);
    EXPECT_EQ(f.mean(0).z, 0.0);
    const double largest = std::nextafter(iris::film::max_sample, 0.0);
    f.add(1, {largest, -largest, 1.0});
    EXPECT_EQ(f.mean(1).x, largest);
    EXPECT_EQ(f.mean(1).y, -largest);
    EXPECT_EQ(f.dropped(), 0u);
    f.add(2, {iris::film::max_sample, 1.0, 1.0});
    f.add(2, {1.0, 1.0, std::numeric_limits<double>::quiet_NaN()});
    f.add(2, {2.0, 2.0, 2.0});
    EXPECT_EQ(f.dropped(), 2u);
    EXPECT_EQ(f.samples(2), 3u);
    EXPECT_EQ(f.mean(2).x, 2.0 / 3.0) << "dropped samples count as samples and add nothing";
    // no overflow at the limits: (2^32 − 1) · fixed(largest) < 2^127
    const iris::exact_int one = iris::film::to_fixed(largest);
    const iris::exact_int max = ((iris::exact_int{1} << 126) - 1) * 2 + 1;  // 2^127 − 1
    EXPECT_LT(one, max / 0xffffffffu);
}

// The fast fixed-point conversion is the plain one (a library call) for values of every
// magnitude and sign in range, and for the boundary cases.
TEST(Film, ToFixedIsTheTruncatedConversion) {
    std::mt19937_64 gen(11);
    std::uniform_real_distribution<double> exponent(-60.0, 39.0), unit(-1.0, 1.0);
    auto plain = [](double v) { return static_cast<iris::exact_int>(v * 0x1p56); };
    for (int i = 0; i < 200'000; ++i) {
        const double v = unit(gen) * std::exp2(exponent(gen));
        ASSERT_TRUE(iris::film::to_fixed(v) == plain(v)) << v;
    }
    for (double v : {0.0, -0.0, 0x1p-56, -0x1p-56, 0x1p-57, 1.0, -1.0, 0x1p40 - 1, std::nextafter(0x1p39, 0.0),
                     -std::nextafter(0x1p39, 0.0), 0x1p-16 + 0x1p-56})
        EXPECT_TRUE(iris::film::to_fixed(v) == plain(v)) << v;
}

}  // namespace

// merge: two films that took disjoint halves of the samples sum to the film that took them
// all, in the same bits (what the ranks of an MPI render and a resumed render rely on). A
// merge that dropped the counts, the dropped counts or a sum would differ in one part.
TEST(Film, MergingTwoFilmsIsTakingBothFilmsSamples) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    iris::film all(3, 2), first(3, 2), second(3, 2);
    for (int k = 0; k < 400; ++k)
        for (std::size_t i = 0; i < 6; ++i) {
            const iris::xyz v = k % 97 == 5 ? iris::xyz{std::nan(""), 0, 0} : iris::xyz{u(rng), u(rng) * 1e-9, u(rng) * 1e6};
            all.add(i, v);
            (k % 3 == 0 ? first : second).add(i, v);
        }
    first.merge(second);
    for (std::size_t i = 0; i < 6; ++i) {
        EXPECT_EQ(first.sum(i), all.sum(i));
        EXPECT_EQ(first.samples(i), all.samples(i));
    }
    EXPECT_EQ(first.dropped(), all.dropped());
    EXPECT_GT(all.dropped(), 0u);
    EXPECT_THROW(first.merge(iris::film(2, 3)), std::invalid_argument);
}

// from_parts rebuilds the same film from its parts, and refuses parts of the wrong length
// or a pixel with more dropped samples than samples (a corrupt checkpoint's film)
TEST(Film, FromPartsRebuildsTheFilmAndChecksItsParts) {
    iris::film f(2, 2);
    for (std::size_t i = 0; i < 4; ++i) f.add(i, {0.25 * static_cast<double>(i), 1.0, -2.0});
    f.add(3, {std::nan(""), 0, 0});
    const auto copy = [](auto s) { return std::vector(s.begin(), s.end()); };
    const iris::film g = iris::film::from_parts(2, 2, copy(f.sums()), copy(f.counts()), copy(f.dropped_counts()));
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(g.sum(i), f.sum(i));
        EXPECT_EQ(g.samples(i), f.samples(i));
    }
    EXPECT_EQ(g.dropped(), 1u);
    EXPECT_THROW((void)iris::film::from_parts(2, 3, copy(f.sums()), copy(f.counts()), copy(f.dropped_counts())),
                 std::invalid_argument);
    EXPECT_THROW((void)iris::film::from_parts(2, 2, copy(f.sums()), copy(f.counts()), {5, 0, 0, 0}), std::invalid_argument);
}

namespace {
/// \brief `count` splats over a w × h film: values over 18 orders of magnitude, some pixels
/// taking many, some none.
std::vector<iris::splat> random_splats(std::size_t count, std::uint32_t pixels, std::uint64_t seed) {
    std::mt19937_64 gen(seed);
    std::uniform_real_distribution<double> exponent(-9.0, 9.0), unit(-1.0, 1.0);
    std::uniform_int_distribution<std::uint32_t> pixel(0, pixels / 2);  // the upper half of the film takes none
    std::vector<iris::splat> out(count);
    for (auto& s : out)
        s = {pixel(gen), {unit(gen) * std::pow(10.0, exponent(gen)), unit(gen), unit(gen) * 1e-3}};
    return out;
}
}  // namespace

// A pass of splats is one sample per pixel, the exact sum of its splats: the same film
// whether the splats come in one list or split over "threads" and shuffled, equal to a film
// that took each pixel's total with add(); pixels no splat reached take a 0 sample.
TEST(Film, APassOfSplatsIsOneSamplePerPixelWhateverTheListsAndOrder) {
    const std::uint32_t w = 6, h = 4, n = w * h;
    const auto all = random_splats(500, n, 3);
    std::mt19937_64 gen(5);
    auto shuffled = all;
    std::shuffle(shuffled.begin(), shuffled.end(), gen);
    std::vector<std::vector<iris::splat>> lists(3);
    for (std::size_t k = 0; k < shuffled.size(); ++k) lists[k % 3].push_back(shuffled[k]);
    lists.emplace_back();  // a thread that splatted nothing

    iris::film one(w, h), split(w, h), chunked(w, h);
    for (std::uint64_t pass = 0; pass < 2; ++pass) {
        one.add_pass(std::vector<std::vector<iris::splat>>{all}, pass);
        split.add_pass(lists, pass);
        // in pieces, as the splatting loops hand over full lists while they render
        chunked.begin_pass();
        for (std::size_t k = 0; k < shuffled.size(); k += 37)
            chunked.add_splats(std::vector<iris::splat>(shuffled.begin() + static_cast<std::ptrdiff_t>(k),
                                                        shuffled.begin() + static_cast<std::ptrdiff_t>(std::min(k + 37, shuffled.size()))));
        chunked.end_pass(pass);
    }
    // the reference: each pixel's exact total, summed in fixed point as add_pass must
    std::vector<iris::exact_xyz> totals(n);
    for (const auto& s : all) {
        totals[s.pixel].x += iris::film::to_fixed(s.value.x);
        totals[s.pixel].y += iris::film::to_fixed(s.value.y);
        totals[s.pixel].z += iris::film::to_fixed(s.value.z);
    }
    for (std::size_t i = 0; i < n; ++i) {
        EXPECT_EQ(one.sum(i), split.sum(i));
        EXPECT_EQ(one.sum(i), chunked.sum(i));
        EXPECT_EQ(chunked.samples(i), 2u);
        const iris::exact_xyz twice{2 * totals[i].x, 2 * totals[i].y, 2 * totals[i].z};
        EXPECT_EQ(one.sum(i), twice) << i;
        EXPECT_EQ(one.samples(i), 2u);
    }
    EXPECT_EQ(one.sum(n - 1), iris::exact_xyz{});  // no splat: a 0 sample, counted
    EXPECT_EQ(one.samples(n - 1), 2u);
    EXPECT_EQ(one.dropped(), 0u);
    // the control: a double running sum of the same splats in the two orders differs
    double a = 0, b = 0;
    for (const auto& s : all) a += s.value.x;
    for (const auto& s : shuffled) b += s.value.x;
    EXPECT_NE(a, b) << "the values no longer test the order";
}

// A non-finite or out-of-range splat drops its pixel's pass sample (0, counted once however
// many bad splats it took) and no other pixel's; a pass total out of range is dropped too.
TEST(Film, ABadSplatDropsItsPixelsPassSampleOnly) {
    iris::film f(3, 1);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<std::vector<iris::splat>> pass{{{0, {1.0, 2.0, 3.0}}, {0, {nan, 0, 0}}, {0, {0, iris::film::max_sample, 0}}},
                                                     {{1, {0.5, 0.5, 0.5}}, {2, {0.75 * iris::film::max_sample, 0, 0}}},
                                                     {{2, {0.75 * iris::film::max_sample, 0, 0}}}};
    f.add_pass(pass, 0);
    EXPECT_EQ(f.samples(0), 1u);
    EXPECT_EQ(f.sum(0), iris::exact_xyz{});
    EXPECT_EQ(f.mean(1).x, 0.5);
    EXPECT_EQ(f.samples(2), 1u);
    EXPECT_EQ(f.sum(2), iris::exact_xyz{});  // 1.5 · max_sample in total
    EXPECT_EQ(f.dropped(), 2u);
    EXPECT_EQ(f.dropped_counts()[0], 1u);
    EXPECT_THROW(f.add_pass(std::vector<std::vector<iris::splat>>{{{3, {1, 1, 1}}}}, 1), std::out_of_range);
}

// With the fade layer, a pass is on the early side when its index is below the split, and
// the layer's sums are the film's: the fade sides of a splatting film equal those of a film
// that took each pixel's pass totals with add().
TEST(Film, PassesFallOnTheFadeLayersSidesByTheirIndex) {
    const std::uint32_t n = 4;
    iris::film f(2, 2), g(2, 2);
    f.enable_fade(2);
    g.enable_fade(2);
    for (std::uint64_t pass = 0; pass < 5; ++pass) {
        const std::vector<iris::splat> s{{0, {0.25 * static_cast<double>(pass + 1), 1.0, 0.0}},
                                         {2, {0.5, 0.125 * static_cast<double>(pass), 2.0}},
                                         {2, {0.25, 0.0, 1.0}}};
        f.add_pass(std::vector<std::vector<iris::splat>>{s}, pass);
        std::vector<iris::xyz> t(n);
        for (const auto& x : s) t[x.pixel] = {t[x.pixel].x + x.value.x, t[x.pixel].y + x.value.y, t[x.pixel].z + x.value.z};
        for (std::size_t i = 0; i < n; ++i) g.add(i, t[i], pass);  // dyadic values: the totals are exact
    }
    for (std::size_t i = 0; i < n; ++i) {
        EXPECT_EQ(f.sum(i), g.sum(i));
        const auto a = f.fade_sides(i), b = g.fade_sides(i);
        for (std::size_t c = 0; c < 3; ++c) {
            EXPECT_EQ(a[c].first.n, 2.0);
            EXPECT_EQ(a[c].second.n, 3.0);
            EXPECT_EQ(a[c].first.mean, b[c].first.mean);
            EXPECT_EQ(a[c].second.mean, b[c].second.mean);
            EXPECT_EQ(a[c].first.var_mean, b[c].first.var_mean);
            EXPECT_EQ(a[c].second.var_mean, b[c].second.var_mean);
        }
    }
}

// ---- the spectral layer ------------------------------------------------------------------

namespace spectral {

const iris::spectral_bands bands{4, 400.0, 800.0};  // 100 nm each

}  // namespace spectral

// Contributions land in the band holding their wavelength (edges: the upper band; λmax:
// the last), the mean is sum ÷ (samples · width), the row is cleared, and the XYZ sums are
// those of a film without the layer.
TEST(FilmSpectral, ContributionsLandInTheirBandAndTheMeanIsPerNanometre) {
    EXPECT_EQ(spectral::bands.index(399.999), -1);
    EXPECT_EQ(spectral::bands.index(400.0), 0);
    EXPECT_EQ(spectral::bands.index(499.999), 0);
    EXPECT_EQ(spectral::bands.index(500.0), 1);
    EXPECT_EQ(spectral::bands.index(800.0), 3);
    EXPECT_EQ(spectral::bands.index(800.001), -1);
    EXPECT_EQ(spectral::bands.index(std::numeric_limits<double>::quiet_NaN()), -1);
    EXPECT_DOUBLE_EQ(spectral::bands.centre(1), 550.0);

    iris::film f(2, 1), plain(2, 1);
    f.enable_spectral(spectral::bands);
    std::vector<double> row(4, 0.0);
    iris::spectral_row r(spectral::bands, row.data());
    r.add(450.0, 10.0);
    r.add(460.0, 30.0);
    r.add(799.0, 200.0);
    r.add(900.0, 1e6);  // outside: left out
    f.add(1, {1.0, 2.0, 3.0}, 0, row.data());
    plain.add(1, {1.0, 2.0, 3.0}, 0);
    EXPECT_EQ(row, std::vector<double>(4, 0.0)) << "the film clears the row it summed";
    r.add(550.0, 50.0);
    f.add(1, {1.0, 2.0, 3.0}, 1, row.data());
    plain.add(1, {1.0, 2.0, 3.0}, 1);
    std::vector<double> mean(4);
    f.spectral_mean(1, mean.data());
    EXPECT_DOUBLE_EQ(mean[0], 40.0 / (2 * 100.0));
    EXPECT_DOUBLE_EQ(mean[1], 50.0 / (2 * 100.0));
    EXPECT_DOUBLE_EQ(mean[2], 0.0);
    EXPECT_DOUBLE_EQ(mean[3], 200.0 / (2 * 100.0));
    f.spectral_mean(0, mean.data());
    EXPECT_EQ(mean, std::vector<double>(4, 0.0)) << "no samples: 0";
    EXPECT_EQ(f.sum(1), plain.sum(1));
    EXPECT_EQ(f.spectral_state()->dropped, 0u);
    EXPECT_EQ(iris::film::spectral_bytes_per_band, 16u);
}

// A row with a band out of range is dropped (counted) while its XYZ is summed; a sample
// whose XYZ is dropped adds no row either (and is not counted twice).
TEST(FilmSpectral, ABadRowIsDroppedAndCountedApartFromItsXyz) {
    iris::film f(1, 1);
    f.enable_spectral(spectral::bands);
    std::vector<double> row(4, 0.0);
    row[2] = std::numeric_limits<double>::infinity();
    f.add(0, {1.0, 1.0, 1.0}, 0, row.data());
    EXPECT_EQ(f.spectral_state()->dropped, 1u);
    EXPECT_EQ(f.dropped(), 0u);
    EXPECT_EQ(f.sum(0).y, iris::film::to_fixed(1.0));
    row[1] = 5.0;
    f.add(0, {std::numeric_limits<double>::quiet_NaN(), 1.0, 1.0}, 1, row.data());
    EXPECT_EQ(f.dropped(), 1u);
    EXPECT_EQ(f.spectral_state()->dropped, 1u);
    row[0] = iris::film::max_sample;  // out of range, finite
    f.add(0, {1.0, 1.0, 1.0}, 2, row.data());
    EXPECT_EQ(f.spectral_state()->dropped, 2u);
    for (auto s : f.spectral_state()->sums) EXPECT_EQ(s, 0);
}

// Order independence, merging and the parts round trip, as for the XYZ sums; films with
// other bands do not merge; a spectral film takes no pass of splats; enabling needs an
// empty film and real bands.
TEST(FilmSpectral, SumsAreExactMergeAndRoundTripThroughTheirParts) {
    std::mt19937_64 gen(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0), lambda(400.0, 800.0), exponent(-10.0, 8.0);
    struct sample {
        double lambda, v;
    };
    std::vector<sample> v(2000);
    for (auto& s : v) s = {lambda(gen), unit(gen) * std::pow(10.0, exponent(gen))};
    const auto fill = [&](const std::vector<sample>& samples) {
        iris::film f(1, 1);
        f.enable_spectral(spectral::bands);
        std::vector<double> row(4, 0.0);
        iris::spectral_row r(spectral::bands, row.data());
        for (std::size_t k = 0; k < samples.size(); ++k) {
            r.add(samples[k].lambda, samples[k].v);
            f.add(0, {1.0, 1.0, 1.0}, k, row.data());
        }
        return f;
    };
    auto reversed = v;
    std::reverse(reversed.begin(), reversed.end());
    const iris::film a = fill(v), b = fill(reversed);
    EXPECT_EQ(a.spectral_state()->sums, b.spectral_state()->sums);

    iris::film first = fill({v.begin(), v.begin() + 700});
    first.merge(fill({v.begin() + 700, v.end()}));
    EXPECT_EQ(first.spectral_state()->sums, a.spectral_state()->sums);

    const auto* sp = a.spectral_state();
    const iris::film c = iris::film::from_parts(1, 1, {a.sums().begin(), a.sums().end()}, {a.counts().begin(), a.counts().end()},
                                                {a.dropped_counts().begin(), a.dropped_counts().end()}, std::nullopt, *sp);
    EXPECT_EQ(c.spectral_state()->sums, sp->sums);
    EXPECT_EQ(c.spectral_state()->bands, sp->bands);
    auto short_parts = *sp;
    short_parts.sums.pop_back();
    EXPECT_THROW(iris::film::from_parts(1, 1, {a.sums().begin(), a.sums().end()}, {a.counts().begin(), a.counts().end()},
                                        {a.dropped_counts().begin(), a.dropped_counts().end()}, std::nullopt, short_parts),
                 std::invalid_argument);

    iris::film other(1, 1);
    other.enable_spectral({8, 400.0, 800.0});
    iris::film copy = a;
    EXPECT_THROW(copy.merge(other), std::invalid_argument);
    EXPECT_THROW(copy.merge(iris::film(1, 1)), std::invalid_argument);
    EXPECT_THROW(copy.begin_pass(), std::logic_error);
    EXPECT_THROW(copy.enable_spectral(spectral::bands), std::logic_error);
    iris::film empty(1, 1);
    EXPECT_THROW(empty.enable_spectral({0, 400.0, 800.0}), std::invalid_argument);
    EXPECT_THROW(empty.enable_spectral({4, 800.0, 400.0}), std::invalid_argument);
}
