#pragma once
/// \file
/// \brief Orthonormal frames and the small vector helpers of the path tracer.

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace iris {

/// \brief An orthonormal basis (s, t, n); `to_local` maps n to +z.
struct frame {
    glm::vec3 s, t, n;

    /// \brief Frame around a unit normal (Duff et al. 2017, branchless and continuous).
    static frame from_normal(const glm::vec3& n) noexcept {
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z);
        const float b = n.x * n.y * a;
        return {{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
    }
    glm::vec3 to_local(const glm::vec3& v) const noexcept { return {glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)}; }
    glm::vec3 to_world(const glm::vec3& v) const noexcept { return v.x * s + v.y * t + v.z * n; }
};

/// \brief Mirror `w` (pointing away from the surface) about `n`.
inline glm::vec3 reflect_about(const glm::vec3& w, const glm::vec3& n) noexcept { return 2.0f * glm::dot(w, n) * n - w; }

/// \brief Move a ray origin off a surface along the normal, on the side of `dir`, by an
/// amount that scales with the magnitude of the position (float spacing), so that rays
/// neither re-hit their own triangle nor tunnel through thin geometry.
inline glm::vec3 offset_ray_origin(const glm::vec3& p, const glm::vec3& ng, const glm::vec3& dir) noexcept {
    const float scale = 1e-4f * (1.0f + std::fmax(std::fabs(p.x), std::fmax(std::fabs(p.y), std::fabs(p.z))));
    return glm::dot(ng, dir) >= 0.0f ? p + scale * ng : p - scale * ng;
}

}  // namespace iris
