#pragma once
/// \file
/// \brief Area-light sampling by power: every emissive triangle is chosen with
/// probability ∝ area × ∫L(λ)dλ, then a point uniformly on it.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/scene.hpp"

namespace iris {

struct light_sample {
    surface_point point;   ///< the point and its floating-point error bound
    glm::vec3 normal;      ///< unit geometric normal of the emitting triangle
    std::uint32_t emitter;
    float pdf_area;        ///< density of this point per unit area
};

class light_sampler {
public:
    explicit light_sampler(const scene_desc& scene) {
        m_shape_offset.assign(scene.shapes.size(), -1);
        std::vector<double> power(scene.emitters.size(), 0.0);
        for (std::size_t e = 0; e < scene.emitters.size(); ++e) {
            const auto& l = scene.emitters[e].radiance;
            // ∫L dλ over the scene's domain by 1 nm trapezoids (build time only)
            for (float x = scene.lambda_min; x < scene.lambda_max; x += 1.0f)
                power[e] += 0.5 * (l(x) + l(std::min(x + 1.0f, scene.lambda_max))) * std::min(1.0f, scene.lambda_max - x);
        }
        double total = 0.0;
        for (std::size_t s = 0; s < scene.shapes.size(); ++s) {
            const auto& shape = scene.shapes[s];
            if (!shape.emitter) continue;
            m_shape_offset[s] = static_cast<std::int64_t>(m_tris.size());
            for (const auto& t : shape.mesh.triangles) {
                const glm::vec3 a = shape.mesh.positions[t[0]], b = shape.mesh.positions[t[1]], c = shape.mesh.positions[t[2]];
                const glm::vec3 cr = glm::cross(b - a, c - a);
                const float area = 0.5f * glm::length(cr);
                const double w = static_cast<double>(area) * power[*shape.emitter] * (scene.emitters[*shape.emitter].two_sided ? 2.0 : 1.0);
                m_tris.push_back({a, b, c, area > 0.0f ? cr / (2.0f * area) : glm::vec3(0.0f), area, *shape.emitter, 0.0f});
                total += w;
                m_cdf.push_back(total);
            }
        }
        if (total > 0.0) {
            double prev = 0.0;
            for (std::size_t i = 0; i < m_tris.size(); ++i) {
                m_tris[i].probability = static_cast<float>((m_cdf[i] - prev) / total);
                prev = m_cdf[i];
                m_cdf[i] /= total;
            }
            m_cdf.back() = 1.0;
        } else {  // no emitter has power: nothing to sample, nothing to look up
            m_tris.clear();
            m_cdf.clear();
            m_shape_offset.assign(scene.shapes.size(), -1);
        }
    }

    bool empty() const noexcept { return m_tris.empty(); }

    /// \brief A point on an emitter; `u_select` picks the triangle, `u` the point.
    std::optional<light_sample> sample(float u_select, glm::vec2 u) const noexcept {
        if (m_tris.empty()) return std::nullopt;
        const auto it = std::upper_bound(m_cdf.begin(), m_cdf.end(), static_cast<double>(u_select));
        const std::size_t i = std::min(static_cast<std::size_t>(it - m_cdf.begin()), m_tris.size() - 1);
        const tri& t = m_tris[i];
        if (!(t.probability > 0.0f)) return std::nullopt;
        // uniform point on a triangle (square-root parametrisation): barycentrics of b and c
        const float su = std::sqrt(u.x);
        const float b1 = u.y * su, b2 = su - b1;  // b0 = 1 − √u.x
        return light_sample{point_on_triangle(t.a, t.b, t.c, b1, b2), t.n, t.emitter, t.probability / t.area};
    }

    /// \brief Area density of sampling a point on triangle `prim` of shape `shape` (0 if not emissive).
    float pdf_area(std::uint32_t shape, std::uint32_t prim) const noexcept {
        if (shape >= m_shape_offset.size() || m_shape_offset[shape] < 0) return 0.0f;
        const tri& t = m_tris[static_cast<std::size_t>(m_shape_offset[shape]) + prim];
        return t.area > 0.0f ? t.probability / t.area : 0.0f;
    }

private:
    struct tri {
        glm::vec3 a, b, c, n;
        float area;
        std::uint32_t emitter;
        float probability;
    };
    std::vector<tri> m_tris;
    std::vector<double> m_cdf;
    std::vector<std::int64_t> m_shape_offset;
};

}  // namespace iris
