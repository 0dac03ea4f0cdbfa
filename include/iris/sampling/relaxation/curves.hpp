#pragma once
/// \file
/// \brief The relaxation curves: `linear` (α = t, the paper's), `quadratic` (α = t², the
/// paper's suggestion: stays restricted longer, relaxes faster at the end) and `none`
/// (α ≡ 1: no restriction at any iteration, the HWSS baseline).

#include <string_view>

#include "iris/sampling/relaxation/concept.hpp"

namespace iris::relaxation {

/// \brief α = t.
struct linear {
    static constexpr std::string_view name = "linear";
    constexpr float operator()(float t) const noexcept { return t; }
};

/// \brief α = t².
struct quadratic {
    static constexpr std::string_view name = "quadratic";
    constexpr float operator()(float t) const noexcept { return t * t; }
};

/// \brief α ≡ 1: the restriction is never applied (plain HWSS from the first sample).
struct none {
    static constexpr std::string_view name = "none";
    constexpr float operator()(float /*t*/) const noexcept { return 1.0f; }
};

static_assert(RelaxationCurve<linear> && RelaxationCurve<quadratic> && RelaxationCurve<none>);

}  // namespace iris::relaxation
