#pragma once
/// \file
/// \brief `image`: a width × height grid of linear RGB (float) pixels, row-major,
/// top row first. The common currency of the film, the EXR module and the metrics.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace iris {

struct rgb_pixel {
    float r = 0, g = 0, b = 0;
    friend constexpr bool operator==(const rgb_pixel&, const rgb_pixel&) = default;
};

class image {
public:
    image() = default;
    /// \throws std::invalid_argument for negative sizes.
    image(int width, int height) : m_width(width), m_height(height) {
        if (width < 0 || height < 0)
            throw std::invalid_argument("image size must be non-negative, got " + std::to_string(width) + "x" +
                                        std::to_string(height));
        m_pixels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    }

    int width() const noexcept { return m_width; }
    int height() const noexcept { return m_height; }
    std::size_t pixel_count() const noexcept { return m_pixels.size(); }
    bool empty() const noexcept { return m_pixels.empty(); }

    rgb_pixel& operator()(int x, int y) noexcept { return m_pixels[index(x, y)]; }
    const rgb_pixel& operator()(int x, int y) const noexcept { return m_pixels[index(x, y)]; }
    std::vector<rgb_pixel>& pixels() noexcept { return m_pixels; }
    const std::vector<rgb_pixel>& pixels() const noexcept { return m_pixels; }

    friend bool operator==(const image&, const image&) = default;

private:
    std::size_t index(int x, int y) const noexcept {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(m_width) + static_cast<std::size_t>(x);
    }
    int m_width = 0;
    int m_height = 0;
    std::vector<rgb_pixel> m_pixels;
};

}  // namespace iris
