#pragma once
/// \file
/// \brief The renderer's random stream: `counter_rng` (sampling/random.hpp) keyed by
/// (seed, pixel, sample index), plus the 2-D draws the path tracer asks for. A pure
/// function of its key and dimension, so no pixel depends on tiling or thread count.

#include <glm/vec2.hpp>

#include "iris/sampling/random.hpp"

namespace iris {

class sample_stream : public counter_rng {
public:
    using counter_rng::counter_rng;

    /// \brief Two consecutive dimensions as a point in [0, 1)².
    constexpr glm::vec2 next2() noexcept {
        const float a = next();
        return {a, next()};
    }
};

}  // namespace iris
