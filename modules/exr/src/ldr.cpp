// 8- and 16-bit images (PNG, JPEG, BMP, TGA) through Debian's compiled stb_image, as
// stored values in [0, 1]: the caller decides whether they are sRGB-encoded.
#include <cstdint>
#include <memory>
#include <string>

#include <stb/stb_image.h>

#include "iris/exr/exr.hpp"

namespace iris::exr {

ldr_image read_ldr(const std::filesystem::path& path) {
    const std::string name = path.string();
    int w = 0, h = 0, channels = 0;
    if (stbi_info(name.c_str(), &w, &h, &channels) == 0)
        throw error("cannot read image '" + name + "': " + (stbi_failure_reason() ? stbi_failure_reason() : "unknown format"));
    if (w < 1 || h < 1 || w > max_side || h > max_side || static_cast<std::int64_t>(w) * h > max_pixels)
        throw error("cannot read image '" + name + "': " + std::to_string(w) + "x" + std::to_string(h) +
                    " is outside the supported size");
    ldr_image out;
    out.channels = channels;
    const bool wide = stbi_is_16_bit(name.c_str()) != 0;
    out.bits = wide ? 16 : 8;
    std::unique_ptr<void, void (*)(void*)> data(nullptr, stbi_image_free);
    if (wide) data.reset(stbi_load_16(name.c_str(), &w, &h, &channels, 3));
    else data.reset(stbi_load(name.c_str(), &w, &h, &channels, 3));
    if (!data)
        throw error("cannot read image '" + name + "': " + (stbi_failure_reason() ? stbi_failure_reason() : "decoding failed"));
    out.pixels = image(w, h);
    const auto n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    const double scale = wide ? 1.0 / 65535.0 : 1.0 / 255.0;
    auto& px = out.pixels.pixels();
    for (std::size_t i = 0; i < n; ++i) {
        float c[3];
        for (std::size_t k = 0; k < 3; ++k) {
            const double v = wide ? static_cast<const std::uint16_t*>(data.get())[3 * i + k]
                                  : static_cast<const std::uint8_t*>(data.get())[3 * i + k];
            c[k] = static_cast<float>(v * scale);
        }
        px[i] = {c[0], c[1], c[2]};
    }
    return out;
}

}  // namespace iris::exr
