#pragma once
/// \file
/// \brief Input checks shared by the image metrics: equal sizes, non-empty, finite values.
/// Every metric throws `std::invalid_argument` for input it cannot measure, so a NaN from a
/// broken render is reported instead of silently turning the score into NaN.

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>

#include "iris/image.hpp"

namespace iris::detail {

/// \brief "W×H" as written in error messages (ASCII x, so it greps and prints everywhere).
inline std::string size_string(const image& img) {
    return std::to_string(img.width()) + "x" + std::to_string(img.height());
}

/// \brief Throws unless `a` and `b` have the same, non-zero size.
inline void require_same_size(const image& a, const image& b, std::string_view metric) {
    if (a.width() != b.width() || a.height() != b.height())
        throw std::invalid_argument(std::string(metric) + ": image sizes differ: " + size_string(a) + " vs " +
                                    size_string(b));
    if (a.empty()) throw std::invalid_argument(std::string(metric) + ": the images are empty (" + size_string(a) + ")");
}

/// \brief Throws at the first NaN or ±Inf channel value, naming the pixel. Metrics refuse
/// non-finite input: a NaN in a render is a bug to surface, not a value to average.
inline void require_finite(const image& img, std::string_view metric, std::string_view which) {
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) {
            const rgb_pixel& p = img(x, y);
            if (!std::isfinite(p.r) || !std::isfinite(p.g) || !std::isfinite(p.b))
                throw std::invalid_argument(std::string(metric) + ": " + std::string(which) +
                                            " image has a non-finite value (NaN or Inf) at pixel (" +
                                            std::to_string(x) + ", " + std::to_string(y) + ")");
        }
}

/// \brief The checks every two-image metric starts with.
inline void require_comparable(const image& a, const image& b, std::string_view metric) {
    require_same_size(a, b, metric);
    require_finite(a, metric, "first");
    require_finite(b, metric, "second");
}

/// \brief Channel accessors, so per-channel loops read as loops over r, g, b.
inline constexpr std::array<float rgb_pixel::*, 3> rgb_channels{&rgb_pixel::r, &rgb_pixel::g, &rgb_pixel::b};

}  // namespace iris::detail
