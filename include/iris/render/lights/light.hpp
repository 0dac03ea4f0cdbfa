#pragma once
/// \file
/// \brief What every light of iris answers, in solid angle: the types a light sample is
/// made of. One header per light in this directory (`area.hpp`: emissive triangles,
/// `point.hpp`: point and spot, `distant.hpp`, `environment.hpp`: uniform or an image);
/// `iris/render/lights.hpp` chooses among a scene's lights by power.
///
/// | member | what it is |
/// |---|---|
/// | `sample_li(ref, u)` | a direction from a surface point toward the light, with its solid-angle pdf, what arrives along it (`emission_ref`) and the shadow segment to test |
/// | `pdf_li(…)` | the solid-angle pdf of a direction that BSDF sampling found (area and environment lights; delta lights have none) |
/// | `sample_le(u…)` | an emitted ray (origin, direction, pdfs of both) — the start of a light subpath |
/// | `power()` | the light's flux Φ/π up to the emitter spectrum's ∫L dλ (the selection weight) |
///
/// A delta light (point, spot, distant) cannot be hit by a ray: its `pdf` in `light_li` is
/// the discrete probability of choosing it, its emitted radiance arrives scaled by the
/// geometry (I·s(θ)/r²), and no BSDF strategy competes with it.

#include <cstdint>

#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"

namespace iris {

/// \brief Which spectrum arrives, as weights of the render's emission tables:
/// Le(λ) = Σ_{i < count} weight[i] · table_{first + i}(λ). The tables are one per
/// `scene_desc::emitters` entry, then the environment's (one for a constant environment,
/// three basis spectra for an image): `hero_tables::emission`, `bin_tables::emission`.
struct emission_ref {
    std::uint32_t first = 0;
    std::uint32_t count = 1;
    glm::vec3 weight{1.0f, 0.0f, 0.0f};
};

/// \brief A direction toward a light from a reference point.
struct light_li {
    glm::vec3 wi{0.0f};    ///< unit, from the reference point toward the light
    float pdf = 0.0f;      ///< solid-angle density of wi, selection included (delta: the selection probability)
    emission_ref le;       ///< what arrives along wi (delta lights: already divided by r², times the falloff)
    shadow_segment shadow; ///< what must be unoccluded (t_max = ∞ for lights at infinity)
    bool delta = false;    ///< point, spot, distant: no BSDF strategy reaches it
    // For bidirectional MIS (iris/render/bdpt.hpp): where the light was sampled and how
    // likely `sample_le` would have been to emit toward the reference point.
    bool infinite = false;   ///< distant, environment: the light is at infinity (`point`, `pdf_emit` unset)
    glm::vec3 point{0.0f};   ///< finite lights: the point sampled on an area light, a point or spot light's position
    glm::vec3 normal{0.0f};  ///< area lights: the unit normal of the sampled point (0 for the others)
    float pdf_emit = 0.0f;   ///< finite lights: solid-angle density of `sample_le` emitting toward the reference point
};

/// \brief An emitted ray: the start of a light subpath.
struct light_le {
    surface_point origin;  ///< with its error bound (exact for point lights)
    glm::vec3 normal{0.0f};///< unit normal of an area light's surface (0 for the others)
    glm::vec3 dir{0.0f};   ///< unit
    float pdf_pos = 0.0f;  ///< area density of the origin, selection included (delta in position: the selection probability)
    float pdf_dir = 0.0f;  ///< solid-angle density of dir
    emission_ref le;       ///< the radiance (or intensity) leaving along dir
    bool infinite = false; ///< distant, environment: the origin is on a disk outside the scene, not on the light
};

}  // namespace iris
