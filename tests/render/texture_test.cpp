// The image-texture lookup against hand-computed values: texel centres return the texel,
// bilinear between them, each wrap mode outside [0, 1]², v pointing up (row 0 at the top),
// non-finite uv never reading out of range; and the reflectance basis a texel mixes is a
// partition of unity at every node.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <iris/render/texture.hpp>

namespace {

/// 4 × 2 texels, texel (x, y) = (x, y, 10x + y) so every lookup can be read back.
iris::image_texture numbered(iris::texture_wrap wrap) {
    iris::image_texture t;
    t.width = 4;
    t.height = 2;
    t.wrap = wrap;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) t.weights.emplace_back(x, y, 10 * x + y);
    return t;
}

/// uv of texel (x, y)'s centre.
glm::vec2 centre(const iris::image_texture& t, float x, float y) {
    return {(x + 0.5f) / static_cast<float>(t.width), 1.0f - (y + 0.5f) / static_cast<float>(t.height)};
}

TEST(Texture, TexelCentresAndBilinear) {
    const auto t = numbered(iris::texture_wrap::clamp);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) {
            const glm::vec3 v = iris::lookup(t, centre(t, static_cast<float>(x), static_cast<float>(y)));
            EXPECT_NEAR(v.x, x, 1e-5f);
            EXPECT_NEAR(v.y, y, 1e-5f);  // row 0 at the top: v = 0.75 reads row 0
        }
    // a quarter of the way from texel (1, 0) to (2, 1) on both axes
    const glm::vec3 v = iris::lookup(t, centre(t, 1.25f, 0.25f));
    EXPECT_NEAR(v.x, 1.25f, 1e-5f);
    EXPECT_NEAR(v.y, 0.25f, 1e-5f);
    EXPECT_NEAR(v.z, 12.75f, 1e-4f);
}

TEST(Texture, WrapModes) {
    // u = −1/8 is half a texel left of texel 0's left edge: the centre of texel −1
    const glm::vec2 left{-0.125f, 0.75f};
    EXPECT_NEAR(iris::lookup(numbered(iris::texture_wrap::repeat), left).x, 3.0f, 1e-5f);  // texel −1 → 3
    EXPECT_NEAR(iris::lookup(numbered(iris::texture_wrap::clamp), left).x, 0.0f, 1e-5f);   // → 0
    EXPECT_NEAR(iris::lookup(numbered(iris::texture_wrap::mirror), left).x, 0.0f, 1e-5f);  // −1 → 0
    // u = 1 + 3/8: texel 5 → repeat 1, clamp 3, mirror 2 (4 → 3, 5 → 2)
    const glm::vec2 right{1.375f, 0.75f};
    EXPECT_NEAR(iris::lookup(numbered(iris::texture_wrap::repeat), right).x, 1.0f, 1e-5f);
    EXPECT_NEAR(iris::lookup(numbered(iris::texture_wrap::clamp), right).x, 3.0f, 1e-5f);
    EXPECT_NEAR(iris::lookup(numbered(iris::texture_wrap::mirror), right).x, 2.0f, 1e-5f);
    // far away: repeat is periodic in whole units, mirror in two
    EXPECT_NEAR(iris::lookup(numbered(iris::texture_wrap::repeat), {0.375f + 7.0f, 0.25f - 3.0f}).z, 11.0f, 1e-4f);
    EXPECT_NEAR(iris::lookup(numbered(iris::texture_wrap::mirror), {0.375f - 6.0f, 0.75f + 4.0f}).z, 10.0f, 1e-4f);
    // between texel 3 and the wrapped texel 0 (repeat): their mean
    EXPECT_NEAR(iris::lookup(numbered(iris::texture_wrap::repeat), {1.0f, 0.75f}).x, 1.5f, 1e-5f);
}

TEST(Texture, NonFiniteUvIsSafe) {
    const auto t = numbered(iris::texture_wrap::repeat);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (const glm::vec2 uv : {glm::vec2(nan, 0.5f), glm::vec2(0.5f, inf), glm::vec2(-inf, nan), glm::vec2(3e9f, 0.0f)}) {
        const glm::vec3 v = iris::lookup(t, uv);
        EXPECT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
    }
}

TEST(Texture, BasisIsAPartitionOfUnity) {
    const auto b = iris::reflectance_basis();
    for (double l = 360.0; l <= 830.0; l += 0.5) {
        const double sum = b[0](l) + b[1](l) + b[2](l);
        EXPECT_NEAR(sum, 1.0, 1e-12) << l;
        for (const auto& s : b) EXPECT_GE(s(l), 0.0);
    }
}

}  // namespace
