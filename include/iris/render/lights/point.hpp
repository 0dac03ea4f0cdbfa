#pragma once
/// \file
/// \brief Point and spot lights: delta in position. Toward a reference point they send
/// I(λ)·s(cos θ)/r² along the one direction that reaches it (s = 1 for a point light; a
/// smoothstep falloff in cos θ about a spot's axis, as pbrt-v4's); emitted rays leave
/// uniformly over the sphere (point) or the spot's cone.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/lights/directions.hpp"
#include "iris/render/lights/light.hpp"
#include "iris/render/scene.hpp"

namespace iris::lights {

/// \brief A point light, or a spot light when `cos_total_width` > −1.
struct point_light {
    glm::vec3 position;
    glm::vec3 axis{0.0f, 0.0f, 1.0f};
    float cos_falloff_start = -1.0f, cos_total_width = -1.0f;  ///< −1, −1: a point light
    std::uint32_t emitter = 0;
    float probability = 0.0f;

    static point_light from(const light::point& p) noexcept { return {p.position, {0.0f, 0.0f, 1.0f}, -1.0f, -1.0f, p.emitter, 0.0f}; }
    static point_light from(const light::spot& s) noexcept {
        return {s.position, glm::normalize(s.direction), s.cos_falloff_start, s.cos_total_width, s.emitter, 0.0f};
    }

    bool is_spot() const noexcept { return cos_total_width > -1.0f; }

    /// \brief s(cos θ): 1 inside the falloff start, 0 outside the total width, smoothstep between.
    float falloff(float cos_theta) const noexcept {
        if (!is_spot()) return 1.0f;
        if (cos_theta >= cos_falloff_start) return 1.0f;
        if (cos_theta <= cos_total_width) return 0.0f;
        const float t = (cos_theta - cos_total_width) / (cos_falloff_start - cos_total_width);
        return t * t * (3.0f - 2.0f * t);
    }

    /// \brief ∫ s(cos θ) dω / π: the flux Φ/π per unit intensity (4 for a point light;
    /// for a spot, 2(1 − cos_start) for the flat part plus (cos_start − cos_width) for the
    /// smoothstep, whose mean over its range is ½).
    float solid_angle_over_pi() const noexcept {
        if (!is_spot()) return 4.0f;
        return 2.0f * ((1.0f - cos_falloff_start) + 0.5f * (cos_falloff_start - cos_total_width));
    }

    std::optional<light_li> sample_li(const surface_point& ref, const glm::vec3& ng) const noexcept {
        const glm::vec3 to_light = position - ref.p;
        const float d2 = glm::dot(to_light, to_light);
        if (!(d2 > 0.0f)) return std::nullopt;
        light_li out;
        out.wi = to_light / std::sqrt(d2);
        const float s = falloff(-glm::dot(out.wi, axis));
        if (!(s > 0.0f)) return std::nullopt;
        out.pdf = probability;
        out.delta = true;
        out.le = {emitter, 1, {s / d2, 0.0f, 0.0f}};
        const glm::vec3 o = offset_ray_origin(ref, ng, to_light);
        out.shadow = {o, position - o, 1.0f - 1e-4f};
        out.point = position;
        out.pdf_emit = is_spot() ? 1.0f / (2.0f * pi * (1.0f - cos_total_width)) : 1.0f / (4.0f * pi);  // s > 0: inside the cone
        return out;
    }

    /// \brief An emitted ray: uniform over the sphere (point) or the cone of the total width (spot).
    light_le sample_le(glm::vec2 u) const noexcept {
        light_le out;
        out.origin = {position, glm::vec3(0.0f)};
        out.pdf_pos = probability;
        if (is_spot()) {
            const frame f = frame::from_normal(axis);
            out.dir = glm::normalize(f.to_world(uniform_cone(u, cos_total_width)));
            out.pdf_dir = 1.0f / (2.0f * pi * (1.0f - cos_total_width));
        } else {
            out.dir = uniform_sphere(u);
            out.pdf_dir = 1.0f / (4.0f * pi);
        }
        out.le = {emitter, 1, {falloff(glm::dot(out.dir, axis)), 0.0f, 0.0f}};
        return out;
    }
};

}  // namespace iris::lights
