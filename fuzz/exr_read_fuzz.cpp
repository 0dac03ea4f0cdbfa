// Fuzz target: iris::exr::read_memory on arbitrary bytes — the path `iris-image`,
// `iris-ablate`'s reference cache and `--reference` take through OpenEXR. Properties: the
// bytes either give an image inside the documented limits (max_side, max_pixels) whose
// pixel count is width × height, or throw iris::exr::error naming the file — never another
// exception, never a crash, never an allocation sized by a corrupt header beyond the limits
// (lowered here to 2^20 pixels).
#include <cstdint>
#include <string_view>

#include <iris/exr/exr.hpp>

#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        // at most 2^20 pixels (12 MiB): the parsing paths, not gigabyte allocations, are the
        // point; the limit check itself is the same code at any limit
        const auto img = iris::exr::read_memory(bytes, "fuzz.exr", std::int64_t{1} << 20);
        const auto& p = img.pixels;
        if (p.width() < 1 || p.height() < 1 || p.width() > iris::exr::max_side || p.height() > iris::exr::max_side)
            iris::fuzz::fail("an image outside the size limits was accepted");
        if (p.pixel_count() != static_cast<std::size_t>(p.width()) * static_cast<std::size_t>(p.height()))
            iris::fuzz::fail("pixel count is not width x height");
    } catch (const iris::exr::error& e) {
        if (std::string_view(e.what()).find("fuzz.exr") == std::string_view::npos)
            iris::fuzz::fail("an error that does not name the file");
    }
    return 0;
}
