#pragma once
/// \file
/// \brief Orthonormal frames and the small vector helpers of the path tracer.

#include <cmath>
#include <limits>

#include <glm/common.hpp>
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

/// \brief A point on a triangle with a bound on its floating-point error, per axis.
struct surface_point {
    glm::vec3 p;      ///< the point, from barycentric coordinates
    glm::vec3 error;  ///< |computed − exact| ≤ error, per axis
};

/// \brief The point b0·a + b1·b + b2·c (b0 = 1 − b1 − b2) and a bound on its error: the
/// rounding of that sum, γ₇·(|b0·a| + |b1·b| + |b2·c|) with γₙ = nε/(1 − nε), ε = 2⁻²⁴
/// (Pharr, Jakob and Humphreys, *Physically Based Rendering*, 3rd ed., §3.9), plus 32ε
/// times the triangle's largest coordinate for the ray–triangle test that will start from
/// it. pbrt's own test rejects hits closer than its error in t; Embree's accepts any
/// t ≥ tnear = 0, so on an axis-aligned plane (zero rounding across it) an unmoved origin
/// re-hits its own triangle (10–37 % of rays leaving the built-in scenes' walls); 2ε
/// already stops that on every built-in scene, 32ε is the margin. Rebuilt from
/// barycentrics, not as o + t·d, the point lies on the triangle's plane up to that bound
/// whatever the error of t.
inline surface_point point_on_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, float b1,
                                       float b2) noexcept {
    const float b0 = 1.0f - b1 - b2;
    const glm::vec3 p = b0 * a + b1 * b + b2 * c;
    constexpr float eps = 0x1.0p-24f;
    constexpr float gamma7 = 7.0f * eps / (1.0f - 7.0f * eps);
    const glm::vec3 m = glm::max(glm::abs(a), glm::max(glm::abs(b), glm::abs(c)));
    const float floor = 32.0f * eps * std::fmax(m.x, std::fmax(m.y, m.z));
    return {p, gamma7 * (glm::abs(b0 * a) + glm::abs(b1 * b) + glm::abs(b2 * c)) + glm::vec3(floor)};
}

/// \brief Move a ray origin off a surface along its unit geometric normal `ng`, to the side
/// of `dir`, by the projection of the point's error bound onto the normal (then one more
/// float step outwards): the smallest move that is sure to put the origin on that side of
/// the surface's plane. Two surfaces closer than a ray offset are indistinguishable to a
/// ray leaving either, so the offset must be small: a fixed 10⁻⁴·(1 + |p|) once put rays
/// leaving the bottom of `cornell`'s glass cube (0.1 mm above the floor) under the floor,
/// and the image lost 2 % (tests/renderer/estimators_test.cpp).
inline glm::vec3 offset_ray_origin(const surface_point& sp, const glm::vec3& ng, const glm::vec3& dir) noexcept {
    const float d = glm::dot(glm::abs(ng), sp.error);
    glm::vec3 offset = d * ng;
    if (glm::dot(ng, dir) < 0.0f) offset = -offset;
    glm::vec3 o = sp.p + offset;
    for (int i = 0; i < 3; ++i) {
        if (offset[i] > 0.0f) o[i] = std::nextafter(o[i], std::numeric_limits<float>::infinity());
        else if (offset[i] < 0.0f) o[i] = std::nextafter(o[i], -std::numeric_limits<float>::infinity());
    }
    return o;
}

/// \brief The segment a shadow ray must test between a surface point `p` (unit geometric
/// normal `np`) and a point `q` on another surface (normal `nq`): `origin` is `p` moved off
/// its surface towards `q`, the far end is `q` moved off its surface towards `p`, and
/// `direction` = far end − origin, so the segment is t ∈ (0, `t_max`) with t_max just below
/// 1. Both ends are offset and the direction is aimed from the moved origin: a direction
/// computed from `p` itself and reused from a moved origin runs parallel to p→q, an offset
/// above it, and reaches q's plane before q — by offset / cos θ at p, more than a relative
/// margin off-axis — so such a ray hit the very emitter it was aimed at and direct light
/// was lost away from a lamp's axis (tests/render/direct_light_test.cpp).
struct shadow_segment {
    glm::vec3 origin, direction;
    float t_max;
};
inline shadow_segment shadow_ray_between(const surface_point& p, const glm::vec3& np, const surface_point& q,
                                         const glm::vec3& nq) noexcept {
    const glm::vec3 o = offset_ray_origin(p, np, q.p - p.p);
    const glm::vec3 target = offset_ray_origin(q, nq, p.p - q.p);
    return {o, target - o, 1.0f - 1e-4f};
}

}  // namespace iris
