#pragma once
/// \file
/// \brief The environment as a light: a constant radiance (sampled uniformly over the
/// sphere), or an image (bilinear lookup; sampled by a piecewise-constant density over its
/// texels, iris/sampling/piecewise.hpp). Directions that escape the scene find it by BSDF
/// sampling too; both strategies are weighted by MIS (`pdf_li`).
///
/// The image's sampling density per texel is the largest texel sum Σ_i w_i in its 3 × 3
/// neighbourhood (so that every direction where the bilinear lookup is positive has a
/// positive density), times sin θ of the texel's centre for the latitude–longitude map
/// (whose texels shrink toward the poles); the density of a direction divides by the
/// map's Jacobian (2π² sin θ, or 4π for the equal-area square).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/lights/directions.hpp"
#include "iris/render/lights/light.hpp"
#include "iris/render/scene.hpp"
#include "iris/sampling/piecewise.hpp"

namespace iris::lights {

class environment_light {
public:
    environment_light() = default;
    /// \brief `table`: the first of the environment's emission tables (one, or three for a map).
    environment_light(const environment_desc& env, std::uint32_t table) : m_table(table) {
        if (!env.map) return;
        m_map = &*env.map;
        m_from_map = glm::transpose(m_map->to_map);  // orthogonal: its inverse
        const int w = m_map->width, h = m_map->height;
        std::vector<float> density(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                float m = 0.0f;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const glm::vec3 t = texel(x + dx, y + dy);
                        m = std::max(m, t.x + t.y + t.z);
                    }
                if (m_map->mapping == environment_mapping::latlong)
                    m *= std::sin(pi * (static_cast<float>(y) + 0.5f) / static_cast<float>(h));
                density[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] = m;
            }
        m_distribution = piecewise_constant_2d(density, static_cast<std::size_t>(w), static_cast<std::size_t>(h));
    }

    bool is_map() const noexcept { return m_map != nullptr; }

    /// \brief The radiance arriving from unit direction `dir` (of a ray leaving the scene).
    emission_ref emission(const glm::vec3& dir) const noexcept {
        if (!m_map) return {m_table, 1, {1.0f, 0.0f, 0.0f}};
        return {m_table, 3, lookup(to_square(dir))};
    }

    /// \brief Solid-angle density of sampling `dir` (selection not included).
    float pdf(const glm::vec3& dir) const noexcept {
        if (!m_map) return 1.0f / (4.0f * pi);
        const glm::vec2 p = to_square(dir);
        const float j = jacobian(p);
        return j > 0.0f ? m_distribution.pdf(p) / j : 0.0f;
    }

    struct direction_sample {
        glm::vec3 dir;
        float pdf;  ///< solid angle
        emission_ref le;
    };
    std::optional<direction_sample> sample(glm::vec2 u) const noexcept {
        if (!m_map) {
            const glm::vec3 d = uniform_sphere(u);
            return direction_sample{d, 1.0f / (4.0f * pi), {m_table, 1, {1.0f, 0.0f, 0.0f}}};
        }
        const auto s = m_distribution.sample(u);
        const float j = jacobian(s.p);
        if (!(s.pdf > 0.0f) || !(j > 0.0f)) return std::nullopt;
        return direction_sample{to_direction(s.p), s.pdf / j, {m_table, 3, lookup(s.p)}};
    }

    std::optional<light_li> sample_li(const surface_point& ref, const glm::vec3& ng, glm::vec2 u,
                                      float probability) const noexcept {
        const auto s = sample(u);
        if (!s) return std::nullopt;
        light_li out;
        out.wi = s->dir;
        out.pdf = probability * s->pdf;
        out.le = s->le;
        out.infinite = true;
        out.shadow = {offset_ray_origin(ref, ng, s->dir), s->dir, std::numeric_limits<float>::infinity()};
        return out;
    }

