#pragma once
/// \file
/// \brief A distant light: parallel light along one direction, irradiance E(λ) on a surface
/// facing it. Emitted rays start uniformly on a disk of the scene's bounding radius R
/// perpendicular to the direction, outside the scene (flux π R² E).

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/lights/directions.hpp"
#include "iris/render/lights/light.hpp"

namespace iris::lights {

struct distant_light {
    glm::vec3 direction;  ///< unit, the way the light travels
    std::uint32_t emitter = 0;
    float probability = 0.0f;

    std::optional<light_li> sample_li(const surface_point& ref, const glm::vec3& ng) const noexcept {
        light_li out;
        out.wi = -direction;
        out.pdf = probability;
        out.delta = true;
        out.infinite = true;
        out.le = {emitter, 1, {1.0f, 0.0f, 0.0f}};
        out.shadow = {offset_ray_origin(ref, ng, out.wi), out.wi, std::numeric_limits<float>::infinity()};
        return out;
    }

    light_le sample_le(glm::vec2 u, const glm::vec3& centre, float radius) const noexcept {
        light_le out;
        const frame f = frame::from_normal(direction);
        const glm::vec2 d = uniform_disk(u) * radius;
        out.origin = {centre + radius * -direction + f.to_world({d.x, d.y, 0.0f}), glm::vec3(0.0f)};
        out.dir = direction;
        out.pdf_pos = probability / (pi * radius * radius);
        out.pdf_dir = 1.0f;  // delta in direction
        out.infinite = true;
        out.le = {emitter, 1, {1.0f, 0.0f, 0.0f}};
        return out;
    }
};

}  // namespace iris::lights
