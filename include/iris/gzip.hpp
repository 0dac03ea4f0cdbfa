#pragma once
/// \file
/// \brief Decompressing a gzip (or zlib) stream in memory, bounded: what reads `mesh.ply.gz`
/// (iris::geometry::gunzip) and a pbrt-v4 scene's `Include "part.pbrt.gz"`. Header-only;
/// the caller links zlib.

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include <zlib.h>

namespace iris {

/// \brief The bytes of `compressed`, or nothing with `why` set ("truncated", zlib's message,
/// or "decompresses to more than N MiB") — a bound on what a small corrupt or hostile file
/// can make the caller allocate.
inline std::optional<std::string> gunzip_bytes(std::string_view compressed, std::size_t max_bytes, std::string& why) {
    z_stream z{};
    // 15 + 32: a window of 2^15 and zlib's detection of the gzip (or zlib) header
    if (inflateInit2(&z, 15 + 32) != Z_OK) {
        why = "cannot initialise zlib";
        return std::nullopt;
    }
    std::string out;
    std::array<char, 1 << 16> chunk{};
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
    z.avail_in = static_cast<uInt>(std::min<std::size_t>(compressed.size(), std::numeric_limits<uInt>::max()));
    std::size_t fed = z.avail_in;
    int rc = Z_OK;
    while (rc != Z_STREAM_END) {
        z.next_out = reinterpret_cast<Bytef*>(chunk.data());
        z.avail_out = static_cast<uInt>(chunk.size());
        rc = inflate(&z, Z_NO_FLUSH);
        if (rc == Z_BUF_ERROR && z.avail_in == 0 && fed < compressed.size()) {  // inputs past 4 GiB: feed the rest
            const std::size_t more = std::min<std::size_t>(compressed.size() - fed, std::numeric_limits<uInt>::max());
            z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data() + fed));
            z.avail_in = static_cast<uInt>(more);
            fed += more;
            rc = Z_OK;
        }
        if (rc != Z_OK && rc != Z_STREAM_END) {
            why = "not a valid gzip file (" +
                  (rc == Z_BUF_ERROR ? std::string("truncated") : z.msg ? std::string(z.msg) : "error " + std::to_string(rc)) + ")";
            inflateEnd(&z);
            return std::nullopt;
        }
        out.append(chunk.data(), chunk.size() - z.avail_out);
        if (out.size() > max_bytes) {
            inflateEnd(&z);
            why = "decompresses to more than " +
                  (max_bytes >= (1u << 20) ? std::to_string(max_bytes >> 20) + " MiB" : std::to_string(max_bytes) + " bytes");
            return std::nullopt;
        }
    }
    inflateEnd(&z);
    return out;
}

}  // namespace iris
