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

#include "iris/render/scene.hpp"

namespace iris {

/// \brief The scene's emitted spectral power Φ(λ), up to one constant: each emitter's
/// radiance L_e(λ) times π times the area of its triangles (twice for two-sided ones),
/// plus a uniform environment's radiance times π · 4πR² (the power it sends into the
/// scene's bounding sphere, radius R). Zero for a scene without emitters.
class emitted_power {
public:
    explicit emitted_power(const scene_desc& s) : m_scene(&s), m_weight(s.emitters.size(), 0.0) {
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
        for (const auto& shape : s.shapes) {
            for (const auto& p : shape.mesh.positions) {
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
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
        if (s.environment) {
            const double r = lo.x <= hi.x ? 0.5 * static_cast<double>(glm::length(hi - lo)) : 1.0;
            m_environment = std::numbers::pi * 4.0 * std::numbers::pi * r * r;
        }
    }

    double operator()(double lambda_nm) const noexcept {
        double v = 0.0;
        for (std::size_t e = 0; e < m_weight.size(); ++e)
            if (m_weight[e] > 0.0) v += m_weight[e] * m_scene->emitters[e].radiance(lambda_nm);
        if (m_scene->environment) v += m_environment * m_scene->environment->radiance(lambda_nm);
        return v;
    }

private:
    const scene_desc* m_scene;
    std::vector<double> m_weight;  ///< π · area (· 2) per emitter
    double m_environment = 0.0;
};

}  // namespace iris
