// The samplers of sample_stream (iris/render/random.hpp): the net property of the Sobol'
// samplers slot by slot, the dimension layout, determinism, and the independent sampler
// unchanged.
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include <iris/render/random.hpp>
#include <iris/sampling/sobol.hpp>

namespace {

using iris::sample_stream;
using iris::sampler_kind;
using iris::sampler_setup;

// The numbers of slot `slot` of samples [0, n) of pixel (x, y) in a w-wide image.
std::vector<glm::vec2> slot_points(sampler_kind k, int spp, std::uint32_t x, std::uint32_t y, int w, std::uint32_t slot,
                                   bool two, std::uint64_t seed = 3) {
    const auto setup = sampler_setup::make(k, seed, static_cast<std::uint64_t>(spp));
    std::vector<glm::vec2> pts;
    for (int i = 0; i < spp; ++i) {
        sample_stream s(setup, x, y, std::uint64_t{y} * static_cast<std::uint64_t>(w) + x, static_cast<std::uint64_t>(i));
        // walk to the slot the way the path tracer does
        if (slot >= sample_stream::first_bounce_slot)
            s.start_bounce(static_cast<int>((slot - sample_stream::first_bounce_slot) / sample_stream::slots_per_bounce));
        while (s.slot() < slot) (void)s.next();
        pts.push_back(two ? s.next2() : glm::vec2{s.next(), 0.0f});
    }
    return pts;
}

// (0, m, 2)-net: for every a + b = m, exactly one point in each 2^-a × 2^-b box.
bool is_net(const std::vector<glm::vec2>& pts, int m) {
    for (int a = 0; a <= m; ++a) {
        const int b = m - a;
        std::set<std::uint64_t> boxes;
        for (const auto& p : pts) {
            const auto i = static_cast<std::uint64_t>(p.x * static_cast<float>(1 << a));
            const auto j = static_cast<std::uint64_t>(p.y * static_cast<float>(1 << b));
            if (!boxes.insert(i << 32 | j).second) return false;
        }
    }
    return true;
}

bool is_stratified(const std::vector<glm::vec2>& pts, int m) {
    std::set<std::uint64_t> strata;
    for (const auto& p : pts)
        if (!strata.insert(static_cast<std::uint64_t>(p.x * static_cast<float>(1 << m))).second) return false;
    return true;
}

// Slot layout (random.hpp): 0 pixel 2-D, 1 hero 1-D, 2 B 1-D, then per bounce light point
// 2-D, light choice 1-D, lobe 1-D, BSDF direction 2-D, roulette 1-D.
struct slot_kind {
    std::uint32_t slot;
    bool two;
    const char* what;
};
constexpr slot_kind layout[] = {{0, true, "pixel jitter"},     {1, false, "hero u"},
                                {2, false, "B jitter"},        {3, true, "bounce 0 light point"},
                                {4, false, "bounce 0 light choice"}, {5, false, "bounce 0 lobe"},
                                {6, true, "bounce 0 BSDF direction"}, {7, false, "bounce 0 roulette"},
                                {8, true, "bounce 1 light point"},    {11, true, "bounce 1 BSDF direction"},
                                {3 + 5 * 20, true, "bounce 20 light point"},
                                {iris::sobol::dimensions + 40, true, "a 2-D slot past the table (padded)"},
                                {iris::sobol::dimensions + 41, false, "a 1-D slot past the table (padded)"}};

TEST(Sampler, SobolSamplersPutAPixelsFirstTwoToTheMSamplesInANetInEverySlot) {
    for (auto k : {sampler_kind::sobol, sampler_kind::zsobol})
        for (int m : {0, 1, 2, 4, 7, 10})
            for (const auto& s : layout)
                for (auto [x, y] : {std::pair<std::uint32_t, std::uint32_t>{0, 0}, {5, 3}, {77, 40}}) {
                    // the render's spp may be larger than 2^m: its first 2^m samples count
                    const int spp = (1 << m) * (m % 2 ? 1 : 4);
                    auto pts = slot_points(k, spp, x, y, 100, s.slot, s.two);
                    pts.resize(std::size_t{1} << m);
                    if (s.two)
                        EXPECT_TRUE(is_net(pts, m)) << iris::sampler_name(k) << " " << s.what << ", m " << m << ", pixel "
                                                    << x << "," << y;
                    else
                        EXPECT_TRUE(is_stratified(pts, m))
                            << iris::sampler_name(k) << " " << s.what << ", m " << m << ", pixel " << x << "," << y;
                }
}

// The negative control: independent numbers are not a net (at m = 6, 64 points in 64 strata
// have probability 64!/64^64 of being stratified).
TEST(Sampler, IndependentSamplesAreNotStratified) {
    const auto pts = slot_points(sampler_kind::independent, 64, 5, 3, 100, 0, true);
    EXPECT_FALSE(is_net(pts, 6));
}

// zsobol: the pixels of an aligned 2^k × 2^k block share one net (the blue-noise property):
// slot 0 of all their samples together is a (0, 2k + log2 spp, 2)-net.
TEST(Sampler, ZSobolPixelsOfAnAlignedBlockShareOneNet) {
    const int spp = 4, w = 64;
    std::vector<glm::vec2> block;
    for (std::uint32_t y = 8; y < 12; ++y)
        for (std::uint32_t x = 4; x < 8; ++x) {
            const auto pts = slot_points(sampler_kind::zsobol, spp, x, y, w, 6, true);
            block.insert(block.end(), pts.begin(), pts.end());
        }
    EXPECT_TRUE(is_net(block, 6));  // 16 pixels × 4 samples
    // the per-pixel sobol sampler scrambles each pixel on its own: no joint net
    std::vector<glm::vec2> apart;
    for (std::uint32_t y = 8; y < 12; ++y)
        for (std::uint32_t x = 4; x < 8; ++x) {
            const auto pts = slot_points(sampler_kind::sobol, spp, x, y, w, 6, true);
            apart.insert(apart.end(), pts.begin(), pts.end());
        }
    EXPECT_FALSE(is_net(apart, 6));
}

// Slots skipped on one path (no B term, a delta vertex without next-event estimation) do not
// shift the slots after them; different slots, pixels and seeds are decorrelated.
TEST(Sampler, SlotsArePureFunctionsOfTheirKey) {
    for (auto k : {sampler_kind::sobol, sampler_kind::zsobol}) {
        const auto setup = sampler_setup::make(k, 9, 16);
        sample_stream a(setup, 3, 4, 4 * 10 + 3, 5), b(setup, 3, 4, 4 * 10 + 3, 5);
        (void)a.next2();
        (void)a.next();
        (void)a.next();  // a used the B slot, b did not
        (void)b.next2();
        (void)b.next();
        a.start_bounce(2);
        b.start_bounce(2);
        EXPECT_EQ(a.next2(), b.next2()) << iris::sampler_name(k);
        EXPECT_EQ(a.slot(), sample_stream::first_bounce_slot + 2 * sample_stream::slots_per_bounce + 1);
        sample_stream other_seed(sampler_setup::make(k, 10, 16), 3, 4, 43, 5);
        sample_stream c(setup, 3, 4, 43, 5);
        EXPECT_NE(c.next2(), other_seed.next2()) << iris::sampler_name(k);
        // two slots of one sample differ
        sample_stream d(setup, 3, 4, 43, 5);
        const auto p0 = d.next2();
        d.start_bounce(0);
        EXPECT_NE(p0, d.next2()) << iris::sampler_name(k);
    }
}

// The independent stream is counter_rng walked dimension by dimension, whatever the layout:
// the images of iris before the samplers.
TEST(Sampler, IndependentIsTheCounterRng) {
    const auto setup = sampler_setup::make(sampler_kind::independent, 42, 64);
    sample_stream s(setup, 3, 2, 2 * 8 + 3, 17);
    iris::counter_rng r(42, 2 * 8 + 3, 17);
    EXPECT_EQ(s.next2(), (glm::vec2{r.at(0), r.at(1)}));
    s.start_bounce(3);
    EXPECT_EQ(s.next(), r.at(2));
}

// The building blocks: bit reversal, Sobol' dimension 1 against its definition, the
// shuffle's aligned-block property, Morton order.
TEST(Sobol, BuildingBlocks) {
    using namespace iris::sobol;
    EXPECT_EQ(reverse_bits(1u), 0x80000000u);
    EXPECT_EQ(reverse_bits(0x12345678u), 0x1e6a2c48u);
    // dimension 1's first points: 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8
    const double want[] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
    for (std::uint32_t i = 0; i < 8; ++i) EXPECT_EQ(dimension1(i) * 0x1.0p-32, want[i]) << i;
    // the byte tables are the column definition
    for (std::uint32_t i : {0u, 1u, 255u, 256u, 0x12345678u, 0xdeadbeefu, 0xffffffffu})
        EXPECT_EQ(dimension1(i), dimension1_by_columns(i)) << i;
    for (std::uint32_t seed : {0u, 1u, 0xdeadbeefu}) {
        std::set<std::uint32_t> first16;
        for (std::uint32_t i = 0; i < 16; ++i) first16.insert(shuffle_index(i, seed) >> 4);
        EXPECT_EQ(first16.size(), 1u) << "the first 16 shuffled indices are one aligned block";
        std::set<std::uint64_t> first32;
        for (std::uint64_t i = 0; i < 32; ++i) first32.insert(shuffle_index64((7ull << 40) + i, seed) >> 5);
        EXPECT_EQ(first32.size(), 1u);
    }
    // Owen scrambling is nested: whether bit 1 (weight 1/4) flips depends on bit 0, for about
    // half the seeds (a digital shift, v ^ seed, flips it the same way for every v)
    int differs = 0;
    for (std::uint32_t seed = 0; seed < 64; ++seed) {
        const auto flip = [&](std::uint32_t v) { return ((owen_scramble(v, seed * 0x9e3779b9u) ^ v) >> 30) & 1u; };
        differs += flip(0) != flip(0x80000000u);
    }
    EXPECT_GT(differs, 16);
    EXPECT_LT(differs, 48);
    // the shuffle XORed with its value at 0 maps [0, 2^m) onto itself
    for (std::uint32_t seed : {0u, 1u, 0xdeadbeefu}) {
        std::set<std::uint32_t> first64;
        for (std::uint32_t i = 0; i < 64; ++i) first64.insert(shuffle_index(i, seed) ^ shuffle_index(0, seed));
        EXPECT_EQ(first64.size(), 64u);
        EXPECT_LT(*first64.rbegin(), 64u);
    }
    EXPECT_EQ(morton2(1, 0), 1u);
    EXPECT_EQ(morton2(0, 1), 2u);
    EXPECT_EQ(morton2(3, 3), 15u);
    EXPECT_EQ(morton2(0xffff, 0), 0x55555555u);
}

// Joe & Kuo's table as transcribed (data/sobol_joe_kuo_6_256.txt): each row's polynomial
// x^s + a₁x^(s−1) + … + a_(s−1)x + 1 is primitive over GF(2) (x has order 2^s − 1 modulo it),
// the degrees never fall, and every m_k is odd and below 2^k; dimension 0 is van der
// Corput and dimension 1 the column definition above. A wrong digit in s or a fails the
// first check, one in m the last.
TEST(Sobol, JoeKuoRowsArePrimitivePolynomialsWithValidDirectionNumbers) {
    using namespace iris::sobol;
    unsigned last_degree = 1;
    for (const auto& r : iris::data::sobol_joe_kuo::rows) {
        const std::uint64_t poly = (1ull << r.s) | (static_cast<std::uint64_t>(r.a) << 1) | 1u;
        const std::uint64_t order = (1ull << r.s) - 1;
        auto mulx = [&](std::uint64_t v) {  // v · x mod poly
            v <<= 1;
            return (v >> r.s) & 1u ? v ^ poly : v;
        };
        std::uint64_t v = 1, n = 0;
        do v = mulx(v), ++n;
        while (v != 1 && n <= order);
        EXPECT_EQ(n, order) << "dimension " << r.d << ": not primitive";
        EXPECT_GE(r.s, last_degree) << r.d;
        last_degree = r.s;
        for (unsigned k = 0; k < r.s; ++k) {
            EXPECT_EQ(r.m[k] % 2, 1u) << r.d << " m" << k + 1;
            EXPECT_LT(r.m[k], 1u << (k + 1)) << r.d << " m" << k + 1;
        }
    }
    for (std::uint32_t i : {0u, 1u, 6u, 255u, 0x12345678u, 0xffffffffu}) {
        EXPECT_EQ(point(i, 0), reverse_bits(i));
        EXPECT_EQ(point(i, 1), dimension1_by_columns(i));
    }
    // dimension 2 (x² + x + 1, m = 1, 3; the recurrence gives m₃ = 2·3 ⊕ 4·1 ⊕ 1 = 3)
    const double want[] = {0, 0.5, 0.75, 0.25, 0.375, 0.875, 0.625, 0.125};
    for (std::uint32_t i = 0; i < 8; ++i) EXPECT_EQ(point(i, 2) * 0x1.0p-32, want[i]) << i;
}

// Every dimension's (0, 2) partner: the first 2^m points of (x_d, paired(x_d)) are a
// (0, m, 2)-net for every d in the table and m ≤ 10 (the proof is in sobol.hpp; the control
// pairs dimension d with dimension d + 1, which is not a (0, 2)-sequence).
TEST(Sobol, EveryDimensionWithItsPartnerIsAZeroTwoSequence) {
    using namespace iris::sobol;
    int controls_failed = 0;
    for (std::uint32_t d = 0; d + 1 < dimensions; ++d)
        for (int m : {1, 4, 7, 10}) {
            std::vector<glm::vec2> pts, control;
            for (std::uint32_t i = 0; i < (1u << m); ++i) {
                const std::uint32_t x = point(i, d);
                pts.push_back({to_unit(x), to_unit(paired(x))});
                control.push_back({to_unit(x), to_unit(point(i, d + 1))});
            }
            EXPECT_TRUE(is_net(pts, m)) << "dimension " << d << ", m " << m;
            controls_failed += !is_net(control, m);
        }
    EXPECT_GT(controls_failed, 500);
}

// The smallest t for which the 2^m points are a (t, m, 2)-net: 2^t points in every
// elementary box of area 2^(t-m).
int t_value(const std::vector<glm::vec2>& pts, int m) {
    for (int t = 0; t < m; ++t) {
        bool ok = true;
        for (int a = 0; a <= m - t && ok; ++a) {
            const int b = m - t - a;
            std::map<std::uint64_t, int> count;
            for (const auto& p : pts)
                ++count[static_cast<std::uint64_t>(p.x * static_cast<float>(1 << a)) << 32 |
                        static_cast<std::uint64_t>(p.y * static_cast<float>(1 << b))];
            ok = count.size() == (std::size_t{1} << (m - t));
        }
        if (ok) return t;
    }
    return m;
}

// Across slots: every 2-D projection of the coordinates of the camera slots and bounce 0
// (pixel x and y, hero u, B jitter, light point x and y, light choice, lobe, BSDF direction
// x and y, roulette) of a pixel's first 2^m samples is a (t, m, 2)-net with t ≤ 4 for
// m ≤ 10, the bound scripts/gen_sobol_slots.py chose the slots' dimensions for. The control:
// dimension slot + 1 for the light point would pair its y with the pixel's y at t = 9.
TEST(Sampler, SobolSlotsAreStratifiedJointly) {
    for (auto k : {sampler_kind::sobol, sampler_kind::zsobol})
        for (int m : {4, 6, 8, 10}) {
            std::vector<std::vector<glm::vec2>> coords;  // one per coordinate, (value, 0)
            for (const auto& s : layout) {
                if (s.slot > 7) continue;
                const auto pts = slot_points(k, 1 << m, 5, 3, 100, s.slot, s.two);
                std::vector<glm::vec2> x, y;
                for (const auto& p : pts) x.push_back({p.x, 0}), y.push_back({p.y, 0});
                coords.push_back(x);
                if (s.two) coords.push_back(y);
            }
            ASSERT_EQ(coords.size(), 11u);
            int worst = 0;
            for (std::size_t i = 0; i < coords.size(); ++i)
                for (std::size_t j = i + 1; j < coords.size(); ++j) {
                    std::vector<glm::vec2> pair;
                    for (std::size_t n = 0; n < coords[i].size(); ++n) pair.push_back({coords[i][n].x, coords[j][n].x});
                    worst = std::max(worst, t_value(pair, m));
                }
            EXPECT_LE(worst, 4) << iris::sampler_name(k) << ", m " << m;
            if (m == 10) {
                EXPECT_GE(worst, 2) << "a 0 would mean the check sees no structure at all";
            }
        }
    using namespace iris::sobol;
    std::vector<glm::vec2> naive;
    for (std::uint32_t i = 0; i < 1024; ++i) naive.push_back({to_unit(paired(point(i, 0))), to_unit(paired(point(i, 4)))});
    EXPECT_EQ(t_value(naive, 10), 9);
}

}  // namespace

