// Fixture of the iris-image CLI tests: writes the input EXRs into an empty directory.
//
//   make_test_images DIR
//
// a.exr          32×24, values on a 1/64 grid (so a + 0.25 is exact), metadata iris:spp=64
// a_copy.exr     the pixels of a.exr, no metadata
// b.exr          a + 0.25 in every channel: mse = 0.0625 and max_abs = 0.25 exactly
// a_crop.exr     a.exr's pixels x 4..19, y 2..13 (what `crop --rect 4,2,16,12` must give)
// small.exr      16×12 (size mismatch)
// tiny_a.exr, tiny_b.exr   8×8 (below the 11×11 SSIM window)
// nan.exr        a.exr with a NaN at pixel (3, 4)
// rg_only.exr    32×24 with channels R and G only
// not_an_exr.exr a text file
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>

#include <iris/exr/exr.hpp>

namespace fs = std::filesystem;

namespace {

iris::image pattern(int w, int h) {
    iris::image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            img(x, y) = {static_cast<float>(x) / 64.0f, static_cast<float>(y) / 64.0f,
                         static_cast<float>((x * y) % 17) / 32.0f};
    return img;
}

void write_rg_only(const fs::path& path, int w, int h) {
    std::vector<float> r(static_cast<std::size_t>(w * h), 0.5f), g(static_cast<std::size_t>(w * h), 0.25f);
    Imf::Header header(w, h);
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    header.channels().insert("G", Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer fb;
    const std::size_t xs = sizeof(float), ys = xs * static_cast<std::size_t>(w);
    fb.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(r.data()), xs, ys));
    fb.insert("G", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(g.data()), xs, ys));
    file.setFrameBuffer(fb);
    file.writePixels(h);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_test_images DIR\n");
        return 2;
    }
    const fs::path dir = argv[1];
    fs::remove_all(dir);  // outputs of earlier runs must not satisfy "file was written" checks
    fs::create_directories(dir);

    const iris::image a = pattern(32, 24);
    iris::exr::write(dir / "a.exr", a, {{"iris:spp", "64"}, {"iris:note", "iris-image test input"}});
    iris::exr::write(dir / "a_copy.exr", a);

    iris::image b = a;
    for (auto& p : b.pixels()) p = {p.r + 0.25f, p.g + 0.25f, p.b + 0.25f};
    iris::exr::write(dir / "b.exr", b);

    iris::image crop(16, 12);
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 16; ++x) crop(x, y) = a(4 + x, 2 + y);
    iris::exr::write(dir / "a_crop.exr", crop);

    iris::exr::write(dir / "small.exr", pattern(16, 12));
    iris::exr::write(dir / "tiny_a.exr", pattern(8, 8));
    iris::image tiny_b = pattern(8, 8);
    tiny_b(1, 1).r += 0.5f;
    iris::exr::write(dir / "tiny_b.exr", tiny_b);

    iris::image nan = a;
    nan(3, 4).g = std::numeric_limits<float>::quiet_NaN();
    iris::exr::write(dir / "nan.exr", nan);

    write_rg_only(dir / "rg_only.exr", 32, 24);
    std::ofstream(dir / "not_an_exr.exr") << "this is not an OpenEXR file\n";
    return 0;
}
