#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <iris/exr/exr.hpp>

namespace fs = std::filesystem;

namespace {

struct ExrTest : ::testing::Test {
    fs::path dir = fs::temp_directory_path() / ("iris-exr-test-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
    void SetUp() override { fs::create_directories(dir); }
    void TearDown() override { fs::remove_all(dir); }

    static iris::image ramp(int w, int h) {
        iris::image img(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                img(x, y) = {static_cast<float>(x) * 0.25f, static_cast<float>(y) * 0.5f, 1.0f / static_cast<float>(1 + x + y)};
        return img;
    }
};

TEST_F(ExrTest, FloatRoundTripIsExactAndKeepsMetadata) {
    const auto img = ramp(7, 5);
    iris::exr::write(dir / "a.exr", img, {{"iris:spp", "64"}, {"iris:preset", "paper"}});
    const auto back = iris::exr::read(dir / "a.exr");
    EXPECT_EQ(back.pixels, img);
    EXPECT_EQ(back.meta.at("iris:spp"), "64");
    EXPECT_EQ(back.meta.at("iris:preset"), "paper");
}

// Spectral channels (Fichet et al. 2021's layout) beside RGB: named S0.<λ>nm with a
// decimal comma, the layout's attributes, read back exactly and sorted by wavelength (also
// from a half RGB file); bad channel names are refused with the reason.
TEST_F(ExrTest, SpectralChannelsRoundTripInTheSpectralLayout) {
    EXPECT_EQ(iris::exr::spectral_channel_name(550.0), "S0.550nm");
    EXPECT_EQ(iris::exr::spectral_channel_name(392.5), "S0.392,5nm");
    EXPECT_EQ(iris::exr::spectral_channel_wavelength("S0.392,5nm"), 392.5);
    EXPECT_EQ(iris::exr::spectral_channel_wavelength("S0.392.5nm"), 392.5);
    EXPECT_EQ(iris::exr::spectral_channel_wavelength("R"), std::nullopt);
    EXPECT_THROW((void)iris::exr::spectral_channel_wavelength("S0.5um"), iris::exr::error);
    EXPECT_THROW((void)iris::exr::spectral_channel_wavelength("S0.abcnm"), iris::exr::error);
    EXPECT_THROW((void)iris::exr::spectral_channel_wavelength("S0.-5nm"), iris::exr::error);

    const auto img = ramp(5, 3);
    iris::exr::spectral_image sp;
    sp.wavelengths = {392.5, 417.5, 650.0};
    for (std::size_t i = 0; i < img.pixel_count(); ++i)
        for (std::size_t b = 0; b < 3; ++b) sp.values.push_back(static_cast<float>(i) + 0.125f * static_cast<float>(b));
    for (auto type : {iris::exr::pixel_type::float32, iris::exr::pixel_type::half}) {
        iris::exr::write(dir / "s.exr", img, {{"iris:spp", "4"}}, type, &sp);
        const auto back = iris::exr::read(dir / "s.exr");
        EXPECT_EQ(back.spectral.wavelengths, sp.wavelengths);
        EXPECT_EQ(back.spectral.values, sp.values) << "float32 whatever the RGB type";
        EXPECT_EQ(back.meta.at("spectralLayoutVersion"), "1.0");
        EXPECT_EQ(back.meta.at("emissiveUnits"), "W.m^-2.sr^-1");
        EXPECT_EQ(back.meta.at("iris:spp"), "4");
    }
    const auto plain = (iris::exr::write(dir / "p.exr", img), iris::exr::read(dir / "p.exr"));
    EXPECT_EQ(plain.spectral.count(), 0u);
    EXPECT_EQ(plain.meta.count("spectralLayoutVersion"), 0u);
    sp.values.pop_back();
    EXPECT_THROW(iris::exr::write(dir / "bad.exr", img, {}, iris::exr::pixel_type::float32, &sp), iris::exr::error);
    EXPECT_FALSE(fs::exists(dir / "bad.exr"));
}

TEST_F(ExrTest, HalfRoundTripIsCloseToHalfPrecision) {
    const auto img = ramp(4, 3);
    iris::exr::write(dir / "h.exr", img, {}, iris::exr::pixel_type::half);
    const auto back = iris::exr::read(dir / "h.exr");
    for (std::size_t i = 0; i < img.pixel_count(); ++i) {
        EXPECT_NEAR(back.pixels.pixels()[i].r, img.pixels()[i].r, 1e-3f * (1.0f + img.pixels()[i].r));
        EXPECT_NEAR(back.pixels.pixels()[i].b, img.pixels()[i].b, 1e-3f);
    }
}

TEST_F(ExrTest, WriteLeavesNoTemporaryBehind) {
    iris::exr::write(dir / "a.exr", ramp(2, 2));
    iris::exr::write(dir / "a.exr", ramp(3, 3));  // replaces
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
    EXPECT_EQ(files, 1u);
    EXPECT_EQ(iris::exr::read(dir / "a.exr").pixels.width(), 3);
}

TEST_F(ExrTest, UnwritableTargetThrowsAndLeavesNothing) {
    EXPECT_THROW(iris::exr::write(dir / "no-such-dir" / "a.exr", ramp(2, 2)), iris::exr::error);
    EXPECT_THROW(iris::exr::write(dir / "empty.exr", iris::image()), iris::exr::error);
    EXPECT_FALSE(fs::exists(dir / "empty.exr"));
}

TEST_F(ExrTest, ReadingGarbageOrMissingFilesIsAClearError) {
    EXPECT_THROW(iris::exr::read(dir / "missing.exr"), iris::exr::error);
    std::ofstream(dir / "junk.exr") << "not an exr";
    try {
        iris::exr::read(dir / "junk.exr");
        FAIL() << "expected an error";
    } catch (const iris::exr::error& e) {
        EXPECT_NE(std::string(e.what()).find("junk.exr"), std::string::npos) << e.what();
    }
}

namespace {
/// \brief The bytes of an EXR with its dataWindow attribute replaced by (x0, y0)–(x1, y1).
std::string with_data_window(const fs::path& exr, std::int32_t x0, std::int32_t y0, std::int32_t x1, std::int32_t y1) {
    std::ifstream in(exr, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string key("dataWindow\0box2i\0", 17);
    const auto at = bytes.find(key);
    EXPECT_NE(at, std::string::npos);
    const std::int32_t box[4] = {x0, y0, x1, y1};
    std::memcpy(bytes.data() + at + key.size() + 4, box, sizeof box);  // after the 4-byte size
    return bytes;
}
}  // namespace

// A corrupt header must not make iris allocate what it claims: data windows beyond the
// documented limits (2e9 × 2e9; one whose width overflows a 32-bit int; an inverted one;
// a side of 65 537) are refused with a message naming the file, before any pixel buffer
// exists; read_memory reads what read reads.
TEST_F(ExrTest, CorruptDataWindowsAreRefusedBeforeAllocating) {
    const auto img = ramp(5, 3);
    iris::exr::write(dir / "a.exr", img);
    std::ifstream in(dir / "a.exr", std::ios::binary);
    const std::string good((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(iris::exr::read_memory(good, "a.exr").pixels, img);
    const struct {
        std::int32_t x0, y0, x1, y1;
    } cases[] = {{0, 0, 2000000000, 2000000000}, {-2147483647, 0, 2147483647, 2}, {5, 5, 0, 0}, {0, 0, 65536, 0}};
    for (const auto& c : cases) {
        const std::string bytes = with_data_window(dir / "a.exr", c.x0, c.y0, c.x1, c.y1);
        try {
            iris::exr::read_memory(bytes, "corrupt.exr");
            ADD_FAILURE() << "accepted a data window to " << c.x1 << ", " << c.y1;
        } catch (const iris::exr::error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("corrupt.exr"), std::string::npos) << what;
            // OpenEXR refuses the first three itself ("Invalid data window"), iris the last
            EXPECT_NE(what.find("data window"), std::string::npos) << what;
        }
    }
    // the lowered limit of read_memory
    EXPECT_THROW(iris::exr::read_memory(good, "a.exr", 14), iris::exr::error);
    EXPECT_NO_THROW(iris::exr::read_memory(good, "a.exr", 15));
}

TEST_F(ExrTest, PngPreviewIsWritten) {
    iris::exr::write_png(dir / "p.png", ramp(8, 8));
    ASSERT_TRUE(fs::exists(dir / "p.png"));
    std::ifstream f(dir / "p.png", std::ios::binary);
    char sig[8] = {};
    f.read(sig, 8);
    EXPECT_EQ(std::string(sig + 1, 3), "PNG");
}

}  // namespace

namespace {
/// \brief Two images of one size that differ everywhere: a ramp and the ramp + 1 in green.
std::pair<iris::image, iris::image> two_images(int w, int h) {
    auto a = ExrTest::ramp(w, h), b = a;
    for (auto& p : b.pixels()) p.g += 1.0f;
    return {a, b};
}

/// \brief A child process that rewrites `path` with `a` and `b` in turn, `count` times (or
/// until killed); returns its pid.
pid_t start_writer(const fs::path& path, const iris::image& a, const iris::image& b, int count) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        for (int i = 0; i < count; ++i) {
            try {
                iris::exr::write(path, i % 2 ? b : a, {{"iris:spp", std::to_string(i)}});
            } catch (...) {
                ::_exit(3);
            }
        }
        ::_exit(0);
    }
    return pid;
}
}  // namespace

// Files are written atomically (write a temporary, then rename): a reader polling the file
// while it is rewritten always reads a whole image, one of the two being written, never a
// truncated or mixed one; and a writer killed by SIGKILL at any moment leaves the last
// complete image readable.
TEST_F(ExrTest, AReaderNeverSeesAHalfWrittenImage) {
    const auto [a, b] = two_images(256, 256);
    const fs::path path = dir / "polled.exr";
    iris::exr::write(path, a);
    const pid_t writer = start_writer(path, a, b, 200);
    ASSERT_GT(writer, 0);
    int reads = 0, status = 0;
    while (::waitpid(writer, &status, WNOHANG) == 0) {
        iris::image got;
        ASSERT_NO_THROW(got = iris::exr::read(path).pixels) << "read " << reads;
        ASSERT_TRUE(got == a || got == b) << "read " << reads << " is neither image";
        ++reads;
    }
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    EXPECT_GT(reads, 10);
}

TEST_F(ExrTest, AWriterKilledMidWriteLeavesTheLastImageReadable) {
    const auto [a, b] = two_images(512, 256);
    const fs::path path = dir / "killed.exr";
    iris::exr::write(path, a);
    for (int k = 0; k < 20; ++k) {
        const pid_t writer = start_writer(path, a, b, 1000000);
        ASSERT_GT(writer, 0);
        ::usleep(static_cast<useconds_t>(2000 + 1371 * k));  // somewhere in a write, a different place each time
        ::kill(writer, SIGKILL);
        int status = 0;
        ::waitpid(writer, &status, 0);
        ASSERT_TRUE(WIFSIGNALED(status));
        iris::image got;
        ASSERT_NO_THROW(got = iris::exr::read(path).pixels) << "kill " << k;
        ASSERT_TRUE(got == a || got == b) << "kill " << k;
    }
}
