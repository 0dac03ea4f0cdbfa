#include "iris/exr/exr.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <array>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <vector>

#include <Imath/half.h>
#include <fmt/core.h>
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

std::string spectral_channel_name(double nm) {
    std::string v = fmt::format("{}", nm);  // shortest round trip
    if (const auto dot = v.find('.'); dot != std::string::npos) v[dot] = ',';
    return "S0." + v + "nm";
}

std::optional<double> spectral_channel_wavelength(std::string_view name) {
    if (!name.starts_with("S0.")) return std::nullopt;
    std::string_view rest = name.substr(3);
    if (!rest.ends_with("nm"))
        throw error(fmt::format("spectral channel '{}' is not in nanometres (iris reads S0.<wavelength>nm)", name));
    std::string number(rest.substr(0, rest.size() - 2));
    std::replace(number.begin(), number.end(), ',', '.');
    double v = 0.0;
    const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), v);
    if (ec != std::errc() || end != number.data() + number.size() || !(v > 0.0) || !std::isfinite(v))
        throw error(fmt::format("spectral channel '{}' does not name a wavelength (expected e.g. S0.550nm or S0.392,5nm)", name));
    return v;
}

void write(const std::filesystem::path& path, const image& img, const metadata& meta, pixel_type type,
           const spectral_image* spectral) {
    if (img.empty()) throw error("cannot write '" + path.string() + "': the image is empty");
    if (spectral && spectral->values.size() != img.pixel_count() * spectral->count())
        throw error("cannot write '" + path.string() + "': the spectral channels do not have one value per pixel and wavelength");
    write_atomically(path, [&](const std::filesystem::path& tmp) {
        try {
            Imf::Header header(img.width(), img.height());
            const Imf::PixelType pt = type == pixel_type::half ? Imf::HALF : Imf::FLOAT;
            for (const char* c : channel_names) header.channels().insert(c, Imf::Channel(pt));
            std::vector<std::string> spectral_names;
            if (spectral && spectral->count() > 0) {
                for (double nm : spectral->wavelengths) {
                    spectral_names.push_back(spectral_channel_name(nm));
                    header.channels().insert(spectral_names.back(), Imf::Channel(Imf::FLOAT));
                }
                header.insert("spectralLayoutVersion", Imf::StringAttribute("1.0"));
                header.insert("emissiveUnits", Imf::StringAttribute("W.m^-2.sr^-1"));
            }
            header.compression() = Imf::ZIP_COMPRESSION;
            for (const auto& [key, value] : meta) header.insert(key, Imf::StringAttribute(value));
            Imf::OutputFile file(tmp.c_str(), header);
            std::vector<float> spectral_copy;  // Slice wants a mutable base pointer
            const auto add_spectral = [&](Imf::FrameBuffer& fb) {
                if (spectral_names.empty()) return;
                spectral_copy = spectral->values;
                const std::size_t xs = spectral->count() * sizeof(float);
                const std::size_t ys = xs * static_cast<std::size_t>(img.width());
                for (std::size_t b = 0; b < spectral_names.size(); ++b)
                    fb.insert(spectral_names[b],
                              Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(spectral_copy.data() + b), xs, ys));
            };
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
                add_spectral(fb);
                file.setFrameBuffer(fb);
            } else {
                Imf::FrameBuffer fb = frame_buffer(copy);
                add_spectral(fb);
                file.setFrameBuffer(fb);
            }
            file.writePixels(img.height());
        } catch (const std::exception& e) {
            throw error("cannot write EXR '" + path.string() + "': " + e.what());
        }
    });
}

