#pragma once
/// \file
/// \brief The film: a per-pixel running mean of XYZ over every sample (the paper's
/// accumulation), with non-finite samples dropped and counted, never accumulated.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "iris/image.hpp"
#include "iris/spectrum/color.hpp"

namespace iris {

class film {
public:
    film(int width, int height)
        : m_width(width), m_height(height), m_sum(static_cast<std::size_t>(width) * static_cast<std::size_t>(height)),
          m_count(m_sum.size(), 0), m_dropped(m_sum.size(), 0) {}

    /// \brief Memory per pixel: the XYZ sums (3 doubles) and two 32-bit counters.
    static constexpr std::size_t bytes_per_pixel = sizeof(xyz) + 2 * sizeof(std::uint32_t);

    int width() const noexcept { return m_width; }
    int height() const noexcept { return m_height; }

    /// \brief Add one sample to pixel `i`; a NaN/Inf sample still counts as a sample taken
    /// (so the mean is not biased upwards) but contributes 0, and is counted.
    void add(std::size_t i, const xyz& v) noexcept {
        ++m_count[i];
        if (std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) {
            m_sum[i].x += v.x;
            m_sum[i].y += v.y;
            m_sum[i].z += v.z;
        } else {
            ++m_dropped[i];
        }
    }

    /// \brief Mean XYZ of pixel `i` (0 before its first sample).
    xyz mean(std::size_t i) const noexcept {
        const double n = static_cast<double>(m_count[i]);
        return n > 0 ? xyz{m_sum[i].x / n, m_sum[i].y / n, m_sum[i].z / n} : xyz{};
    }

    /// \brief Non-finite samples dropped so far, over all pixels.
    std::uint64_t dropped() const noexcept {
        std::uint64_t n = 0;
        for (auto d : m_dropped) n += d;
        return n;
    }
    std::uint32_t samples(std::size_t i) const noexcept { return m_count[i]; }

    /// \brief The running mean as linear sRGB.
    image to_image() const {
        image img(m_width, m_height);
        for (std::size_t i = 0; i < m_sum.size(); ++i) {
            const rgb c = xyz_to_linear_srgb(mean(i));
            img.pixels()[i] = {static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b)};
        }
        return img;
    }

private:
    int m_width, m_height;
    std::vector<xyz> m_sum;  // double precision: 1e6 spp of float-sized values stay exact enough
    std::vector<std::uint32_t> m_count;
    std::vector<std::uint32_t> m_dropped;
};

}  // namespace iris
