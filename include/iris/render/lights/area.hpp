#pragma once
/// \file
/// \brief An emissive triangle: a point uniform on its area, converted to solid angle at
/// the reference point (the density of the direction is p_A · r² / |cos θ_l|). One-sided
/// emitters emit toward their normal only.
///
/// Spherical-triangle sampling (uniform in solid angle) was not added: the built-in lamps
/// are small and far compared with their size, where area sampling's density is within a
/// few per cent of uniform solid angle (docs/performance.md, "Lights").

#include <cmath>
#include <cstdint>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/lights/directions.hpp"
#include "iris/render/lights/light.hpp"

namespace iris::lights {

struct triangle {
    glm::vec3 a, b, c, n;  ///< corners and unit geometric normal
    float area;
    std::uint32_t emitter;
    float probability;     ///< of being chosen
    bool two_sided;

    /// \brief A uniform point (square-root parametrisation: barycentrics of b and c).
    surface_point point(glm::vec2 u) const noexcept {
        const float su = std::sqrt(u.x);
        const float b1 = u.y * su, b2 = su - b1;  // b0 = 1 − √u.x
        return point_on_triangle(a, b, c, b1, b2);
    }

    bool emits_toward(float cos_l) const noexcept { return two_sided ? cos_l != 0.0f : cos_l > 0.0f; }

    std::optional<light_li> sample_li(const surface_point& ref, const glm::vec3& ng, glm::vec2 u) const noexcept {
        const surface_point q = point(u);
        const glm::vec3 to_light = q.p - ref.p;
        const float d2 = glm::dot(to_light, to_light);
        const float d = std::sqrt(d2);
        if (!(d > 0.0f)) return std::nullopt;
        light_li out;
        out.wi = to_light / d;
        const float cos_l = -glm::dot(n, out.wi);
        if (!emits_toward(cos_l)) return std::nullopt;
        out.pdf = probability / area * d2 / std::fabs(cos_l);
        out.le = {emitter, 1, {1.0f, 0.0f, 0.0f}};
        out.shadow = shadow_ray_between(ref, ng, q, n);
        out.point = q.p;
        out.normal = n;
        out.pdf_emit = (two_sided ? 0.5f : 1.0f) * std::fabs(cos_l) / pi;  // sample_le's cosine lobe on the side facing ref
        return out;
    }

    /// \brief A point uniform on the triangle, a direction cosine-weighted about the
    /// emitting side (either side with probability ½ for a two-sided emitter).
    light_le sample_le(glm::vec2 u_pos, glm::vec2 u_dir, float u_side) const noexcept {
        light_le out;
        out.origin = point(u_pos);
        glm::vec3 side = n;
        float side_p = 1.0f;
        if (two_sided) {
            side_p = 0.5f;
            if (u_side < 0.5f) side = -n;
        }
        out.normal = n;
        const frame f = frame::from_normal(side);
        const glm::vec3 l = cosine_hemisphere(u_dir);
        out.dir = glm::normalize(f.to_world(l));
        out.pdf_pos = probability / area;
        out.pdf_dir = side_p * l.z / pi;
        out.le = {emitter, 1, {1.0f, 0.0f, 0.0f}};
        return out;
    }
};

}  // namespace iris::lights