// A bounce that draws more than its slots reads numbers of its own past the table, not the
// next bounce's (render/random.hpp), and the stream counts it; the next bounce is unchanged.
TEST(Sampler, ABounceThatOverflowsReadsNoOtherSlot) {
    for (auto k : {sampler_kind::sobol, sampler_kind::zsobol}) {
        const auto setup = sampler_setup::make(k, 9, 16);
        sample_stream a(setup, 3, 4, 43, 5), b(setup, 3, 4, 43, 5);
        a.start_bounce(0);
        b.start_bounce(1);
        std::vector<float> bounce1;
        for (std::uint32_t i = 0; i < sample_stream::slots_per_bounce; ++i) bounce1.push_back(b.next());
        for (std::uint32_t i = 0; i < sample_stream::slots_per_bounce; ++i) (void)a.next();
        EXPECT_EQ(a.overflows(), 0u);
        std::vector<float> extra;
        for (int i = 0; i < 3 * static_cast<int>(sample_stream::slots_per_bounce); ++i) extra.push_back(a.next());
        EXPECT_EQ(a.overflows(), 1u) << iris::sampler_name(k);
        for (float x : extra)
            for (float y : bounce1) EXPECT_NE(x, y) << iris::sampler_name(k);
        a.start_bounce(1);
        for (std::uint32_t i = 0; i < sample_stream::slots_per_bounce; ++i) EXPECT_EQ(a.next(), bounce1[i]) << i;
        EXPECT_EQ(a.overflows(), 1u);
        // the camera's slots (before bounce 0) are guarded as well
        sample_stream c(setup, 3, 4, 43, 5);
        for (std::uint32_t i = 0; i < sample_stream::first_bounce_slot; ++i) (void)c.next();
        const float past = c.next();
        EXPECT_EQ(c.overflows(), 1u);
        sample_stream d(setup, 3, 4, 43, 5);
        d.start_bounce(0);
        EXPECT_NE(past, d.next());
    }
}
