#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

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

TEST_F(ExrTest, PngPreviewIsWritten) {
    iris::exr::write_png(dir / "p.png", ramp(8, 8));
    ASSERT_TRUE(fs::exists(dir / "p.png"));
    std::ifstream f(dir / "p.png", std::ios::binary);
    char sig[8] = {};
    f.read(sig, 8);
    EXPECT_EQ(std::string(sig + 1, 3), "PNG");
}

}  // namespace
