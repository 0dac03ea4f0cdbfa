#pragma once
/// \file
/// \brief Absorbing dielectrics (Beer–Lambert; docs/method.md §8): which solid a ray travels
/// inside, and what it keeps of a length t there, exp(−σ_a(λ)·t).
///
/// The medium of a ray is decided where it leaves a surface, as pbrt-v4's medium interfaces
/// decide it: a dielectric's boundary puts the ray inside its solid when the ray leaves
/// toward the back of its geometric normal (the solid's inside; normals point out of a
/// closed mesh), outside otherwise — outside is always clear, so solids of glass do not
/// nest; any other surface leaves the ray where it was (a diffuse object inside a glass
/// block reflects within the glass). Paths start outside: the camera and the lights are
/// taken to be in the clear. A ray that meets nothing while inside a solid (an open mesh)
/// crossed an infinite length of it.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <variant>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "iris/render/scene.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief The clear outside (no absorbing solid).
inline constexpr std::uint32_t no_medium = 0xffffffffu;

/// \brief The medium a ray leaving a surface of material `m` along `w` (world) travels in,
/// having arrived in `current`: the inside of an absorbing dielectric (its material index)
/// when `w` goes to the back of the unit geometric normal `ng`, the clear outside when it
/// goes to the front or the dielectric does not absorb; `current` for any other surface.
inline std::uint32_t medium_after(const scene_desc& scene, std::uint32_t m, const glm::vec3& ng, const glm::vec3& w,
                                  std::uint32_t current) noexcept {
    const auto* d = std::get_if<material::dielectric>(&scene.materials[m]);
    if (!d) return current;
    return d->absorption && glm::dot(w, ng) < 0.0f ? m : no_medium;
}

/// \brief What a length t (possibly ∞) of a medium with absorption coefficient σ ≥ 0 lets
/// through: exp(−σ·t), exactly 1 where σ = 0 (also for t = ∞).
inline float beer_lambert(float sigma, float t) noexcept { return sigma > 0.0f ? std::exp(-sigma * t) : 1.0f; }

/// \brief The absorption coefficient of material m (an absorbing dielectric), at λ.
inline const tabulated_spectrum& absorption_of(const scene_desc& scene, std::uint32_t m) noexcept {
    return *std::get<material::dielectric>(scene.materials[m]).absorption;
}

}  // namespace iris
