#pragma once
/// \file
/// \brief All image metrics (MSE, relMSE, SSIM, max |a − b|) and `compare`, which computes
/// them together for a test image against a reference; `bias_variance` splits the MSE of
/// several runs into variance and squared bias. Definitions: docs/metrics.md.

#include <cmath>
#include <cstddef>
#include <limits>

#include "iris/image.hpp"
#include "iris/metrics/bias_variance.hpp"
#include "iris/metrics/common.hpp"
#include "iris/metrics/mse.hpp"
#include "iris/metrics/ssim.hpp"

namespace iris {

/// \brief Every metric of one image against a reference.
struct image_metrics {
    double mse = 0;      ///< `mse(image, reference)`
    double relmse = 0;   ///< `relmse(image, reference)` with ε = `relmse_default_epsilon`
    double ssim = 0;     ///< `ssim(image, reference)`; NaN when the images are smaller than 11 × 11
    double max_abs = 0;  ///< `max_abs(image, reference)`
    std::size_t pixels = 0;  ///< pixels per image (width · height)
};

/// \brief All metrics of `img` against `reference`. SSIM is undefined for images with a
/// side shorter than the 11-pixel window; `compare` reports it as quiet NaN there (instead
/// of throwing like `ssim`) so the pixel-wise metrics of small crops stay available.
/// \throws std::invalid_argument for different or zero sizes and NaN/Inf values.
inline image_metrics compare(const image& img, const image& reference) {
    detail::require_comparable(img, reference, "compare");
    image_metrics m;
    m.mse = mse(img, reference);
    m.relmse = relmse(img, reference);
    m.max_abs = max_abs(img, reference);
    m.ssim = img.width() >= ssim_window && img.height() >= ssim_window ? ssim(img, reference)
                                                                       : std::numeric_limits<double>::quiet_NaN();
    m.pixels = img.pixel_count();
    return m;
}

}  // namespace iris