    /// \brief An emitted ray: a direction toward the scene from the environment's density,
    /// starting on a disk of radius R perpendicular to it, outside the bounding sphere.
    std::optional<light_le> sample_le(glm::vec2 u_dir, glm::vec2 u_pos, const glm::vec3& centre, float radius,
                                      float probability) const noexcept {
        const auto s = sample(u_dir);
        if (!s) return std::nullopt;
        light_le out;
        out.dir = -s->dir;  // light arriving from s->dir travels along −s->dir
        const frame f = frame::from_normal(out.dir);
        const glm::vec2 d = uniform_disk(u_pos) * radius;
        out.origin = {centre + radius * s->dir + f.to_world({d.x, d.y, 0.0f}), glm::vec3(0.0f)};
        out.pdf_pos = probability / (pi * radius * radius);
        out.pdf_dir = s->pdf;
        out.le = s->le;
        out.infinite = true;
        return out;
    }

    /// \brief ∫ w_i(ω) dω over the sphere, per basis spectrum (the map's flux per unit
    /// radiance of each; (4π, 0, 0) for a constant environment).
    glm::dvec3 integral() const {
        if (!m_map) return {4.0 * static_cast<double>(pi), 0.0, 0.0};
        glm::dvec3 sum(0.0);
        const int w = m_map->width, h = m_map->height;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const glm::vec2 p{(static_cast<float>(x) + 0.5f) / static_cast<float>(w),
                                  (static_cast<float>(y) + 0.5f) / static_cast<float>(h)};
                sum += glm::dvec3(texel(x, y)) * static_cast<double>(jacobian(p));
            }
        return sum / (static_cast<double>(w) * static_cast<double>(h));
    }

private:
    glm::vec2 to_square(const glm::vec3& world) const noexcept {
        const glm::vec3 d = m_map->to_map * world;
        return m_map->mapping == environment_mapping::latlong ? direction_to_latlong(d) : direction_to_equal_area(d);
    }
    glm::vec3 to_direction(glm::vec2 p) const noexcept {
        const glm::vec3 d = m_map->mapping == environment_mapping::latlong ? latlong_to_direction(p) : equal_area_to_direction(p);
        return m_from_map * d;
    }
    /// \brief dω / (dx dy) at p.
    float jacobian(glm::vec2 p) const noexcept {
        if (m_map->mapping == environment_mapping::equal_area) return 4.0f * pi;
        return 2.0f * pi * pi * std::sin(pi * p.y);
    }

    /// \brief The texel at (x, y): x wraps around a latitude–longitude map, everything else clamps.
    glm::vec3 texel(int x, int y) const noexcept {
        const int w = m_map->width, h = m_map->height;
        if (m_map->mapping == environment_mapping::latlong) x = ((x % w) + w) % w;
        else x = std::clamp(x, 0, w - 1);
        y = std::clamp(y, 0, h - 1);
        return m_map->weights[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)];
    }

    /// \brief Bilinear between the four texel centres around p.
    glm::vec3 lookup(glm::vec2 p) const noexcept {
        const float fx = p.x * static_cast<float>(m_map->width) - 0.5f, fy = p.y * static_cast<float>(m_map->height) - 0.5f;
        if (!std::isfinite(fx) || !std::isfinite(fy)) return glm::vec3(0.0f);  // a NaN direction sees nothing
        const float x0 = std::floor(fx), y0 = std::floor(fy);
        const float tx = fx - x0, ty = fy - y0;
        const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
        return (1.0f - ty) * ((1.0f - tx) * texel(ix, iy) + tx * texel(ix + 1, iy)) +
               ty * ((1.0f - tx) * texel(ix, iy + 1) + tx * texel(ix + 1, iy + 1));
    }

    std::uint32_t m_table = 0;
    const environment_map* m_map = nullptr;
    glm::mat3 m_from_map{1.0f};
    piecewise_constant_2d m_distribution;
};

}  // namespace iris::lights
