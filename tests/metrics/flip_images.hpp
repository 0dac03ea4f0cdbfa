#pragma once
// Image pairs for the ꟻLIP tests (tests/metrics/flip_test.cpp): deterministic, built from
// integer hashes, so that the same pixels can be handed to the reference implementation of
// ꟻLIP (docs/metrics.md says how the expected values were obtained).
#include <cmath>
#include <cstdint>

#include "iris/image.hpp"

namespace iris::test {

/// \brief A value in [0, 1) from (x, y, k): an integer hash, the same on every machine.
inline float flip_noise(int x, int y, int k) {
    std::uint32_t h = static_cast<std::uint32_t>(x) * 73856093u ^ static_cast<std::uint32_t>(y) * 19349663u ^
                      static_cast<std::uint32_t>(k) * 83492791u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return static_cast<float>(h & 0xffffu) / 65536.0f;
}

/// \brief An HDR "render": a lit gradient with coloured squares and a bright lamp (values to ~40).
inline image flip_hdr_reference(int w, int h) {
    image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float fx = static_cast<float>(x) / static_cast<float>(w), fy = static_cast<float>(y) / static_cast<float>(h);
            float r = 0.05f + 0.6f * fx * fy, g = 0.05f + 0.4f * fy, b = 0.08f + 0.3f * (1.0f - fx);
            if ((x / 12 + y / 12) % 3 == 0) r *= 3.0f, g *= 0.5f;
            const float dx = fx - 0.7f, dy = fy - 0.3f;
            const float lamp = 40.0f * std::exp(-(dx * dx + dy * dy) / 0.002f);
            img.pixels()[static_cast<std::size_t>(y * w + x)] = {r + lamp, g + 0.9f * lamp, b + 0.7f * lamp};
        }
    return img;
}

/// \brief The same with Monte Carlo-like noise: each pixel scaled by a per-channel factor of
/// mean 1 (spread `amount`), plus a few fireflies.
inline image flip_hdr_noisy(const image& ref, float amount, int k) {
    image img = ref;
    for (int y = 0; y < ref.height(); ++y)
        for (int x = 0; x < ref.width(); ++x) {
            auto& p = img.pixels()[static_cast<std::size_t>(y * ref.width() + x)];
            p.r *= 1.0f + amount * (2.0f * flip_noise(x, y, 3 * k) - 1.0f);
            p.g *= 1.0f + amount * (2.0f * flip_noise(x, y, 3 * k + 1) - 1.0f);
            p.b *= 1.0f + amount * (2.0f * flip_noise(x, y, 3 * k + 2) - 1.0f);
            if (flip_noise(x, y, 1000 + k) < 0.004f) p.r += 20.0f, p.g += 18.0f, p.b += 15.0f;
        }
    return img;
}

/// \brief An LDR pair as 8-bit sRGB codes (the reference implementation reads PNG): `code(x, y, c)`.
inline int flip_ldr_code(int x, int y, int c, bool test) {
    const int base = ((x / 6 + y / 6) % 2 ? 190 : 40) + 15 * c + (x * 2 + y) % 30;  // ≤ 249
    if (!test) return base;
    const int shifted = ((x / 6 + (y + 1) / 6) % 2 ? 190 : 40) + 15 * c + (x * 2 + y) % 30;  // an edge moved by a pixel
    const int noise = static_cast<int>(40.0f * flip_noise(x, y, 7 + c)) - 20;
    const int v = (x < 32 ? shifted : base) + noise;
    return v < 0 ? 0 : v > 255 ? 255 : v;
}

}  // namespace iris::test
