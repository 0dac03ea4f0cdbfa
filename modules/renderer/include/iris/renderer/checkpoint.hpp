#pragma once
/// \file
/// \brief Checkpoints: a render's exact film and how far it got, with the key of the
/// render it belongs to, so that `render` can go on from it (options::start_spp) to the
/// same film an uninterrupted render gives.
///
/// **File format** (version 3; host byte order, little-endian on every machine iris builds
/// for, and checked by the magic):
///
/// | bytes | what |
/// |---|---|
/// | 8 | magic `IRISCKPT` |
/// | 4 | format version (uint32, 2) |
/// | 4 | header length L (uint32) |
/// | L | header: `key=value` lines (the key's fields, then spp_done, samples, rays, seconds, fade_split, and with spectral_bins > 0 spectral_range=λmin,λmax and spectral_dropped) |
/// | 48·P | per pixel (P = width·height, row-major): X, Y, Z sums as 128-bit fixed point (film.hpp) |
/// | 4·P | per pixel: samples (uint32) |
/// | 4·P | per pixel: dropped samples (uint32) |
/// | | only if fade_split > 0 (a fading preset's film: its fade layer, film.hpp): |
/// | 48·P | per pixel: the early samples' X, Y, Z sums |
/// | 4·P | per pixel: early samples (uint32) |
/// | 144·P | per pixel, early then late side, X, Y, Z: sums of squares (fade.hpp), 16 bytes low part then 8 bytes high |
/// | | only if spectral_bins = B > 0 (the film's spectral layer, film.hpp): |
/// | 16·B·P | per pixel, per band: the exact sums |
/// | 8 | FNV-1a (64 bit) of every byte before it |
///
/// Version 1 (written before the fade layer) is the same without fade_split, version 2
/// without spectral_bins; both are still read. A reader checks everything it can: the magic and version, every header field, the
/// exact length, the checksum, that every pixel holds spp_done samples and, with a fade
/// layer, min(spp_done, fade_split) early ones. It is written
/// atomically (a temporary file, then rename), so a crash at any moment leaves either the
/// previous checkpoint or the new one.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "iris/render/film.hpp"

namespace iris::renderer {

/// \brief What a checkpoint belongs to: a render with another key gives another image.
struct checkpoint_key {
    std::string version;                 ///< iris version that wrote it
    std::string scene;                   ///< the scene's name
    std::uint64_t scene_fingerprint = 0; ///< iris::scene::fingerprint: the scene's content
    std::string preset, estimator, sampler;
    std::uint64_t seed = 0;
    int nthold = 0, max_depth = 0;
    int spp = 0;                         ///< the render's target (zsobol's points depend on it)
    int width = 0, height = 0;
    int spectral_bins = 0;               ///< the film's spectral bands (0: none)
    friend bool operator==(const checkpoint_key&, const checkpoint_key&) = default;
};

/// \brief A checkpoint's contents.
struct checkpoint {
    checkpoint_key key;
    int spp_done = 0;          ///< passes in the film (every pixel has this many samples)
    std::uint64_t samples = 0; ///< totals over every run that contributed (for statistics)
    std::uint64_t rays = 0;
    double seconds = 0.0;
    film image{0, 0};
};

/// \brief A checkpoint that cannot be read or used; the message names the file and why.
class checkpoint_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// \brief Write `c` to `path` atomically. \throws checkpoint_error if it cannot be written
/// (the previous file, if any, is then untouched).
void write_checkpoint(const std::filesystem::path& path, const checkpoint& c);

/// \brief Read and check the checkpoint at `path`. \throws checkpoint_error (missing,
/// unreadable, not a checkpoint, another format version, truncated or too long, a bad
/// header field, checksum mismatch, a film inconsistent with spp_done).
checkpoint read_checkpoint(const std::filesystem::path& path);

/// \brief The same checks on a checkpoint's bytes; `name` names it in messages (the fuzz
/// target's entry point: fuzz/checkpoint_read_fuzz.cpp).
checkpoint parse_checkpoint(std::string_view bytes, const std::string& name);

/// \brief The first field in which `stored` differs from `wanted`, as "its seed is 1, this
/// render's is 2"; nullopt if they are equal.
std::optional<std::string> key_mismatch(const checkpoint_key& stored, const checkpoint_key& wanted);

}  // namespace iris::renderer
