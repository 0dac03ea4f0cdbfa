// No NaN or Inf reaches the film: a test integrator that returns NaN, +Inf and −Inf in
// chosen pixels, run through the renderer's own progressive loop
// (modules/renderer/src/render_loop.hpp, the code every preset runs). Those samples must be
// counted (status::nan_inf, film::dropped), contribute nothing, and still count as samples
// taken, so the pixel's mean is not biased upwards; the image stays finite.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <iris/render/camera.hpp>
#include <iris/render/film.hpp>
#include <iris/render/integrator.hpp>

#include "render_loop.hpp"

namespace {

struct no_tracer {};
struct no_distribution {};

constexpr int width = 8, height = 4;

/// \brief XYZ = (1, 2, 3) everywhere, except: pixel 5 NaN in X, pixel 6 +Inf in Y, pixel 7
/// −Inf in Z, on every sample; pixel 9 NaN in all three on about half its samples. The
/// pixel is recovered from the camera direction (camera at the origin looking down −z).
class poisoned_integrator {
public:
    explicit poisoned_integrator(const iris::pinhole_camera& c) : m_tan(std::tan(0.5f * c.fov_y_degrees * 3.14159265f / 180.0f)) {}

    iris::path_sample trace(const no_tracer&, glm::vec3, glm::vec3 d, const no_distribution&, float,
                            iris::sample_stream& rng, iris::spectral_row* = nullptr) const noexcept {
        const float sx = (d.x / -d.z) / (m_tan * static_cast<float>(width) / static_cast<float>(height));
        const float sy = (d.y / -d.z) / m_tan;
        const int x = static_cast<int>(std::floor((sx + 1.0f) * 0.5f * width));
        const int y = static_cast<int>(std::floor((1.0f - sy) * 0.5f * height));
        const int pixel = y * width + x;
        constexpr double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
        iris::path_sample s;
        s.value = {1.0, 2.0, 3.0};
        if (pixel == 5) s.value.x = nan;
        if (pixel == 6) s.value.y = inf;
        if (pixel == 7) s.value.z = -inf;
        if (pixel == 9 && rng.next() < 0.5f) s.value = {nan, nan, nan};
        return s;
    }

private:
    float m_tan;
};

}  // namespace

TEST(FilmGuard, NonFiniteSamplesAreDroppedCountedAndNeverReachTheImage) {
    iris::pinhole_camera c;
    c.position = {0, 0, 0};
    c.look_at = {0, 0, -1};
    c.fov_y_degrees = 60.0f;
    c.width = width;
    c.height = height;
    const iris::camera_rays cam(c, width, height);
    const poisoned_integrator integ(c);
    iris::renderer::options opt;
    opt.spp = 64;
    opt.threads = 2;
    opt.tile_size = 3;
    iris::film f(width, height);
    iris::renderer::status st;
    st.isa = "baseline";
    static constexpr no_distribution none{};
    iris::renderer::detail::run_passes<iris::renderer::detail::isa::baseline>(integ, no_tracer{}, cam, opt,
                                       [&](int) { return std::pair<float, const no_distribution&>(1.0f, none); }, f, st, {});
    ASSERT_EQ(st.spp_done, opt.spp);
    // pixel 9: k of its 64 samples were NaN; its mean is (64 − k)/64 · (1, 2, 3)
    const double kept = f.mean(9).x * opt.spp;
    const auto k = static_cast<std::uint64_t>(std::llround(opt.spp - kept));
    EXPECT_NEAR(kept, std::round(kept), 1e-9);
    EXPECT_GT(k, 0u);
    EXPECT_LT(k, static_cast<std::uint64_t>(opt.spp));
    EXPECT_EQ(f.dropped(), 3u * static_cast<std::uint64_t>(opt.spp) + k);
    EXPECT_EQ(st.nan_inf, f.dropped());
    for (std::size_t i = 0; i < static_cast<std::size_t>(width * height); ++i) {
        EXPECT_EQ(f.samples(i), static_cast<std::uint32_t>(opt.spp)) << "pixel " << i;
        const auto m = f.mean(i);
        ASSERT_TRUE(std::isfinite(m.x) && std::isfinite(m.y) && std::isfinite(m.z)) << "pixel " << i;
        if (i == 5 || i == 6 || i == 7) {
            EXPECT_EQ(m.x + m.y + m.z, 0.0) << "pixel " << i << ": every sample dropped";
        } else if (i != 9) {
            EXPECT_EQ(m.y, 2.0) << "pixel " << i;
        }
    }
    const iris::image img = f.to_image();
    for (const auto& p : img.pixels())
        ASSERT_TRUE(std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b));
}
