#pragma once
/// \file
/// \brief The film: a per-pixel mean of XYZ over every sample (the paper's accumulation),
/// summed exactly, with non-finite and out-of-range samples dropped and counted, never
/// accumulated.
///
/// **Exact accumulation.** Each sample's X, Y and Z are added as 128-bit fixed-point
/// integers with 56 fractional bits (`fraction_bits`): v · 2^56 rounded toward zero, so a
/// sample loses less than 2^-56 ≈ 1.4·10^-17 in absolute terms (relative 1.8·10^-13 at
/// 7.8·10^-5, 10^-15 at 0.01). Integer sums are associative: a pixel's sums, and so its
/// image, do not depend on the order its samples were added in — by one thread or several,
/// in one run or split over runs (resume) or processes (MPI) — only on which samples.
/// **Range:** a sample with |X|, |Y| or |Z| ≥ 2^39 ≈ 5.5·10^11 (`max_sample`) is dropped and
/// counted like a NaN; below it, 2^32 − 1 samples per pixel (the counter's limit) cannot
/// overflow the sums: 2^39 · 2^56 · 2^32 = 2^127. The mean is the sum converted to double
/// once (rounded to nearest) and divided by the sample count.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "iris/image.hpp"
#include "iris/spectrum/color.hpp"

namespace iris {

__extension__ typedef __int128 exact_int;  ///< GCC and Clang; the film's only non-standard type

/// \brief A pixel's exact sums: X, Y, Z in fixed point (film::fraction_bits fractional bits).
struct exact_xyz {
    exact_int x = 0, y = 0, z = 0;
    friend bool operator==(const exact_xyz&, const exact_xyz&) = default;
};

class film {
public:
    static constexpr int fraction_bits = 56;
    static constexpr double max_sample = 0x1p39;

    film(int width, int height)
        : m_width(width), m_height(height), m_sum(static_cast<std::size_t>(width) * static_cast<std::size_t>(height)),
          m_count(m_sum.size(), 0), m_dropped(m_sum.size(), 0) {}

    /// \brief Memory per pixel: the exact XYZ sums (3 × 16 bytes) and two 32-bit counters.
    static constexpr std::size_t bytes_per_pixel = sizeof(exact_xyz) + 2 * sizeof(std::uint32_t);

    int width() const noexcept { return m_width; }
    int height() const noexcept { return m_height; }

    /// \brief Whether a sample's value can be summed: finite and |v| < max_sample.
    static constexpr bool summable(double v) noexcept { return std::fabs(v) < max_sample; }  // false for NaN

    /// \brief v in fixed point, rounded toward zero (exact for |v| < max_sample): the same as
    /// static_cast<exact_int>(v · 2^56), without the library call that conversion is (≈ 20 ns
    /// for three). w = v · 2^56 is exact; its high part h = trunc(w · 2^-40) and the rest
    /// w − h · 2^40 (exact: it is w's low mantissa bits, |·| < 2^40) have the sign of w, so
    /// trunc(w) = h · 2^40 + trunc(rest), each part a 64-bit conversion.
    static exact_int to_fixed(double v) noexcept {
        const double w = v * 0x1p56;
        const auto h = static_cast<std::int64_t>(w * 0x1p-40);
        const auto rest = static_cast<std::int64_t>(w - static_cast<double>(h) * 0x1p40);
        return static_cast<exact_int>(h) * (std::int64_t{1} << 40) + rest;
    }

    /// \brief Add one sample to pixel `i`; a NaN/Inf or out-of-range sample still counts as
    /// a sample taken (so the mean is not biased upwards) but contributes 0, and is counted.
    void add(std::size_t i, const xyz& v) noexcept {
        ++m_count[i];
        if (summable(v.x) && summable(v.y) && summable(v.z)) {
            m_sum[i].x += to_fixed(v.x);
            m_sum[i].y += to_fixed(v.y);
            m_sum[i].z += to_fixed(v.z);
        } else {
            ++m_dropped[i];
        }
    }

    /// \brief Mean XYZ of pixel `i` (0 before its first sample).
    xyz mean(std::size_t i) const noexcept {
        const double n = static_cast<double>(m_count[i]);
        if (n == 0) return {};
        const auto v = [&](exact_int s) { return static_cast<double>(s) * 0x1p-56 / n; };
        return {v(m_sum[i].x), v(m_sum[i].y), v(m_sum[i].z)};
    }

    /// \brief Samples dropped so far (non-finite or out of range), over all pixels.
    std::uint64_t dropped() const noexcept {
        std::uint64_t n = 0;
        for (auto d : m_dropped) n += d;
        return n;
    }
    std::uint32_t samples(std::size_t i) const noexcept { return m_count[i]; }

    /// \brief Pixel `i`'s exact sums.
    const exact_xyz& sum(std::size_t i) const noexcept { return m_sum[i]; }

    /// \brief The whole state, pixel by pixel (row-major): what a checkpoint stores and
    /// what ranks exchange. `from_parts` rebuilds a film from it.
    std::span<const exact_xyz> sums() const noexcept { return m_sum; }
    std::span<const std::uint32_t> counts() const noexcept { return m_count; }
    std::span<const std::uint32_t> dropped_counts() const noexcept { return m_dropped; }

    /// \brief A film with the given state. \throws std::invalid_argument if a part does not
    /// have width · height entries or a pixel has more dropped samples than samples.
    static film from_parts(int width, int height, std::vector<exact_xyz> sums, std::vector<std::uint32_t> counts,
                           std::vector<std::uint32_t> dropped) {
        film f(0, 0);
        const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
        if (width < 0 || height < 0 || sums.size() != n || counts.size() != n || dropped.size() != n)
            throw std::invalid_argument("film::from_parts: the parts do not have width x height entries");
        for (std::size_t i = 0; i < n; ++i)
            if (dropped[i] > counts[i]) throw std::invalid_argument("film::from_parts: more dropped samples than samples");
        f.m_width = width;
        f.m_height = height;
        f.m_sum = std::move(sums);
        f.m_count = std::move(counts);
        f.m_dropped = std::move(dropped);
        return f;
    }

    /// \brief Add another film's samples to this one's, exactly: the result is the film
    /// that took both films' samples (in any order). \throws std::invalid_argument for
    /// another size, std::overflow_error if a pixel's sample count would pass 2^32 − 1.
    void merge(const film& other) {
        if (other.m_width != m_width || other.m_height != m_height)
            throw std::invalid_argument("film::merge: the films differ in size");
        for (std::size_t i = 0; i < m_sum.size(); ++i)
            if (other.m_count[i] > UINT32_MAX - m_count[i]) throw std::overflow_error("film::merge: more than 2^32 - 1 samples in a pixel");
        for (std::size_t i = 0; i < m_sum.size(); ++i) {
            m_sum[i].x += other.m_sum[i].x;
            m_sum[i].y += other.m_sum[i].y;
            m_sum[i].z += other.m_sum[i].z;
            m_count[i] += other.m_count[i];
            m_dropped[i] += other.m_dropped[i];
        }
    }

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
    std::vector<exact_xyz> m_sum;
    std::vector<std::uint32_t> m_count;
    std::vector<std::uint32_t> m_dropped;
};

}  // namespace iris
