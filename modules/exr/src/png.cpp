#include <cmath>
#include <cstdint>
#include <vector>

#include <stb/stb_image_write.h>

#include "iris/exr/exr.hpp"
#include "iris/spectrum/color.hpp"

namespace iris::exr {

void write_png(const std::filesystem::path& path, const image& img, double exposure) {
    if (img.empty()) throw error("cannot write '" + path.string() + "': the image is empty");
    const double scale = std::exp2(exposure);
    std::vector<std::uint8_t> bytes;
    bytes.reserve(img.pixel_count() * 3);
    auto encode = [&](float v) {
        const double e = srgb_encode(static_cast<double>(v) * scale);  // clamps, maps NaN to 0
        return static_cast<std::uint8_t>(std::lround(e * 255.0));
    };
    for (const rgb_pixel& p : img.pixels()) {
        bytes.push_back(encode(p.r));
        bytes.push_back(encode(p.g));
        bytes.push_back(encode(p.b));
    }
    write_atomically(path, [&](const std::filesystem::path& tmp) {
        if (stbi_write_png(tmp.c_str(), img.width(), img.height(), 3, bytes.data(), img.width() * 3) == 0)
            throw error("cannot write PNG '" + path.string() + "'");
    });
}

}  // namespace iris::exr
