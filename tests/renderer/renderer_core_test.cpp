// The renderer (Embree, TBB, preset dispatch) on analytic scenes: U1 on the white furnace
// for every preset, determinism across thread counts, cancellation, bad options.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <sstream>
#include <string>
#include <thread>

#include <iris/renderer/renderer.hpp>
#include <iris/sampling/presets.hpp>
#include <iris/spectrum/color.hpp>

#include "region_stats.hpp"
#include "test_scenes.hpp"

namespace {

using iris::renderer::options;

/// \brief Per-pixel Y means of the samples with index ≥ from, from two snapshots.
std::vector<double> window_y(const iris::scene_desc& s, const options& o, int from) {
    std::vector<double> at;
    iris::renderer::hooks h;
    h.on_pass = [&](const iris::film& f, const iris::renderer::status& st) {
        if (st.spp_done == from)
            for (std::size_t i = 0; i < static_cast<std::size_t>(f.width() * f.height()); ++i) at.push_back(f.mean(i).y);
        return true;
    };
    iris::film f(1, 1);
    iris::renderer::render(s, o, f, h);
    std::vector<double> y;
    for (std::size_t i = 0; i < static_cast<std::size_t>(f.width() * f.height()); ++i)
        y.push_back((f.mean(i).y * o.spp - (from > 0 ? at[i] * from : 0.0)) / (o.spp - from));
    return y;
}

/// \brief E[Y] of `scaled-pdf` (linear relaxation, uniform base pdf) on the flat furnace
/// over samples [from, to): F = F_R / Z_α weighs each λ by r_α/Z_α · p/p = r_α/∫r_α over
/// the domain Λ, so E[Y]_α = Y · (∫ ȳ r_α / ∫ r_α) / (∫ ȳ / |Λ|) — Y = 5 only where the
/// windows' mean ȳ equals the domain's (docs/method.md §2, Bias policies: "right brightness
/// for flat spectra", flat meaning the integrand L·ȳ, not the emitter). α_i = i / N_thold, written out here.
/// `preset` is `scaled-pdf` or `scaled-pdf-auto`; `windows` what renderer::windows reports
/// for it on the furnace ("c:w,c:w,c:w"), so the automatic windows are the render's own.
double scaled_pdf_furnace_y(const std::string& preset, const std::string& windows, int nthold, int from, int to) {
    return iris::dispatch_preset(preset, [&]<class P>() {
        typename P::parameters params;
        params.n_thold = static_cast<std::uint32_t>(nthold);
        if constexpr (iris::detail::is_multi_box<typename P::kernel_type>) {
            std::istringstream in(windows);
            for (std::size_t k = 0; k < P::kernel_type::max_intervals; ++k) {
                char colon = 0, comma = 0;
                in >> params.kernel.centres_nm[k] >> colon >> params.kernel.widths_nm[k];
                if (k + 1 < P::kernel_type::max_intervals) in >> comma;
                EXPECT_TRUE(in && colon == ':') << "windows '" << windows << "'";
            }
        }
        const P cfg(params);
        const double lo = params.domain.min_nm, hi = params.domain.max_nm, step = 0.05;
        double sum = 0.0;
        for (int i = from; i < to; ++i) {
            const auto dist = cfg.distribution(std::min(1.0f, static_cast<float>(i) / static_cast<float>(nthold)));
            double yr = 0.0, r = 0.0, y = 0.0;
            for (double l = lo + 0.5 * step; l < hi; l += step) {
                const double rl = dist.restriction(static_cast<float>(l));
                yr += iris::cie::y_bar(l) * rl;
                r += rl;
                y += iris::cie::y_bar(l);
            }
            sum += 5.0 * (yr / r) / (y / ((hi - lo) / step));
        }
        return sum / (to - from);
    });
}

/// \brief Mean and standard error of per-pixel values (the furnace's pixels are i.i.d.).
std::pair<double, double> mean_se(const std::vector<double>& y) {
    double m = 0, m2 = 0;
    for (double v : y) m += v, m2 += v * v;
    const double n = static_cast<double>(y.size());
    m /= n;
    return {m, std::sqrt((m2 / n - m * m) / (n - 1))};
}

// U1 on the flat white furnace, Y = 1/(1 − 0.8) = 5 (max depth 200: 0.8^200 is nothing),
// judged separately on the samples taken while α < 1 ([0, N_thold)) and after ([N_thold,
// spp)): a bias confined to α < 1 would be diluted over the whole run. Before N_thold
// the unrestricted and propagating presets must give 5 (U1), and `scaled-pdf` its own
// exact expectation (`scaled_pdf_furnace_y`: 6.4 here, brighter because its windows sit
// where ȳ is high; `scaled-pdf-auto`'s, from its own windows, 7.1), which pins its
// division by Z_α; after N_thold every preset gives 5.
// restrict-only before N_thold is the negative control below. Family: ≤ 16 presets × 2 windows at family-wise α = 0.01 (Šidák); each
// window's standard error is asserted small enough to detect a 2 % bias (0.1) with 90 %
// power: (z + 1.2816) · se ≤ 0.1.
TEST(RendererCore, WhiteFurnaceIsFiveForEveryPresetBeforeAndAfterNthold) {
    const auto s = iris::test::furnace(0.8);
    const auto presets = iris::renderer::presets();
    ASSERT_LE(presets.size(), 16u);
    const double z = iris_test::sidak_z(0.01, 2 * presets.size());
    for (const auto& p : presets) {
        const bool scaled = p.config.find("/scaled") != std::string::npos;
        options o;
        o.preset = p.name;
        o.width = o.height = 48;
        o.spp = 256;
        o.nthold = 128;
        o.seed = 11;
        o.path.max_depth = 200;
        const std::pair<int, int> windows[] = {{0, o.nthold}, {o.nthold, o.spp}};
        for (std::size_t k = p.unbiased_before_nthold || scaled ? 0 : 1; k < 2; ++k) {
            const auto [from, to] = windows[k];
            auto w = o;
            w.spp = to;  // samples [from, to): the run up to `to`, less its first `from`
            const auto [m, se] = mean_se(window_y(s, w, from));
            const double want = scaled && from < o.nthold
                                    ? scaled_pdf_furnace_y(p.name, iris::renderer::windows(s, p.name), o.nthold, from, to)
                                    : 5.0;
            EXPECT_NEAR(m, want, z * se) << p.name << ", samples [" << from << ", " << to << "), se " << se;
            EXPECT_LE((z + 1.2816) * se, 0.1) << p.name << ": cannot detect a 2 % bias, se " << se;
        }
    }
}

// accumulation::fade changes what the film shows, not which samples it takes: `paper-fade`'s
// running mean is `paper`'s bit for bit, and so is its image until two samples have been
// taken at α = 1 (N_thold + 2); after that the image is the blend, which differs. A fading
// render resumed at a pass, or split over ranks, gives the uninterrupted film's fade layer
// and image bit for bit (would catch a resumed film without its layer, or a rank's layer
// left out of the merge: the blend would differ); a film without the layer, or split at
// another N_thold, is refused.
TEST(RendererCore, PaperFadeTakesPapersSamplesAndFadesOnlyAfterNthold) {
    const auto s = iris::test::furnace(0.8);
    options o;
    o.width = 12;
    o.height = 10;
    o.nthold = 8;
    o.seed = 5;
    const auto run = [&](const std::string& preset, int spp) {
        auto w = o;
        w.preset = preset;
        w.spp = spp;
        iris::film f(1, 1);
        iris::renderer::render(s, w, f, {});
        return f;
    };
    for (int spp : {4, 9, 10, 24}) {
        const auto plain = run("paper", spp), fade = run("paper-fade", spp);
        ASSERT_TRUE(fade.fades());
        ASSERT_FALSE(plain.fades());
        const auto a = plain.to_image(), b = fade.to_image();
        bool image_same = true;
        for (std::size_t i = 0; i < 120; ++i) {
            ASSERT_EQ(plain.sum(i), fade.sum(i)) << spp << " spp, pixel " << i;
            image_same = image_same && a.pixels()[i].g == b.pixels()[i].g;
        }
        EXPECT_EQ(image_same, spp < o.nthold + 2) << spp << " spp";
    }
    const auto whole = run("paper-fade", 16);
    const auto expect_same = [&](const iris::film& f) {
        const iris::film::fade_parts *pa = whole.fade_state(), *pb = f.fade_state();
        ASSERT_TRUE(pa != nullptr && pb != nullptr);
        const auto &a = *pa, &b = *pb;
        for (std::size_t i = 0; i < 120; ++i) {
            ASSERT_EQ(whole.sum(i), f.sum(i)) << "pixel " << i;
            ASSERT_EQ(a.early_sum[i], b.early_sum[i]) << "pixel " << i;
            ASSERT_EQ(a.early_count[i], b.early_count[i]) << "pixel " << i;
            ASSERT_EQ(a.early_sq[i], b.early_sq[i]) << "pixel " << i;
            ASSERT_EQ(a.late_sq[i], b.late_sq[i]) << "pixel " << i;
        }
        const auto x = whole.to_image(), y = f.to_image();
        for (std::size_t i = 0; i < 120; ++i) ASSERT_EQ(x.pixels()[i].g, y.pixels()[i].g) << "pixel " << i;
    };
    auto resume = o;
    resume.preset = "paper-fade";
    resume.spp = 16;
    resume.start_spp = 5;  // before N_thold = 8: the resumed passes are early and late
    {
        iris::film f = run("paper-fade", 5);
        iris::renderer::render(s, resume, f, {});
        expect_same(f);
    }
    for (int start : {0, 5}) {  // ranks 0 and 1 of 2, from the start and from a resumed film
        SCOPED_TRACE(start);
        iris::film sum = start > 0 ? run("paper-fade", start) : iris::film(12, 10);
        if (start == 0) sum.enable_fade(8);
        for (int r = 0; r < 2; ++r) {
            auto part = resume;
            part.start_spp = start;
            part.rank = r;
            part.ranks = 2;
            iris::film f(12, 10);  // an empty film: the renderer gives it the layer
            iris::renderer::render(s, part, f, {});
            sum.merge(f);
        }
        expect_same(sum);
    }
    iris::film plain = run("paper", 5);  // no fade layer to go on from
    EXPECT_THROW(iris::renderer::render(s, resume, plain, {}), std::invalid_argument);
    iris::film other = run("paper-fade", 5);
    resume.nthold = 6;  // the film splits at 8
    EXPECT_THROW(iris::renderer::render(s, resume, other, {}), std::invalid_argument);
}

TEST(RendererCore, RestrictOnlyIsDimBeforeNtholdNegativeControl) {
    const auto s = iris::test::furnace(0.8);
    options o;
    o.preset = "restrict-only";
    o.width = o.height = 16;
    o.spp = 32;
    o.nthold = 512;
    o.path.max_depth = 200;
    // restriction without a bias term loses the light outside the windows: the mean must
    // be below 5 by more than a one-sided z test at 0.001 allows (z = 3.09)
    const auto [m, se] = mean_se(window_y(s, o, 0));
    EXPECT_GT((5.0 - m) / se, 3.09) << "restrict-only before N_thold: Y " << m << " ± " << se;
}

// Determinism, for every sampler: a pixel's samples depend on (seed, pixel, sample index) only. 160 × 120
// pixels in tiles of 8 (300 tiles a pass) on 1, 3 and 4 threads, and in tiles of 13 and 64: the
// images must be identical, and each multi-threaded render must spread its tiles over more
// than one thread (a random stream keyed by the thread would pass otherwise). Left to the
// scheduler, a loaded machine may let the calling thread do a whole short render (CI saw 100
// renders in a row on one thread), so the test makes a second thread take part: the calling
// thread (arena slot 0) waits in its first chunk of tiles until another slot has started one.
TEST(RendererCore, IdenticalPixelsForAnyThreadCountAndTiling) {
    if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "needs two hardware threads";
    const iris::sellmeier_ior bk7{1.03961212, 0.231792344, 1.01046945, 0.00600069867, 0.0200179144, 103.560653};
    const auto s = iris::test::furnace_with_glass(0.5, bk7);
    std::string sampler;
    auto run = [&](int threads, int tile, std::uint64_t seed) {
        options o;
        o.sampler = sampler;
        o.preset = "paper";
        o.width = 160;
        o.height = 120;
        o.spp = 8;
        o.nthold = 4;
        o.threads = threads;
        o.tile_size = tile;
        o.seed = seed;
        std::atomic<bool> other{false}, waited{false};
        iris::renderer::hooks h;
        if (threads > 1)
            h.on_tile = [&](int slot) {
                if (slot != 0) {
                    other.store(true);
                } else if (!waited.exchange(true)) {
                    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
                    while (!other.load() && std::chrono::steady_clock::now() < until)
                        std::this_thread::sleep_for(std::chrono::milliseconds(1));
                }
            };
        iris::film f(1, 1);
        const auto st = iris::renderer::render(s, o, f, h);
        EXPECT_EQ(st.threads, threads);
        if (threads > 1) {
            EXPECT_GE(st.threads_used, 2) << threads << " threads, tiles of " << tile
                                          << ": no second thread took a tile within a minute";
        }
        return f.to_image();
    };
    for (const char* smp : {"independent", "sobol", "zsobol"}) {
        sampler = smp;
        const auto a = run(1, 8, 7);
        for (const auto& [threads, tile] : std::vector<std::pair<int, int>>{{3, 8}, {4, 8}, {3, 13}})
            EXPECT_TRUE(a == run(threads, tile, 7)) << smp << ", " << threads << " threads, tiles of " << tile;
        EXPECT_TRUE(a == run(1, 64, 7)) << smp;
        EXPECT_TRUE(a == run(1, 8, 7)) << smp << ": a second run";
        EXPECT_FALSE(a == run(3, 8, 8)) << smp << ": another seed, another image";
    }
}

// The relaxation schedule the renderer runs: sample i of a pixel is drawn from p_α with
// α = curve(i / N_thold), i = 0 first (docs/method.md §1), written out here for the linear, quadratic
// and constant curves.
TEST(RendererCore, SampleIUsesAlphaOfIOverNthold) {
    const auto s = iris::test::furnace(0.8);
    const struct {
        const char* preset;
        double (*curve)(double);
    } cases[] = {{"paper", [](double t) { return t; }},
                 {"paper-quadratic", [](double t) { return t * t; }},
                 {"hwss", [](double) { return 1.0; }}};
    for (const auto& c : cases) {
        options o;
        o.preset = c.preset;
        o.width = o.height = 2;
        o.spp = 12;
        o.nthold = 8;
        int checked = 0;
        iris::renderer::hooks h;
        h.on_pass = [&](const iris::film&, const iris::renderer::status& st) {
            const int i = st.spp_done - 1;  // the sample index of the pass just done
            const double want = c.curve(std::min(1.0, static_cast<double>(i) / o.nthold));
            EXPECT_NEAR(st.alpha, want, 1e-6) << c.preset << ", sample " << i;
            ++checked;
            return true;
        };
        iris::film f(1, 1);
        iris::renderer::render(s, o, f, h);
        EXPECT_EQ(checked, o.spp);
    }
}

TEST(RendererCore, CancelKeepsTheLastCompletePass) {
    const auto s = iris::test::furnace(0.5);
    options o;
    o.spp = 100;
    o.width = o.height = 8;
    std::atomic<bool> cancel{false};
    iris::renderer::hooks h;
    h.cancel = &cancel;
    h.on_pass = [&](const iris::film&, const iris::renderer::status& st) {
        if (st.spp_done == 3) cancel = true;
        return true;
    };
    iris::film f(1, 1);
    const auto st = iris::renderer::render(s, o, f, h);
    EXPECT_TRUE(st.interrupted);
    EXPECT_EQ(st.spp_done, 3);
    for (std::size_t i = 0; i < 64; ++i) EXPECT_EQ(f.samples(i), 3u);
}

TEST(RendererCore, BadOptionsNameWhatIsAccepted) {
    const auto s = iris::test::furnace(0.5);
    iris::film f(1, 1);
    options o;
    o.preset = "no-such-preset";
    try {
        iris::renderer::render(s, o, f);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("paper"), std::string::npos) << e.what();
    }
    o.preset = "hwss";
    o.spp = 0;
    EXPECT_THROW(iris::renderer::render(s, o, f), std::invalid_argument);
    o.spp = 1;
    o.nthold = 0;
    EXPECT_THROW(iris::renderer::render(s, o, f), std::invalid_argument);
    o.nthold = 1;
    o.width = -3;
    o.height = 4;
    EXPECT_THROW(iris::renderer::render(s, o, f), std::invalid_argument);
    o.width = o.height = 0;
    o.isa = "sse9";
    try {
        iris::renderer::render(s, o, f);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("avx2"), std::string::npos) << e.what();
    }
    o.isa = "avx512";  // no longer compiled: refused with the reason
    try {
        iris::renderer::render(s, o, f);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("no longer compiled"), std::string::npos) << e.what();
    }
    const auto sets = iris::renderer::instruction_sets();
    for (const char* isa : {"avx2"})  // known, but refused where this CPU cannot run it
        if (std::find(sets.begin(), sets.end(), isa) == sets.end()) {
            o.isa = isa;
            EXPECT_THROW(iris::renderer::render(s, o, f), std::invalid_argument) << isa;
        }
}

TEST(RendererCore, ExtremeIorsStayFinite) {
    for (double eta : {1.0, 4.0}) {
        const auto s = iris::test::furnace_with_glass(0.5, iris::constant_ior{eta});
        options o;
        o.preset = "paper";
        o.width = o.height = 12;
        o.spp = 4;
        o.nthold = 1;
        iris::film f(1, 1);
        EXPECT_EQ(iris::renderer::render(s, o, f).nan_inf, 0u) << eta;
    }
}

}  // namespace
