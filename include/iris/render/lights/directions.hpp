#pragma once
/// \file
/// \brief Sampling directions and points for lights: the uniform sphere, the uniform cone,
/// the cosine-weighted hemisphere, the uniform disk, and the environment maps' two
/// parametrisations of the sphere (latitude–longitude and pbrt-v4's equal-area square).
/// Each routine states the density it produces; tests/render/light_test.cpp checks each
/// with a χ² test.

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace iris::lights {

inline constexpr float pi = std::numbers::pi_v<float>;

/// \brief Uniform on the unit sphere; density 1/(4π).
inline glm::vec3 uniform_sphere(glm::vec2 u) noexcept {
    const float z = 1.0f - 2.0f * u.x;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * pi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

/// \brief Uniform in the cone around +z of cos θ ≥ `cos_max`; density 1/(2π(1 − cos_max)).
inline glm::vec3 uniform_cone(glm::vec2 u, float cos_max) noexcept {
    const float c = 1.0f - u.x * (1.0f - cos_max);
    const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
    const float phi = 2.0f * pi * u.y;
    return {s * std::cos(phi), s * std::sin(phi), c};
}

/// \brief Cosine-weighted on the hemisphere around +z; density cos θ / π.
inline glm::vec3 cosine_hemisphere(glm::vec2 u) noexcept {
    const float r = std::sqrt(u.x), phi = 2.0f * pi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u.x))};
}

/// \brief Uniform on the unit disk in the xy-plane; density 1/π.
inline glm::vec2 uniform_disk(glm::vec2 u) noexcept {
    const float r = std::sqrt(u.x), phi = 2.0f * pi * u.y;
    return {r * std::cos(phi), r * std::sin(phi)};
}

/// \brief Latitude–longitude: (x, y) ∈ [0, 1]² → θ = πy from +y, φ = 2πx;
/// dω = 2π² sin θ dx dy.
inline glm::vec3 latlong_to_direction(glm::vec2 p) noexcept {
    const float theta = pi * p.y, phi = 2.0f * pi * p.x;
    const float s = std::sin(theta);
    return {s * std::cos(phi), std::cos(theta), s * std::sin(phi)};
}
inline glm::vec2 direction_to_latlong(const glm::vec3& d) noexcept {
    const float theta = std::acos(std::clamp(d.y, -1.0f, 1.0f));
    float phi = std::atan2(d.z, d.x);
    if (phi < 0.0f) phi += 2.0f * pi;
    float x = phi / (2.0f * pi);
    if (!(x < 1.0f)) x = 0.0f;
    return {x, theta / pi};
}

/// \brief The equal-area octahedral map of the square onto the sphere (Clarberg 2008, as
/// pbrt-v4 stores its environment maps), in its own frame (+z the pole of the square's
/// centre); iris's directions are (x, z, −y) of that frame (its +z is iris's +y). Uniform
/// on the square is uniform on the sphere: dω = 4π dx dy.
inline glm::vec3 equal_area_to_direction(glm::vec2 p) noexcept {
    const float u = 2.0f * p.x - 1.0f, v = 2.0f * p.y - 1.0f;
    const float up = std::fabs(u), vp = std::fabs(v);
    const float signed_distance = 1.0f - (up + vp);  // > 0: the upper hemisphere
    const float d = std::fabs(signed_distance);
    const float r = 1.0f - d;
    const float phi = (r == 0.0f ? 1.0f : (vp - up) / r + 1.0f) * pi / 4.0f;
    const float z = std::copysign(1.0f - r * r, signed_distance);
    const float k = r * std::sqrt(std::max(0.0f, 2.0f - r * r));
    const float x = std::copysign(std::cos(phi), u) * k, y = std::copysign(std::sin(phi), v) * k;
    return glm::normalize(glm::vec3(x, z, -y));
}
inline glm::vec2 direction_to_equal_area(const glm::vec3& dir) noexcept {
    const float x = dir.x, y = -dir.z, z = dir.y;  // back to the map's frame
    const float ax = std::fabs(x), ay = std::fabs(y), az = std::fabs(z);
    const float r = std::sqrt(std::max(0.0f, 1.0f - az));
    // φ ∈ [0, π/2] in the first quadrant; t = (v′ − u′)/r and u′ + v′ = r (upper half)
    const float phi = std::atan2(ay, ax);
    const float t = phi * 4.0f / pi - 1.0f;
    float vp = 0.5f * r * (1.0f + t), up = 0.5f * r * (1.0f - t);
    if (z < 0.0f) {  // lower hemisphere: the square's outer triangles, folded
        const float a = 1.0f - vp, b = 1.0f - up;
        up = a;
        vp = b;
    }
    const float u = std::copysign(up, x), v = std::copysign(vp, y);
    return {std::clamp(0.5f * (u + 1.0f), 0.0f, 1.0f), std::clamp(0.5f * (v + 1.0f), 0.0f, 1.0f)};
}

}  // namespace iris::lights
