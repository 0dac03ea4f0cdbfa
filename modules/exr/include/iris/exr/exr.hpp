#pragma once
/// \file
/// \brief iris::exr — OpenEXR images with string metadata, PNG previews, atomic writes.
///
/// Every writer here writes a temporary file beside the target and renames it over the
/// target, so a reader (tev, a script, an interrupted render) never sees a half-written
/// image. All OpenEXR/stb failures leave this module as `iris::exr::error`.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "iris/image.hpp"

namespace iris::exr {

/// \brief Any failure to read or write an image (message names the file).
class error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// \brief Header attributes stored as EXR string attributes (e.g. "iris:spp" → "64").
using metadata = std::map<std::string, std::string>;

enum class pixel_type { half, float32 };

/// \brief Spectral channels beside RGB, in the layout of Fichet, Pacanowski and Wilkie, "An
/// OpenEXR Layout for Spectral Images" (JCGT 10(3), 2021): an emissive, unpolarised spectrum
/// as one float channel per wavelength named `S0.<λ>nm` (decimal comma: `S0.392,5nm`), with
/// the string attributes `spectralLayoutVersion` = "1.0" and `emissiveUnits` = "W.m^-2.sr^-1".
struct spectral_image {
    std::vector<double> wavelengths;  ///< nm, increasing; empty: no spectral channels
    std::vector<float> values;        ///< pixel-major: pixel i's value at wavelength b is values[i · count + b]
    std::size_t count() const noexcept { return wavelengths.size(); }
};

/// \brief `S0.<λ>nm` for λ in nm: the shortest decimal that reads back as λ, with a comma.
std::string spectral_channel_name(double nm);
/// \brief λ in nm of a channel named `S0.<λ>nm` (comma or point); nullopt for another name.
/// \throws error for an `S0.` channel in other units (the layout allows m, Hz, … — iris reads nm).
std::optional<double> spectral_channel_wavelength(std::string_view name);

/// \brief Write linear RGB as an EXR (channels R, G, B), atomically; with `spectral`, its
/// channels too (float32, whatever `type` is), in the spectral layout above.
void write(const std::filesystem::path& path, const image& img, const metadata& meta = {},
           pixel_type type = pixel_type::float32, const spectral_image* spectral = nullptr);

/// \brief An EXR's RGB channels (as float), its string attributes and its spectral channels
/// (`S0.<λ>nm`, sorted by λ; empty if it has none).
struct loaded {
    iris::image pixels;
    metadata meta;
    spectral_image spectral;
};

/// \brief The largest images `read` accepts: a side of at most 65 536 pixels and at most
/// 2^27 pixels (1.5 GiB of float RGB, e.g. 16 384 × 8 192). A corrupt header cannot make
/// iris allocate more than that.
inline constexpr std::int64_t max_side = 65536;
inline constexpr std::int64_t max_pixels = std::int64_t{1} << 27;

/// \brief Read an EXR with R, G and B channels. Missing channels are an error, not zeros;
/// so is a data window outside the limits above. \throws error naming the file
loaded read(const std::filesystem::path& path);

/// \brief `read` for an EXR already in memory; `name` is used in error messages. A data
/// window of more than `pixel_limit` pixels (≤ max_pixels) is refused like one beyond the
/// limits (the fuzz target lowers it, so that it does not spend its time allocating).
loaded read_memory(std::string_view bytes, const std::string& name, std::int64_t pixel_limit = max_pixels);

/// \brief An 8- or 16-bit image as stored: values in [0, 1] (not decoded from sRGB), grey
/// and grey-alpha images expanded to RGB, alpha dropped.
struct ldr_image {
    iris::image pixels;
    int bits = 8;      ///< per channel in the file: 8 or 16
    int channels = 3;  ///< in the file: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
};

/// \brief Read a PNG, JPEG, BMP or TGA image (stb_image), within `max_side`/`max_pixels`.
/// \throws error naming the file and what went wrong
ldr_image read_ldr(const std::filesystem::path& path);

/// \brief Write an 8-bit sRGB-encoded PNG preview of linear RGB, scaled by 2^exposure, atomically.
void write_png(const std::filesystem::path& path, const image& img, double exposure = 0.0);

/// \brief Call `write_to(tmp)` for a temporary path beside `target`, then rename it onto
/// `target`. The temporary is removed if `write_to` throws. \throws error
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path&)>& write_to);

}  // namespace iris::exr
