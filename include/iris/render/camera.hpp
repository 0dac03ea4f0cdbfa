#pragma once
/// \file
/// \brief Primary rays of a pinhole camera (box pixel filter), and the camera's importance
/// for estimators that reach it from the light's side.

#include <cmath>
#include <numbers>
#include <optional>

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
        m_pixel_area = 4.0f * tan_half * tan_half * aspect / (static_cast<float>(width) * static_cast<float>(height));
    }

    const glm::vec3& origin() const noexcept { return m_origin; }
    int width() const noexcept { return m_width; }
    int height() const noexcept { return m_height; }

    /// \brief Unit direction through image position (x + jitter.x, y + jitter.y); y = 0 is the top row.
    glm::vec3 direction(int x, int y, glm::vec2 jitter) const noexcept {
        const float sx = 2.0f * (static_cast<float>(x) + jitter.x) / static_cast<float>(m_width) - 1.0f;
        const float sy = 1.0f - 2.0f * (static_cast<float>(y) + jitter.y) / static_cast<float>(m_height);
        return glm::normalize(m_fwd + sx * m_right + sy * m_up);
    }

    /// \brief The image position (x, y) in pixels, continuous (y = 0 the top edge), that unit
    /// direction d from the origin passes through: the inverse of `direction`. Nothing when
    /// d misses the image (or points away from it).
    std::optional<glm::vec2> raster(const glm::vec3& d) const noexcept {
        const float c = glm::dot(d, m_fwd);
        if (!(c > 0.0f)) return std::nullopt;
        const glm::vec3 p = d / c - m_fwd;  // on the image plane at distance 1
        const float sx = glm::dot(p, m_right) / glm::dot(m_right, m_right);
        const float sy = glm::dot(p, m_up) / glm::dot(m_up, m_up);
        const float x = 0.5f * (sx + 1.0f) * static_cast<float>(m_width);
        const float y = 0.5f * (1.0f - sy) * static_cast<float>(m_height);
        if (!(x >= 0.0f && x < static_cast<float>(m_width) && y >= 0.0f && y < static_cast<float>(m_height)))
            return std::nullopt;
        return glm::vec2(x, y);
    }

    /// \brief The importance W_e of the pixel that unit direction d passes through (d inside
    /// the image): 1 / (A_p cos⁴θ), A_p a pixel's area on the image plane at distance 1 and θ
    /// the angle to the view axis — so that ∫ W_e cos θ dω over a pixel's directions is 1 and
    /// a pixel's value is the mean radiance over its footprint, the box filter's.
    float importance(const glm::vec3& d) const noexcept {
        const float c = glm::dot(d, m_fwd);
        return c > 0.0f ? 1.0f / (m_pixel_area * c * c * c * c) : 0.0f;
    }

    /// \brief The solid-angle density of `direction(x, y, u)` for uniform u, at the direction
    /// d it gives: 1 / (A_p cos³θ) (uniform on the pixel's footprint on the image plane).
    float pdf_direction(const glm::vec3& d) const noexcept {
        const float c = glm::dot(d, m_fwd);
        return c > 0.0f ? 1.0f / (m_pixel_area * c * c * c) : 0.0f;
    }

private:
    int m_width, m_height;
    glm::vec3 m_origin, m_fwd, m_right, m_up;
    float m_pixel_area = 0.0f;  ///< one pixel on the image plane at distance 1
};

}  // namespace iris