namespace {

// An EXR held in memory, for `read_memory` (the fuzz target's way in).
class memory_stream final : public Imf::IStream {
public:
    memory_stream(std::string_view bytes, const std::string& name) : Imf::IStream(name.c_str()), m_bytes(bytes) {}
    bool read(char c[], int n) override {
        if (n < 0 || static_cast<std::uint64_t>(n) > m_bytes.size() - m_pos)
            throw std::runtime_error("early end of file");
        std::memcpy(c, m_bytes.data() + m_pos, static_cast<std::size_t>(n));
        m_pos += static_cast<std::uint64_t>(n);
        return m_pos < m_bytes.size();
    }
    std::uint64_t tellg() override { return m_pos; }
    void seekg(std::uint64_t pos) override { m_pos = std::min<std::uint64_t>(pos, m_bytes.size()); }

private:
    std::string_view m_bytes;
    std::uint64_t m_pos = 0;
};

loaded read_file(Imf::InputFile& file, const std::string& name, std::int64_t pixel_limit = max_pixels) {
    const Imath::Box2i dw = file.header().dataWindow();
    // in 64 bits: a corrupt window can overflow int
    const std::int64_t w = std::int64_t{dw.max.x} - dw.min.x + 1;
    const std::int64_t h = std::int64_t{dw.max.y} - dw.min.y + 1;
    if (w < 1 || h < 1 || w > max_side || h > max_side || w * h > std::min(pixel_limit, max_pixels))
        throw error("EXR '" + name + "' has a data window of " + std::to_string(w) + "x" + std::to_string(h) +
                    " pixels; iris reads images of 1 to " + std::to_string(max_side) + " pixels a side and at most " +
                    std::to_string(std::min(pixel_limit, max_pixels)) + " pixels");
    for (const char* c : channel_names)
        if (file.header().channels().findChannel(c) == nullptr)
            throw error("EXR '" + name + "' has no channel '" + c + "' (iris reads R, G, B)");
    loaded out{image(static_cast<int>(w), static_cast<int>(h)), {}, {}};
    Imf::FrameBuffer fb;
    auto* base = reinterpret_cast<char*>(out.pixels.pixels().data());
    const std::ptrdiff_t xs = sizeof(rgb_pixel);
    const std::ptrdiff_t ys = xs * static_cast<std::ptrdiff_t>(w);
    // OpenEXR addresses slices by absolute data-window coordinates: shift the base
    // (as an integer: the shifted pointer lies outside the buffer until OpenEXR adds back)
    const std::ptrdiff_t origin = -static_cast<std::ptrdiff_t>(dw.min.x) * xs - static_cast<std::ptrdiff_t>(dw.min.y) * ys;
    for (std::size_t c = 0; c < channel_names.size(); ++c)
        fb.insert(channel_names[c],
                  Imf::Slice(Imf::FLOAT,
                             reinterpret_cast<char*>(reinterpret_cast<std::uintptr_t>(base) +
                                                     static_cast<std::uintptr_t>(origin + static_cast<std::ptrdiff_t>(c * sizeof(float)))),
                             static_cast<std::size_t>(xs), static_cast<std::size_t>(ys)));
    // the spectral channels (S0.<λ>nm), sorted by wavelength
    std::vector<std::pair<double, std::string>> spectral;
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it)
        if (const auto nm = spectral_channel_wavelength(it.name())) spectral.emplace_back(*nm, it.name());
    std::sort(spectral.begin(), spectral.end());
    for (std::size_t b = 1; b < spectral.size(); ++b)
        if (spectral[b].first == spectral[b - 1].first)
            throw error(fmt::format("EXR '{}' has two spectral channels at {} nm ('{}', '{}')", name, spectral[b].first,
                                    spectral[b - 1].second, spectral[b].second));
    // at most 8 float channels' worth of spectral values per pixel of the limit (4 GiB at
    // max_pixels): a header with many channels cannot make iris allocate more
    const std::int64_t value_limit = std::min(pixel_limit, max_pixels) * 8;
    if (!spectral.empty() && static_cast<std::int64_t>(spectral.size()) > value_limit / (w * h))
        throw error(fmt::format("EXR '{}' has {} spectral channels of {}x{} pixels: more than iris reads ({} values)", name,
                                spectral.size(), w, h, value_limit));
    if (!spectral.empty()) {
        out.spectral.values.resize(static_cast<std::size_t>(w * h) * spectral.size());
        const std::ptrdiff_t sxs = static_cast<std::ptrdiff_t>(spectral.size() * sizeof(float));
        const std::ptrdiff_t sys = sxs * static_cast<std::ptrdiff_t>(w);
        const std::ptrdiff_t sorigin = -static_cast<std::ptrdiff_t>(dw.min.x) * sxs - static_cast<std::ptrdiff_t>(dw.min.y) * sys;
        auto* sbase = reinterpret_cast<char*>(out.spectral.values.data());
        for (std::size_t b = 0; b < spectral.size(); ++b) {
            out.spectral.wavelengths.push_back(spectral[b].first);
            fb.insert(spectral[b].second,
                      Imf::Slice(Imf::FLOAT,
                                 reinterpret_cast<char*>(reinterpret_cast<std::uintptr_t>(sbase) +
                                                         static_cast<std::uintptr_t>(sorigin + static_cast<std::ptrdiff_t>(b * sizeof(float)))),
                                 static_cast<std::size_t>(sxs), static_cast<std::size_t>(sys)));
        }
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    for (auto it = file.header().begin(); it != file.header().end(); ++it)
        if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) out.meta[it.name()] = s->value();
    return out;
}

}  // namespace

loaded read(const std::filesystem::path& path) {
    try {
        Imf::InputFile file(path.c_str());
        return read_file(file, path.string());
    } catch (const error&) {
        throw;
    } catch (const std::exception& e) {
        throw error("cannot read EXR '" + path.string() + "': " + e.what());
    }
}

loaded read_memory(std::string_view bytes, const std::string& name, std::int64_t pixel_limit) {
    try {
        memory_stream stream(bytes, name);
        Imf::InputFile file(stream);
        return read_file(file, name, pixel_limit);
    } catch (const error&) {
        throw;
    } catch (const std::exception& e) {
        throw error("cannot read EXR '" + name + "': " + e.what());
    }
}

}  // namespace iris::exr
