#pragma once
/// \file
/// \brief A film's spectral layer (iris/render/film.hpp) as an EXR's spectral channels:
/// what `iris-render --spectral` and the Python `Renderer.save` write beside RGB.

#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include "iris/exr/exr.hpp"
#include "iris/render/film.hpp"

namespace iris::renderer {

/// \brief The film's mean spectral radiance per band (film::spectral_mean) as float
/// channels at the bands' centres; empty without a spectral layer.
inline exr::spectral_image spectral_channels(const film& f) {
    exr::spectral_image out;
    const film::spectral_parts* sp = f.spectral_state();
    if (!sp) return out;
    const auto n = static_cast<std::size_t>(sp->bands.count);
    for (int o = 0; o < sp->bands.count; ++o) out.wavelengths.push_back(sp->bands.centre(o));
    const std::size_t pixels = f.sums().size();
    out.values.resize(pixels * n);
    std::vector<double> row(n);
    for (std::size_t i = 0; i < pixels; ++i) {
        f.spectral_mean(i, row.data());
        for (std::size_t o = 0; o < n; ++o) out.values[i * n + o] = static_cast<float>(row[o]);
    }
    return out;
}

/// \brief The attributes a spectral image adds to `image_metadata`'s: the bands' range and
/// width, and the samples whose spectral row was dropped (out of range while their XYZ was
/// not; film.hpp). Nothing without a spectral layer.
inline void add_spectral_metadata(const film& f, exr::metadata& m) {
    const film::spectral_parts* sp = f.spectral_state();
    if (!sp) return;
    char text[160];
    std::snprintf(text, sizeof text, "%d bands of %g nm over %g-%g nm, each channel the band's mean, named at its centre",
                  sp->bands.count, sp->bands.width(), sp->bands.lambda_min, sp->bands.lambda_max);
    m["iris:spectral_bands"] = text;
    m["iris:spectral_dropped"] = std::to_string(sp->dropped);
}

}  // namespace iris::renderer
