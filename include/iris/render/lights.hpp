#pragma once
/// \file
/// \brief `light_sampler`: every light of a scene — emissive triangles, point, spot and
/// distant lights, the environment — chosen with probability ∝ its flux (pbrt-v4's default
/// "power" selection), each answering in solid angle (iris/render/lights/light.hpp).
///
/// Selection weights are Φ/π (π cancels): a triangle A·∫L dλ (×2 two-sided), a point light
/// 4∫I dλ, a spot ∫s dω/π·∫I dλ, a distant light R²∫E dλ and the environment
/// R²·Σ_i ∫w_i dω ∫basis_i dλ (4πR²∫L dλ when constant), R the radius of the scene's
/// bounding sphere (the flux these lights send through it). Triangles come first in one
/// CDF, so a scene of area lights only is sampled as before this interface existed.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <variant>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/frame.hpp"
#include "iris/render/lights/area.hpp"
#include "iris/render/lights/distant.hpp"
#include "iris/render/lights/environment.hpp"
#include "iris/render/lights/light.hpp"
#include "iris/render/lights/point.hpp"
#include "iris/render/scene.hpp"

namespace iris {

/// \brief ∫L dλ over the scene's domain by 1 nm trapezoids (build time only).
inline double integrate_over_domain(const tabulated_spectrum& l, float lambda_min, float lambda_max) {
    double sum = 0.0;
    for (float x = lambda_min; x < lambda_max; x += 1.0f)
        sum += 0.5 * (l(x) + l(std::min(x + 1.0f, lambda_max))) * std::min(1.0f, lambda_max - x);
    return sum;
}

/// \brief The centre and radius of a sphere around every shape and light position of a scene.
struct bounding_sphere {
    glm::vec3 centre{0.0f};
    float radius = 1.0f;

    explicit bounding_sphere(const scene_desc& scene) {
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
        for (const auto& s : scene.shapes)
            for (const auto& p : s.mesh.positions) {
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
        for (const auto& l : scene.lights)
            if (const auto* p = std::get_if<light::point>(&l)) {
                lo = glm::min(lo, p->position);
                hi = glm::max(hi, p->position);
            } else if (const auto* s = std::get_if<light::spot>(&l)) {
                lo = glm::min(lo, s->position);
                hi = glm::max(hi, s->position);
            }
        if (lo.x <= hi.x) {
            centre = 0.5f * (lo + hi);
            radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
        }
    }
};

class light_sampler {
public:
    explicit light_sampler(const scene_desc& scene) : m_bounds(scene), m_environment_table(static_cast<std::uint32_t>(scene.emitters.size())) {
        m_shape_offset.assign(scene.shapes.size(), -1);
        std::vector<double> power(scene.emitters.size(), 0.0);
        for (std::size_t e = 0; e < scene.emitters.size(); ++e)
            power[e] = integrate_over_domain(scene.emitters[e].radiance, scene.lambda_min, scene.lambda_max);
        std::vector<double> weight;
        for (std::size_t s = 0; s < scene.shapes.size(); ++s) {
            const auto& shape = scene.shapes[s];
            if (!shape.emitter) continue;
            const bool two = scene.emitters[*shape.emitter].two_sided;
            m_shape_offset[s] = static_cast<std::int64_t>(m_tris.size());
            for (const auto& t : shape.mesh.triangles) {
                const glm::vec3 a = shape.mesh.positions[t[0]], b = shape.mesh.positions[t[1]], c = shape.mesh.positions[t[2]];
                const glm::vec3 cr = glm::cross(b - a, c - a);
                const float area = 0.5f * glm::length(cr);
                weight.push_back(static_cast<double>(area) * power[*shape.emitter] * (two ? 2.0 : 1.0));
                m_tris.push_back({a, b, c, area > 0.0f ? cr / (2.0f * area) : glm::vec3(0.0f), area, *shape.emitter, 0.0f, two});
            }
        }
        const double r2 = static_cast<double>(m_bounds.radius) * static_cast<double>(m_bounds.radius);
        for (const auto& l : scene.lights) {
            std::visit(
                [&](const auto& x) {
                    using L = std::decay_t<decltype(x)>;
                    if constexpr (std::is_same_v<L, light::distant>) {
                        m_others.push_back(lights::distant_light{glm::normalize(x.direction), x.emitter, 0.0f});
                        weight.push_back(r2 * power[x.emitter]);
                    } else {
                        const auto p = lights::point_light::from(x);
                        m_others.push_back(p);
                        weight.push_back(static_cast<double>(p.solid_angle_over_pi()) * power[x.emitter]);
                    }
                },
                l);
        }
        if (scene.environment) {
            m_environment = lights::environment_light(*scene.environment, m_environment_table);
            const glm::dvec3 flux = m_environment.integral();
            double w = 0.0;
            if (scene.environment->map) {
                for (int i = 0; i < 3; ++i)
                    w += flux[i] * integrate_over_domain(scene.environment->basis[static_cast<std::size_t>(i)],
                                                         scene.lambda_min, scene.lambda_max);
            } else {
                w = flux[0] * integrate_over_domain(scene.environment->radiance, scene.lambda_min, scene.lambda_max);
            }
            m_has_environment = true;
            m_environment_slot = m_others.size();
            m_others.push_back(environment_slot{});
            weight.push_back(r2 * w);
        }
        double total = 0.0;
        for (double w : weight) total += (std::isfinite(w) && w > 0.0) ? w : 0.0;
        if (!(total > 0.0) || !std::isfinite(total)) {  // no light has power: nothing to sample, nothing to look up
            m_tris.clear();
            m_others.clear();
            m_shape_offset.assign(scene.shapes.size(), -1);
            m_environment_slot = no_slot;
            return;
        }
        double sum = 0.0;
        m_probability.resize(weight.size());
        for (std::size_t i = 0; i < weight.size(); ++i) {
            const double w = (std::isfinite(weight[i]) && weight[i] > 0.0) ? weight[i] : 0.0;
            sum += w;
            m_cdf.push_back(sum / total);
            m_probability[i] = static_cast<float>(w / total);
        }
        m_cdf.back() = 1.0;
        for (std::size_t i = 0; i < m_tris.size(); ++i) m_tris[i].probability = m_probability[i];
        for (std::size_t i = 0; i < m_others.size(); ++i) {
            const float p = m_probability[m_tris.size() + i];
            std::visit(
                [&](auto& x) {
                    if constexpr (!std::is_same_v<std::decay_t<decltype(x)>, environment_slot>) x.probability = p;
                },
                m_others[i]);
        }
    }

