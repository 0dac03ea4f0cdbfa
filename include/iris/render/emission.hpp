#pragma once
/// \file
/// \brief What a scene emits, as one spectrum: the input of automatic window placement
/// (iris/sampling/placement.hpp).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <vector>

#include <glm/glm.hpp>

#include "iris/render/lights.hpp"
#include "iris/render/scene.hpp"

namespace iris {

/// \brief The scene's emitted spectral power Φ(λ), up to one constant: each emissive
/// shape's radiance L_e(λ) times π times the area of its triangles (twice for two-sided
/// ones), each point or spot light's intensity times its solid angle ∫s dω, each distant
/// light's irradiance times πR², and the environment's radiance integrated over the sphere
/// times πR² (π · 4πR² · L for a constant one), R the radius of the scene's bounding sphere
/// (the power these send into it). Zero for a scene without emitters.
class emitted_power {
public:
    explicit emitted_power(const scene_desc& s) : m_scene(&s), m_weight(s.emitters.size(), 0.0) {
        const bounding_sphere bounds(s);
        const double r2 = static_cast<double>(bounds.radius) * static_cast<double>(bounds.radius);
        for (const auto& shape : s.shapes) {
            if (!shape.emitter || *shape.emitter >= s.emitters.size()) continue;
            double area = 0.0;
            for (const auto& t : shape.mesh.triangles) {
                const auto& a = shape.mesh.positions[t[0]];
                const auto& b = shape.mesh.positions[t[1]];
                const auto& c = shape.mesh.positions[t[2]];
                area += 0.5 * static_cast<double>(glm::length(glm::cross(b - a, c - a)));
            }
            m_weight[*shape.emitter] += std::numbers::pi * area * (s.emitters[*shape.emitter].two_sided ? 2.0 : 1.0);
        }
        for (const auto& l : s.lights)
            std::visit(
                [&](const auto& x) {
                    using L = std::decay_t<decltype(x)>;
                    if (x.emitter >= s.emitters.size()) return;
                    if constexpr (std::is_same_v<L, light::distant>)
                        m_weight[x.emitter] += std::numbers::pi * r2;
                    else
                        m_weight[x.emitter] +=
                            std::numbers::pi * static_cast<double>(lights::point_light::from(x).solid_angle_over_pi());
                },
                l);
        if (s.environment) {
            const glm::dvec3 flux = lights::environment_light(*s.environment, 0).integral();
            m_environment = std::numbers::pi * r2 * flux;
        }
    }

    double operator()(double lambda_nm) const noexcept {
        double v = 0.0;
        for (std::size_t e = 0; e < m_weight.size(); ++e)
            if (m_weight[e] > 0.0) v += m_weight[e] * m_scene->emitters[e].radiance(lambda_nm);
        if (const auto& env = m_scene->environment) {
            if (env->map)
                for (std::size_t i = 0; i < 3; ++i) v += m_environment[static_cast<int>(i)] * env->basis[i](lambda_nm);
            else
                v += m_environment[0] * env->radiance(lambda_nm);
        }
        return v;
    }

private:
    const scene_desc* m_scene;
    std::vector<double> m_weight;  ///< per emitter: π · area (· 2), or a light's solid angle (· π R²)
    glm::dvec3 m_environment{0.0}; ///< π R² ∫w_i dω per basis spectrum (the first alone for a constant environment)
};

}  // namespace iris
