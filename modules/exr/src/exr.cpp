#include "iris/exr/exr.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>

#include <array>
#include <vector>

#include <Imath/half.h>
#include <cstddef>

namespace iris::exr {
namespace {

constexpr std::array<const char*, 3> channel_names{"R", "G", "B"};

Imf::FrameBuffer frame_buffer(image& img) {
    Imf::FrameBuffer fb;
    auto* base = reinterpret_cast<char*>(img.pixels().data());
    const std::size_t xs = sizeof(rgb_pixel);
    const std::size_t ys = xs * static_cast<std::size_t>(img.width());
    for (std::size_t c = 0; c < channel_names.size(); ++c)
        fb.insert(channel_names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
    return fb;
}

}  // namespace

void write(const std::filesystem::path& path, const image& img, const metadata& meta, pixel_type type) {
    if (img.empty()) throw error("cannot write '" + path.string() + "': the image is empty");
    write_atomically(path, [&](const std::filesystem::path& tmp) {
        try {
            Imf::Header header(img.width(), img.height());
            const Imf::PixelType pt = type == pixel_type::half ? Imf::HALF : Imf::FLOAT;
            for (const char* c : channel_names) header.channels().insert(c, Imf::Channel(pt));
            header.compression() = Imf::ZIP_COMPRESSION;
            for (const auto& [key, value] : meta) header.insert(key, Imf::StringAttribute(value));
            Imf::OutputFile file(tmp.c_str(), header);
            // OpenEXR converts pixel types when reading but not when writing: a half file
            // needs a half frame buffer.
            image copy = img;  // Slice wants a mutable base pointer
            std::vector<half> halves;
            if (type == pixel_type::half) {
                halves.reserve(img.pixel_count() * 3);
                for (const rgb_pixel& p : img.pixels()) {
                    halves.emplace_back(p.r);
                    halves.emplace_back(p.g);
                    halves.emplace_back(p.b);
                }
                Imf::FrameBuffer fb;
                auto* base = reinterpret_cast<char*>(halves.data());
                const std::size_t xs = 3 * sizeof(half);
                const std::size_t ys = xs * static_cast<std::size_t>(img.width());
                for (std::size_t c = 0; c < channel_names.size(); ++c)
                    fb.insert(channel_names[c], Imf::Slice(Imf::HALF, base + c * sizeof(half), xs, ys));
                file.setFrameBuffer(fb);
            } else {
                file.setFrameBuffer(frame_buffer(copy));
            }
            file.writePixels(img.height());
        } catch (const std::exception& e) {
            throw error("cannot write EXR '" + path.string() + "': " + e.what());
        }
    });
}

loaded read(const std::filesystem::path& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const int w = dw.max.x - dw.min.x + 1;
        const int h = dw.max.y - dw.min.y + 1;
        for (const char* c : channel_names)
            if (file.header().channels().findChannel(c) == nullptr)
                throw error("EXR '" + path.string() + "' has no channel '" + c + "' (iris reads R, G, B)");
        loaded out{image(w, h), {}};
        Imf::FrameBuffer fb;
        auto* base = reinterpret_cast<char*>(out.pixels.pixels().data());
        const std::size_t xs = sizeof(rgb_pixel);
        const std::size_t ys = xs * static_cast<std::size_t>(w);
        // OpenEXR addresses slices by absolute data-window coordinates: shift the base.
        const std::ptrdiff_t origin = -static_cast<std::ptrdiff_t>(dw.min.x) * static_cast<std::ptrdiff_t>(xs) -
                                      static_cast<std::ptrdiff_t>(dw.min.y) * static_cast<std::ptrdiff_t>(ys);
        for (std::size_t c = 0; c < channel_names.size(); ++c)
            fb.insert(channel_names[c], Imf::Slice(Imf::FLOAT, base + origin + static_cast<std::ptrdiff_t>(c * sizeof(float)), xs, ys));
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        for (auto it = file.header().begin(); it != file.header().end(); ++it)
            if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
                out.meta[it.name()] = s->value();
        return out;
    } catch (const error&) {
        throw;
    } catch (const std::exception& e) {
        throw error("cannot read EXR '" + path.string() + "': " + e.what());
    }
}

}  // namespace iris::exr
