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
/// in the scene's own medium if it has one (`scene_desc::medium`, fog), in the clear
/// otherwise. A ray that meets nothing while inside a solid (an open mesh) or in the scene's
/// medium crossed an infinite length of it. Scattering media: iris/render/medium.hpp.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <variant>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "iris/render/scene.hpp"
#include "iris/spectrum/sampled.hpp"

namespace iris {

/// \brief No medium: the clear outside of a scene without its own medium, or the inside of
/// clear glass.
inline constexpr std::uint32_t no_medium = 0xffffffffu;

/// \brief A medium is named by the index of the material whose solid it fills (a dielectric
/// with `absorption` or `scattering`), or by the material count for the scene's own medium
/// (`scene_desc::medium`, outside every solid): this one, or `no_medium` without one.
inline std::uint32_t outside_medium(const scene_desc& scene) noexcept {
    return scene.medium ? static_cast<std::uint32_t>(scene.materials.size()) : no_medium;
}

/// \brief Does dielectric d's solid hold a medium (absorbing, scattering or both)?
inline bool fills_medium(const material::dielectric& d) noexcept { return d.absorption || d.scattering; }

/// \brief The medium a ray leaving a surface of material `m` along `w` (world) travels in,
/// having arrived in `current`: at a dielectric, the inside of its solid when `w` goes to the
/// back of the unit geometric normal `ng` (its medium, or none for clear glass), the scene's
/// outside medium when `w` goes to the front; `current` for any other surface.
inline std::uint32_t medium_after(const scene_desc& scene, std::uint32_t m, const glm::vec3& ng, const glm::vec3& w,
                                  std::uint32_t current) noexcept {
    const auto* d = std::get_if<material::dielectric>(&scene.materials[m]);
    if (!d) return current;
    if (glm::dot(w, ng) < 0.0f) return fills_medium(*d) ? m : no_medium;
    return outside_medium(scene);
}

/// \brief The absorption coefficient σ_a of medium `id` (a material index or the scene's
/// medium; `outside_medium`), or null where it does not absorb.
inline const tabulated_spectrum* medium_absorption(const scene_desc& scene, std::uint32_t id) noexcept {
    if (id == no_medium) return nullptr;
    if (id == scene.materials.size()) return scene.medium && scene.medium->absorption ? &*scene.medium->absorption : nullptr;
    const auto* d = std::get_if<material::dielectric>(&scene.materials[id]);
    return d && d->absorption ? &*d->absorption : nullptr;
}

/// \brief The scattering of medium `id`, or null where it does not scatter.
inline const medium_scattering* medium_scattering_of(const scene_desc& scene, std::uint32_t id) noexcept {
    if (id == no_medium) return nullptr;
    if (id == scene.materials.size()) return scene.medium && scene.medium->scattering ? &*scene.medium->scattering : nullptr;
    const auto* d = std::get_if<material::dielectric>(&scene.materials[id]);
    return d && d->scattering ? &*d->scattering : nullptr;
}

/// \brief The number of medium ids a scene's tables hold: one per material, and one for the
/// scene's own medium if it has one.
inline std::size_t medium_count(const scene_desc& scene) noexcept {
    return scene.materials.size() + (scene.medium ? 1 : 0);
}

/// \brief What a length t (possibly ∞) of a medium with absorption coefficient σ ≥ 0 lets
/// through: exp(−σ·t), exactly 1 where σ = 0 (also for t = ∞).
inline float beer_lambert(float sigma, float t) noexcept { return sigma > 0.0f ? std::exp(-sigma * t) : 1.0f; }


}  // namespace iris
