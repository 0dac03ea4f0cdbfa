#pragma once
// Render options shared by the tests of absorbing glass and thin films (phenomena_test):
// an 8×8 image, 2 threads, N_thold far beyond the passes.

#include <cstdint>
#include <string>

#include <iris/renderer/renderer.hpp>

namespace iris_test {

/// \brief `estimator` with `preset` at `spp`, seed `seed`, on an 8×8 image; α < 1
/// throughout, so `paper`'s B term is on for every sample.
inline iris::renderer::options phenomena_options(const std::string& estimator, const std::string& preset, int spp,
                                                 std::uint64_t seed) {
    iris::renderer::options o;
    o.estimator = estimator;
    o.preset = preset;
    o.width = 8;
    o.height = 8;
    o.spp = spp;
    o.nthold = 1 << 20;
    o.seed = seed;
    o.threads = 2;
    return o;
}

}  // namespace iris_test
