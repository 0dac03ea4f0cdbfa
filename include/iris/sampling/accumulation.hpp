#pragma once
/// \file
/// \brief Accumulation: how a pixel's samples become its value. A compile-time policy of
/// `integrator_config` (its seventh parameter):
///
/// | policy | name | a pixel's value |
/// |---|---|---|
/// | `accumulation::running_mean` | (none) | the mean of every sample (the paper's; the control) |
/// | `accumulation::fade` | `fade` | the blend of the samples taken while α < 1 and those taken at α = 1 whose estimated mean squared error is smallest (iris/render/fade.hpp) |
///
/// The policy decides what the film keeps: `fade` makes the renderer switch on the film's
/// fade layer (film::enable_fade), which splits each pixel's sums at sample N_thold and
/// keeps their second moments; the running mean is still there, and is what checkpoints
/// and MPI ranks exchange.

#include <concepts>
#include <string_view>

namespace iris::accumulation {

/// \brief Every sample weighs the same: the bias of the samples taken while α < 1 decays as
/// N_thold / N.
struct running_mean {
    static constexpr std::string_view name = "mean";
    static constexpr bool fades = false;
};

/// \brief The MSE-optimal blend of the biased (α < 1) and unbiased (α = 1) means, per pixel.
struct fade {
    static constexpr std::string_view name = "fade";
    static constexpr bool fades = true;
};

/// \brief What an accumulation policy provides: a name and whether the film fades.
template <class A>
concept Accumulation = requires {
    { A::name } -> std::convertible_to<std::string_view>;
    { A::fades } -> std::convertible_to<bool>;
};

}  // namespace iris::accumulation
