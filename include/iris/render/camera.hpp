#pragma once
/// \file
/// \brief Primary rays of a pinhole camera (box pixel filter).

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/scene.hpp"

namespace iris {

class camera_rays {
public:
    camera_rays(const pinhole_camera& c, int width, int height) noexcept : m_width(width), m_height(height) {
        m_origin = c.position;
        const glm::vec3 fwd = glm::normalize(c.look_at - c.position);
        const glm::vec3 right = glm::normalize(glm::cross(fwd, c.up));
        const glm::vec3 up = glm::cross(right, fwd);
        const float tan_half = std::tan(0.5f * c.fov_y_degrees * std::numbers::pi_v<float> / 180.0f);
        const float aspect = static_cast<float>(width) / static_cast<float>(height);
        m_fwd = fwd;
        m_right = right * (tan_half * aspect);
        m_up = up * tan_half;
    }

    const glm::vec3& origin() const noexcept { return m_origin; }

    /// \brief Unit direction through image position (x + jitter.x, y + jitter.y); y = 0 is the top row.
    glm::vec3 direction(int x, int y, glm::vec2 jitter) const noexcept {
        const float sx = 2.0f * (static_cast<float>(x) + jitter.x) / static_cast<float>(m_width) - 1.0f;
        const float sy = 1.0f - 2.0f * (static_cast<float>(y) + jitter.y) / static_cast<float>(m_height);
        return glm::normalize(m_fwd + sx * m_right + sy * m_up);
    }

private:
    int m_width, m_height;
    glm::vec3 m_origin, m_fwd, m_right, m_up;
};

}  // namespace iris
