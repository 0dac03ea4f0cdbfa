// Checkpoints (iris/renderer/checkpoint.hpp) and the renderer's resume and rank options:
// a render split at a pass, or over ranks, gives the uninterrupted film bit for bit; a
// checkpoint file reads back to what was written and every kind of damage is refused.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <iris/renderer/checkpoint.hpp>
#include <iris/renderer/renderer.hpp>
#include <iris/scene/scene.hpp>

namespace {

namespace fs = std::filesystem;
using iris::renderer::checkpoint;
using iris::renderer::checkpoint_error;

iris::renderer::options small(const std::string& sampler) {
    iris::renderer::options o;
    o.preset = "paper";
    o.spp = 9;
    o.width = 24;
    o.height = 16;
    o.threads = 2;
    o.nthold = 4;  // relaxation ends inside the render: α differs between the parts
    o.sampler = sampler;
    return o;
}

void expect_identical(const iris::film& a, const iris::film& b) {
    ASSERT_EQ(a.sums().size(), b.sums().size());
    for (std::size_t i = 0; i < a.sums().size(); ++i) {
        ASSERT_EQ(a.sum(i), b.sum(i)) << "pixel " << i;
        ASSERT_EQ(a.samples(i), b.samples(i)) << "pixel " << i;
    }
    ASSERT_EQ(a.dropped(), b.dropped());
}

// Resume: passes [0, 4) then [4, 9) into the same film equal passes [0, 9) in one call,
// for every sampler (zsobol's points depend on the total spp). Would catch a resumed
// render restarting at pass 0 (12 samples per pixel), replacing the film, or a sample
// index off by one (other sums).
TEST(Resume, ARenderGoesOnFromItsFilmToTheUninterruptedOne) {
    const auto scene = iris::scene::builtin_scene("prism");
    for (const std::string sampler : {"sobol", "zsobol", "independent"}) {
        SCOPED_TRACE(sampler);
        iris::film whole(1, 1), parts(1, 1);
        (void)iris::renderer::render(scene, small(sampler), whole);
        auto o = small(sampler);
        iris::renderer::hooks stop_after_4;
        stop_after_4.on_pass = [](const iris::film&, const iris::renderer::status& st) { return st.spp_done < 4; };
        const auto first = iris::renderer::render(scene, o, parts, stop_after_4);
        ASSERT_EQ(first.spp_done, 4);
        o.start_spp = 4;
        const auto second = iris::renderer::render(scene, o, parts);
        EXPECT_EQ(second.spp_done, 9);
        EXPECT_EQ(second.samples, 5u * 24 * 16);
        expect_identical(parts, whole);
    }
}

// Ranks: the films of ranks 0..N-1 (each its passes i ≡ rank mod N) merged equal the
// single film, for N = 2 and 3 (9 passes: the last round of 3 is complete, of 2 not), and
// from a resumed film. Would catch a rank rendering another's pass or none.
TEST(Resume, TheRanksFilmsSumToTheSingleProcessFilm) {
    const auto scene = iris::scene::builtin_scene("prism");
    iris::film whole(1, 1);
    (void)iris::renderer::render(scene, small("sobol"), whole);
    for (int ranks : {2, 3}) {
        for (int start : {0, 5}) {
            SCOPED_TRACE(ranks * 10 + start);
            iris::film sum(1, 1);
            if (start > 0) {
                auto o = small("sobol");
                o.spp = 9;
                iris::renderer::hooks stop;
                stop.on_pass = [&](const iris::film&, const iris::renderer::status& st) { return st.spp_done < start; };
                (void)iris::renderer::render(scene, o, sum, stop);
            } else {
                sum = iris::film(24, 16);
            }
            for (int r = 0; r < ranks; ++r) {
                auto o = small("sobol");
                o.rank = r;
                o.ranks = ranks;
                o.start_spp = start;
                iris::film part(24, 16);
                const auto st = iris::renderer::render(scene, o, part);
                EXPECT_EQ(st.spp_done, 9);
                sum.merge(part);
            }
            expect_identical(sum, whole);
        }
    }
    auto o = small("sobol");
    o.rank = 2;
    o.ranks = 2;
    iris::film f(1, 1);
    EXPECT_THROW((void)iris::renderer::render(scene, o, f), std::invalid_argument);
    o.rank = 0;
    o.start_spp = 3;  // a film of the wrong size to resume
    EXPECT_THROW((void)iris::renderer::render(scene, o, f), std::invalid_argument);
}

class CheckpointFile : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() /
              ("iris_checkpoint_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir);
        fs::create_directories(dir);
        path = dir / "x.exr.ckpt";
        c.key = {"0.1.0", "prism", 0x0123456789abcdefull, "paper", "nee-mis", "zsobol", 7, 4, 32, 9, 24, 16, 0};
        auto o = small("zsobol");
        o.seed = 7;
        iris::renderer::hooks stop;
        stop.on_pass = [](const iris::film&, const iris::renderer::status& st) { return st.spp_done < 3; };
        (void)iris::renderer::render(iris::scene::builtin_scene("prism"), o, c.image, stop);
        c.spp_done = 3;
        c.samples = 3 * 24 * 16;
        c.rays = 12345;
        c.seconds = 0.125;
        iris::renderer::write_checkpoint(path, c);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string bytes() const {
        std::ifstream in(path, std::ios::binary);
        std::string b(static_cast<std::size_t>(fs::file_size(path)), '\0');
        in.read(b.data(), static_cast<std::streamsize>(b.size()));
        return b;
    }
    void rewrite(const std::string& b) const { std::ofstream(path, std::ios::binary) << b; }
    /// \brief `b` with its checksum (FNV-1a of everything before it) made right again.
    static void fix_checksum(std::string& b) {
        std::uint64_t h = 0xcbf29ce484222325ull;
        for (std::size_t i = 0; i + 8 < b.size(); ++i) h = (h ^ static_cast<unsigned char>(b[i])) * 0x100000001b3ull;
        std::memcpy(b.data() + b.size() - 8, &h, 8);
    }
    /// \brief Rewrite the file as an older format `version` would have it: without the
    /// header line `field` (the header length and the checksum made right).
    void rewrite_as_version(std::uint8_t version, const std::string& field) const {
        std::string b = bytes();
        const auto at = b.find(field);
        ASSERT_NE(at, std::string::npos);
        b.erase(at, field.size());
        b[8] = static_cast<char>(version);
        std::uint32_t length = 0;
        std::memcpy(&length, b.data() + 12, 4);
        length -= static_cast<std::uint32_t>(field.size());
        std::memcpy(b.data() + 12, &length, 4);
        fix_checksum(b);
        rewrite(b);
    }
    /// \brief read_checkpoint must throw checkpoint_error whose message contains `what`.
    void expect_refused(const std::string& what) const {
        try {
            (void)iris::renderer::read_checkpoint(path);
            ADD_FAILURE() << "read, expected an error containing '" << what << "'";
        } catch (const checkpoint_error& e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    }
    fs::path dir, path;
    checkpoint c;
};

// Written and read back: the same key, counters and film; no temporary left beside it.
TEST_F(CheckpointFile, ReadsBackWhatWasWritten) {
    const checkpoint r = iris::renderer::read_checkpoint(path);
    EXPECT_EQ(r.key, c.key);
    EXPECT_EQ(r.spp_done, 3);
    EXPECT_EQ(r.samples, c.samples);
    EXPECT_EQ(r.rays, 12345u);
    EXPECT_EQ(r.seconds, 0.125);
    expect_identical(r.image, c.image);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

// Damage anywhere is refused with a message saying what: one flipped bit in the sums,
// the header or the checksum; a truncated or extended file; another magic or version; a
// missing file. Would catch a reader that trusts the file (garbage image) or crashes.
TEST_F(CheckpointFile, DamagedFilesAreRefusedWithTheReason) {
    const std::string good = bytes();
    const std::size_t header_end = good.find("seconds=");
    ASSERT_NE(header_end, std::string::npos);
    for (std::size_t at : {good.size() / 2, header_end + 2, good.size() - 3}) {  // a sum, the header, the checksum
        std::string b = good;
        b[at] = static_cast<char>(b[at] ^ 0x10);
        rewrite(b);
        SCOPED_TRACE(at);
        expect_refused("corrupt");
    }
    rewrite(good.substr(0, good.size() - 1));
    expect_refused("bytes, a 24x16 checkpoint has");
    rewrite(good + "x");
    expect_refused("bytes, a 24x16 checkpoint has");
    rewrite(good.substr(0, 10));
    expect_refused("truncated");
    rewrite("PNG" + good.substr(3));
    expect_refused("does not start with IRISCKPT");
    {
        std::string b = good;
        b[8] = 4;  // format version 4
        rewrite(b);
        expect_refused("format version 4");
    }
    {
        std::string b = good;  // a header field that is not a number
        const auto at = b.find("nthold=4");
        b[at + 7] = 'x';
        rewrite(b);
        expect_refused("nthold='x' is not a number");
    }
    fs::remove(path);
    expect_refused("no such file");
}

// A film whose counts are not spp_done everywhere (a checkpoint from a broken writer) is
// refused: resuming it would give a wrong image silently.
TEST_F(CheckpointFile, AFilmThatDoesNotHoldSppDoneSamplesIsRefused) {
    c.spp_done = 2;
    iris::renderer::write_checkpoint(path, c);
    expect_refused("pixel 0 has 3 samples, spp_done is 2");
}

// Format version 1 (before the fade layer: no fade_split) is still read, to the same film.
// Would catch a reader that demands fade_split of every file.
TEST_F(CheckpointFile, VersionOneIsStillRead) {
    rewrite_as_version(1, "fade_split=0\n");
    const checkpoint r = iris::renderer::read_checkpoint(path);
    EXPECT_FALSE(r.image.fades());
    expect_identical(r.image, c.image);
}

// A fading preset's film (paper-fade, N_thold 4, stopped after 6 passes: both sides hold
// samples) reads back with its fade layer bit for bit and the same blended image; a layer
// whose early counts are not min(spp_done, split) is refused. Would catch a writer or
// reader that drops the layer, one side of it, or a square sum's high part.
TEST_F(CheckpointFile, AFadingFilmKeepsItsFadeLayer) {
    auto o = small("zsobol");
    o.preset = "paper-fade";
    iris::renderer::hooks stop;
    stop.on_pass = [](const iris::film&, const iris::renderer::status& st) { return st.spp_done < 6; };
    checkpoint f = c;
    f.key.preset = "paper-fade";
    (void)iris::renderer::render(iris::scene::builtin_scene("prism"), o, f.image, stop);
    f.spp_done = 6;
    iris::renderer::write_checkpoint(path, f);
    const checkpoint r = iris::renderer::read_checkpoint(path);
    ASSERT_TRUE(r.image.fades());
    expect_identical(r.image, f.image);
    const iris::film::fade_parts *pa = f.image.fade_state(), *pb = r.image.fade_state();
    ASSERT_TRUE(pa != nullptr && pb != nullptr);
    const auto &a = *pa, &b = *pb;
    EXPECT_EQ(b.split, 4u);
    EXPECT_EQ(a.early_sum, b.early_sum);
    EXPECT_EQ(a.early_count, b.early_count);
    EXPECT_EQ(a.early_sq, b.early_sq);
    EXPECT_EQ(a.late_sq, b.late_sq);
    const auto x = f.image.to_image(), y = r.image.to_image();
    for (std::size_t i = 0; i < x.pixels().size(); ++i) ASSERT_EQ(x.pixels()[i].r, y.pixels()[i].r) << "pixel " << i;

    auto broken = a;
    broken.early_count[7] = 3;
    const auto& img = f.image;
    f.image = iris::film::from_parts(24, 16, {img.sums().begin(), img.sums().end()}, {img.counts().begin(), img.counts().end()},
                                     {img.dropped_counts().begin(), img.dropped_counts().end()}, broken);
    iris::renderer::write_checkpoint(path, f);
    expect_refused("pixel 7 has 3 early samples in the fade layer, 4 with spp_done 6 and fade_split 4");
}

// Format version 2 (before the spectral layer: no spectral_bins) is still read, to the same
// film without a layer. Would catch a reader that demands spectral_bins of every file.
TEST_F(CheckpointFile, VersionTwoIsStillRead) {
    rewrite_as_version(2, "spectral_bins=0\n");
    const checkpoint r = iris::renderer::read_checkpoint(path);
    EXPECT_EQ(r.image.spectral_state(), nullptr);
    EXPECT_EQ(r.key.spectral_bins, 0);
    expect_identical(r.image, c.image);
}

// A film with a spectral layer (16 bands) reads back with it bit for bit, its bands and
// its dropped count; a key whose spectral_bins is not the film's is not written; a damaged
// range is refused. Would catch a writer or reader that drops the layer or its range.
TEST_F(CheckpointFile, ASpectralFilmKeepsItsSpectralLayer) {
    auto o = small("zsobol");
    o.spectral_bins = 16;
    iris::renderer::hooks stop;
    stop.on_pass = [](const iris::film&, const iris::renderer::status& st) { return st.spp_done < 3; };
    checkpoint f = c;
    (void)iris::renderer::render(iris::scene::builtin_scene("prism"), o, f.image, stop);
    EXPECT_THROW(iris::renderer::write_checkpoint(path, f), checkpoint_error) << "key without spectral_bins";
    f.key.spectral_bins = 16;
    iris::renderer::write_checkpoint(path, f);
    const checkpoint r = iris::renderer::read_checkpoint(path);
    EXPECT_EQ(r.key.spectral_bins, 16);
    expect_identical(r.image, f.image);
    const auto *a = f.image.spectral_state(), *b = r.image.spectral_state();
    ASSERT_TRUE(a != nullptr && b != nullptr);
    EXPECT_EQ(a->bands, b->bands);
    EXPECT_EQ(a->sums, b->sums);
    EXPECT_EQ(a->dropped, b->dropped);
    std::string bad = bytes();
    const auto at = bad.find("spectral_range=");
    ASSERT_NE(at, std::string::npos);
    bad[at + 15] = 'x';
    fix_checksum(bad);  // a consistent file: the field itself is checked
    rewrite(bad);
    expect_refused("is not two increasing wavelengths");
}

// key_mismatch names the first field that differs, with both values.
TEST(CheckpointKey, AMismatchNamesTheField) {
    const iris::renderer::checkpoint_key a{"0.1.0", "prism", 1, "paper", "nee-mis", "sobol", 7, 4, 32, 9, 24, 16, 0};
    EXPECT_FALSE(iris::renderer::key_mismatch(a, a));
    auto b = a;
    b.seed = 8;
    EXPECT_EQ(iris::renderer::key_mismatch(a, b).value_or(""), "its seed is 7, this render's is 8");
    b = a;
    b.scene_fingerprint = 2;
    EXPECT_EQ(iris::renderer::key_mismatch(a, b).value_or(""),
              "its scene_fingerprint is 0000000000000001, this render's is 0000000000000002");
    b = a;
    b.width = 25;
    EXPECT_EQ(iris::renderer::key_mismatch(a, b).value_or(""), "its width is 24, this render's is 25");
}

// The scene fingerprint: equal for the same scene loaded twice, different for another
// scene and for one vertex moved by one ulp.
TEST(CheckpointKey, TheSceneFingerprintSeesOneVertexMove) {
    auto s = iris::scene::builtin_scene("prism");
    const auto f = iris::scene::fingerprint(s);
    EXPECT_EQ(iris::scene::fingerprint(iris::scene::builtin_scene("prism")), f);
    EXPECT_NE(iris::scene::fingerprint(iris::scene::builtin_scene("cornell")), f);
    auto& p = s.shapes.back().mesh.positions.back();
    p.x = std::nextafter(p.x, 1e9f);
    EXPECT_NE(iris::scene::fingerprint(s), f);
}

}  // namespace
