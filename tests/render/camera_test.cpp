// The pinhole camera seen from the light's side: `raster` inverts `direction`, the
// importance integrates to one per pixel, and the direction pdf is the density of the
// pixel's primary rays.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include <iris/render/camera.hpp>
#include <iris/render/random.hpp>

namespace {

iris::pinhole_camera tilted_camera() {
    iris::pinhole_camera c;
    c.position = {0.3f, 1.2f, 4.0f};
    c.look_at = {-0.2f, 0.4f, 0.0f};
    c.up = {0.0f, 1.0f, 0.0f};
    c.fov_y_degrees = 50.0f;
    return c;
}

glm::vec3 uniform_sphere(glm::vec2 u) {
    const float z = 1.0f - 2.0f * u.x, r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * std::numbers::pi_v<float> * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

}  // namespace

TEST(Camera, RasterInvertsDirection) {
    const iris::camera_rays cam(tilted_camera(), 64, 40);
    iris::sample_stream rng(3, 1, 4);
    for (int i = 0; i < 5000; ++i) {
        const int x = static_cast<int>(rng.next() * 64), y = static_cast<int>(rng.next() * 40);
        const glm::vec2 j = rng.next2();
        const auto r = cam.raster(cam.direction(x, y, j));
        ASSERT_TRUE(r.has_value()) << x << " " << y;
        EXPECT_NEAR(r->x, static_cast<float>(x) + j.x, 2e-3f);
        EXPECT_NEAR(r->y, static_cast<float>(y) + j.y, 2e-3f);
    }
    const glm::vec3 fwd = glm::normalize(tilted_camera().look_at - tilted_camera().position);
    EXPECT_FALSE(cam.raster(-fwd).has_value());                                   // behind
    EXPECT_FALSE(cam.raster(glm::normalize(fwd + glm::vec3(0, 5, 0))).has_value());  // above the image
    EXPECT_EQ(cam.importance(-fwd), 0.0f);
}

// ∫ W_e cos θ dω over the whole image is the number of pixels (one per pixel), and so is
// ∫ pdf dω of the primary rays' density (one per pixel: `direction` with uniform jitter),
// by uniform sampling of the sphere (N = 4·10⁶, fixed seed), each sample counted where
// `raster` puts it in the image. Tolerance: 4.4 standard errors of the estimate (two-sided
// α = 10⁻⁵ per check); power: a 2 % error of either normalisation is detected.
TEST(Camera, ImportanceAndPdfIntegrateToOnePerPixel) {
    const int w = 32, h = 24;
    const iris::camera_rays cam(tilted_camera(), w, h);
    const glm::vec3 fwd = glm::normalize(tilted_camera().look_at - tilted_camera().position);
    iris::counter_rng rng(17, 0);
    const int n = 4000000;
    double sum[2] = {}, sum2[2] = {};
    for (int i = 0; i < n; ++i) {
        const glm::vec3 d = uniform_sphere({rng.next(), rng.next()});
        if (!cam.raster(d)) continue;
        const double v[2] = {4.0 * std::numbers::pi * cam.importance(d) * glm::dot(d, fwd),
                             4.0 * std::numbers::pi * cam.pdf_direction(d)};
        for (int k = 0; k < 2; ++k) {
            sum[k] += v[k];
            sum2[k] += v[k] * v[k];
        }
    }
    for (int k = 0; k < 2; ++k) {
        const double mean = sum[k] / n, se = std::sqrt((sum2[k] / n - mean * mean) / (n - 1));
        EXPECT_NEAR(mean, static_cast<double>(w * h), 4.4 * se) << (k ? "pdf" : "importance") << ", se " << se;
        EXPECT_LT(4.4 * se, 0.02 * w * h);
    }
    // a pixel's own rays: pdf is their density, W_e cos θ / pdf = 1 on each
    iris::sample_stream s(5, 2, 7);
    for (int i = 0; i < 1000; ++i) {
        const glm::vec3 d = cam.direction(static_cast<int>(s.next() * w), static_cast<int>(s.next() * h), s.next2());
        EXPECT_NEAR(cam.importance(d) * glm::dot(d, fwd) / cam.pdf_direction(d), 1.0, 1e-5);
    }
}
