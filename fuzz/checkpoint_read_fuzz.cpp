// Fuzz target: iris::renderer::parse_checkpoint on arbitrary bytes — what `iris-render
// --resume` reads. Properties: the bytes either give a checkpoint whose film has the key's
// size and spp_done samples in every pixel (and no more dropped than taken; with a fade
// layer, min(spp_done, split) early ones, and an image its blend can make), or throw
// checkpoint_error naming the file — never another exception, never a crash, never an
// allocation sized by a header the file's length does not back.
#include <algorithm>
#include <cstdint>
#include <string_view>

#include <iris/renderer/checkpoint.hpp>

#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        const auto c = iris::renderer::parse_checkpoint(bytes, "fuzz.ckpt");
        if (c.image.width() != c.key.width || c.image.height() != c.key.height)
            iris::fuzz::fail("a film of another size than the key's");
        for (std::size_t i = 0; i < c.image.counts().size(); ++i)
            if (c.image.samples(i) != static_cast<std::uint32_t>(c.spp_done) || c.image.dropped_counts()[i] > c.image.samples(i))
                iris::fuzz::fail("a film inconsistent with spp_done");
        if (c.spp_done < 0 || c.spp_done > c.key.spp) iris::fuzz::fail("spp_done outside 0..spp");
        if (const auto* fade = c.image.fade_state()) {
            if (fade->split == 0 || fade->early_count.size() != c.image.counts().size())
                iris::fuzz::fail("a fade layer without a split or of another size");
            for (std::size_t i = 0; i < fade->early_count.size(); ++i)
                if (fade->early_count[i] != std::min(c.image.samples(i), fade->split))
                    iris::fuzz::fail("a fade layer inconsistent with spp_done");
            (void)c.image.to_image();  // the blend of any layer that passed the checks
        }
    } catch (const iris::renderer::checkpoint_error& e) {
        if (std::string_view(e.what()).find("fuzz.ckpt") == std::string_view::npos)
            iris::fuzz::fail("an error that does not name the file");
    }
    return 0;
}
