#pragma once
/// \file
/// \brief Image textures at a hit: the bilinear lookup of an `image_texture` at uv with its
/// wrap mode, and the reflectance of a material at a surface interaction as a mix of
/// spectra (`emission_ref`'s form: up to three tables and their weights).
///
/// A reflectance texel holds the weights of the three reflectance basis spectra of
/// iris/spectrum/rgb_upsampling.hpp (a partition of unity: weights in [0, 1] give a
/// reflectance in [0, 1]). The basis is linear, so the bilinear mix of four texels' weights
/// is the weights of the bilinear mix of their spectra, and a lookup costs the C hero
/// wavelengths three table reads and the B term's bins three precomputed rows mixed — the
/// same as an environment texel (docs/method.md, "spectra at the hit"). An untextured
/// material is its own one table with weight 1, exactly as before textures existed.
///
/// Convention (pbrt-v4's): u runs left to right, v bottom to top; texel (x, y) (row 0 at
/// the top) covers [x, x+1]/W × [1 − (y+1)/H, 1 − y/H] and its value sits at its centre.

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <variant>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "iris/render/scene.hpp"
#include "iris/spectrum/color.hpp"
#include "iris/spectrum/rgb_upsampling.hpp"
#include "iris/spectrum/tabulated.hpp"

namespace iris {

namespace detail {
/// \brief Texel index i (any integer) of a side of n texels under `wrap`.
inline int wrap_texel(int i, int n, texture_wrap wrap) noexcept {
    switch (wrap) {
        case texture_wrap::clamp: return i < 0 ? 0 : (i >= n ? n - 1 : i);
        case texture_wrap::mirror: {
            const int period = 2 * n;
            int m = i % period;
            if (m < 0) m += period;
            return m < n ? m : period - 1 - m;
        }
        case texture_wrap::repeat:
        default: {
            int m = i % n;
            return m < 0 ? m + n : m;
        }
    }
}
}  // namespace detail

/// \brief The texture's weights at the surface's uv (mapped by the texture's `uv_scale` and
/// `uv_offset`), bilinear between the four nearest texel centres.
/// A uv that is not finite gives texel (0, 0)'s value (never an out-of-range read).
inline glm::vec3 lookup(const image_texture& tex, glm::vec2 uv) noexcept {
    uv = uv * tex.uv_scale + tex.uv_offset;
    const float fx = uv.x * static_cast<float>(tex.width) - 0.5f;
    const float fy = (1.0f - uv.y) * static_cast<float>(tex.height) - 0.5f;
    if (!(std::fabs(fx) < 1e9f) || !(std::fabs(fy) < 1e9f)) return tex.weights[0];
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float tx = fx - x0f, ty = fy - y0f;
    const int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
    const int xa = detail::wrap_texel(x0, tex.width, tex.wrap), xb = detail::wrap_texel(x0 + 1, tex.width, tex.wrap);
    const int ya = detail::wrap_texel(y0, tex.height, tex.wrap), yb = detail::wrap_texel(y0 + 1, tex.height, tex.wrap);
    const auto at = [&](int x, int y) -> const glm::vec3& {
        return tex.weights[static_cast<std::size_t>(y) * static_cast<std::size_t>(tex.width) + static_cast<std::size_t>(x)];
    };
    return (1.0f - ty) * ((1.0f - tx) * at(xa, ya) + tx * at(xb, ya)) + ty * ((1.0f - tx) * at(xa, yb) + tx * at(xb, yb));
}

/// \brief The three reflectance basis spectra (red, green, blue) as tables on 1 nm nodes
/// over 360–830 nm, `outside::clamp` — the rows a texel's weights mix.
inline std::array<tabulated_spectrum, 3> reflectance_basis() {
    std::array<std::vector<double>, 3> v;
    std::vector<double> lambda;
    for (std::size_t i = 0; i < cie::cmf_samples; ++i) {
        const double x = cie::cmf_lambda_min + static_cast<double>(i);
        lambda.push_back(x);
        v[0].push_back(rgb_upsampling::red_basis(x));
        v[1].push_back(rgb_upsampling::green_basis(x));
        v[2].push_back(rgb_upsampling::blue_basis(x));
    }
    return {tabulated_spectrum(lambda, std::move(v[0]), outside::clamp),
            tabulated_spectrum(lambda, std::move(v[1]), outside::clamp),
            tabulated_spectrum(std::move(lambda), std::move(v[2]), outside::clamp)};
}

/// \brief The texture weights of material `m`'s reflectance at uv, or nothing for an
/// untextured material.
inline std::optional<glm::vec3> texture_weights(const scene_desc& scene, const material_desc& m, glm::vec2 uv) noexcept {
    if (const auto* d = diffuse_part(m))
        if (d->texture) return lookup(scene.textures[*d->texture], uv);
    return std::nullopt;
}

/// \brief Whether material `m` reads a texture.
inline bool is_textured(const material_desc& m) noexcept {
    const auto* d = diffuse_part(m);
    return d && d->texture.has_value();
}

}  // namespace iris