    bool empty() const noexcept { return m_cdf.empty(); }
    /// \brief Lights that are not emissive triangles (point, spot, distant, environment).
    std::size_t other_count() const noexcept { return m_others.size(); }

    /// \brief A direction toward one light from surface point `ref` (unit geometric normal
    /// `ng`): `u_select` picks the light, `u` the point or direction on it.
    std::optional<light_li> sample_li(const surface_point& ref, const glm::vec3& ng, float u_select,
                                      glm::vec2 u) const noexcept {
        if (m_cdf.empty()) return std::nullopt;
        const std::size_t i = choose(u_select);
        if (i < m_tris.size()) {
            const lights::triangle& t = m_tris[i];
            if (!(t.probability > 0.0f)) return std::nullopt;
            return t.sample_li(ref, ng, u);
        }
        const std::size_t k = i - m_tris.size();
        return std::visit(
            [&](const auto& x) -> std::optional<light_li> {
                using L = std::decay_t<decltype(x)>;
                if constexpr (std::is_same_v<L, environment_slot>)
                    return m_environment.sample_li(ref, ng, u, m_probability[i]);
                else {
                    if (!(x.probability > 0.0f)) return std::nullopt;
                    return x.sample_li(ref, ng);
                }
            },
            m_others[k]);
    }

    /// \brief Area density of sampling a point on triangle `prim` of shape `shape`,
    /// selection included (0 if not emissive).
    float pdf_area(std::uint32_t shape, std::uint32_t prim) const noexcept {
        if (shape >= m_shape_offset.size() || m_shape_offset[shape] < 0) return 0.0f;
        const lights::triangle& t = m_tris[static_cast<std::size_t>(m_shape_offset[shape]) + prim];
        return t.area > 0.0f ? t.probability / t.area : 0.0f;
    }

    /// \brief Is there an environment (whatever its power)?
    bool has_environment() const noexcept { return m_has_environment; }
    /// \brief What arrives along a ray that escapes the scene in unit direction `dir`.
    emission_ref environment_emission(const glm::vec3& dir) const noexcept { return m_environment.emission(dir); }
    /// \brief Solid-angle density with which next-event estimation samples `dir` toward the
    /// environment, selection included (0 if it is never sampled).
    float pdf_environment(const glm::vec3& dir) const noexcept {
        if (m_environment_slot == no_slot) return 0.0f;
        return m_probability[m_tris.size() + m_environment_slot] * m_environment.pdf(dir);
    }

    /// \brief An emitted ray from one light, chosen by power (for light subpaths).
    std::optional<light_le> sample_le(float u_select, glm::vec2 u_pos, glm::vec2 u_dir, float u_side) const noexcept {
        if (m_cdf.empty()) return std::nullopt;
        const std::size_t i = choose(u_select);
        if (i < m_tris.size()) {
            if (!(m_tris[i].probability > 0.0f)) return std::nullopt;
            return m_tris[i].sample_le(u_pos, u_dir, u_side);
        }
        const std::size_t k = i - m_tris.size();
        return std::visit(
            [&](const auto& x) -> std::optional<light_le> {
                using L = std::decay_t<decltype(x)>;
                if constexpr (std::is_same_v<L, environment_slot>)
                    return m_environment.sample_le(u_dir, u_pos, m_bounds.centre, m_bounds.radius, m_probability[i]);
                else if constexpr (std::is_same_v<L, lights::distant_light>)
                    return x.sample_le(u_pos, m_bounds.centre, m_bounds.radius);
                else
                    return x.sample_le(u_dir);
            },
            m_others[k]);
    }

    const bounding_sphere& bounds() const noexcept { return m_bounds; }
    /// \brief The index of the environment's first emission table (= the scene's emitter count).
    std::uint32_t environment_table() const noexcept { return m_environment_table; }

private:
    struct environment_slot {};
    using other = std::variant<lights::point_light, lights::distant_light, environment_slot>;
    static constexpr std::size_t no_slot = std::numeric_limits<std::size_t>::max();

    std::size_t choose(float u) const noexcept {
        const auto it = std::upper_bound(m_cdf.begin(), m_cdf.end(), static_cast<double>(u));
        return std::min(static_cast<std::size_t>(it - m_cdf.begin()), m_cdf.size() - 1);
    }

    bounding_sphere m_bounds;
    std::uint32_t m_environment_table;
    std::vector<lights::triangle> m_tris;
    std::vector<other> m_others;
    std::vector<double> m_cdf;
    std::vector<float> m_probability;
    std::vector<std::int64_t> m_shape_offset;
    lights::environment_light m_environment;
    bool m_has_environment = false;
    std::size_t m_environment_slot = no_slot;
};

}  // namespace iris
