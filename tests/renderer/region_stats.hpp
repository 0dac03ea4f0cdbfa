// Per-region means of a render and their standard errors, from the samples of each pass.
// One pass gives every pixel one sample, drawn independently of the other passes (the
// random stream is keyed by the sample index), so a region's per-pass means are
// independent; for presets whose distribution does not change with the sample index (or
// once α = 1) they are identically distributed too, and their spread estimates the
// standard error of the region's mean.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <iris/renderer/renderer.hpp>

namespace iris_test {

/// \brief A region's mean X, Y, Z and the standard error of each.
struct region_estimate {
    std::array<double, 3> mean{}, se{};
    std::size_t passes = 0;
    std::size_t pixels = 0;
};

/// \brief Render with `opt` and return, for each of `regions` regions, the mean over passes
/// [from, spp) of the region's per-pass mean XYZ. `region_of(x, y, width, height)` gives a
/// pixel's region, or −1 for a pixel that does not count.
template <class RegionOf>
std::vector<region_estimate> region_estimates(const iris::scene_desc& scene, const iris::renderer::options& opt,
                                              std::size_t regions, int from, RegionOf&& region_of) {
    std::vector<std::array<double, 3>> sum(regions), sum2(regions), previous(regions);
    std::vector<std::size_t> pixels(regions, 0);
    std::vector<int> region;
    std::size_t passes = 0;
    iris::renderer::hooks h;
    h.on_pass = [&](const iris::film& f, const iris::renderer::status& st) {
        const int w = f.width(), ht = f.height();
        if (region.empty()) {
            region.assign(static_cast<std::size_t>(w * ht), -1);
            for (int y = 0; y < ht; ++y)
                for (int x = 0; x < w; ++x) {
                    const int r = region_of(x, y, w, ht);
                    if (r < 0 || static_cast<std::size_t>(r) >= regions) continue;
                    region[static_cast<std::size_t>(y * w + x)] = r;
                    ++pixels[static_cast<std::size_t>(r)];
                }
        }
        std::vector<std::array<double, 3>> total(regions, {0.0, 0.0, 0.0});
        for (std::size_t i = 0; i < region.size(); ++i) {
            if (region[i] < 0) continue;
            const auto m = f.mean(i);
            const double n = f.samples(i);
            auto& t = total[static_cast<std::size_t>(region[i])];
            t[0] += m.x * n;
            t[1] += m.y * n;
            t[2] += m.z * n;
        }
        if (st.spp_done > from) {
            ++passes;
            for (std::size_t r = 0; r < regions; ++r)
                for (std::size_t c = 0; c < 3; ++c) {
                    if (pixels[r] == 0) continue;
                    const double v = (total[r][c] - previous[r][c]) / static_cast<double>(pixels[r]);
                    sum[r][c] += v;
                    sum2[r][c] += v * v;
                }
        }
        previous = total;
        return true;
    };
    iris::film f(1, 1);
    iris::renderer::render(scene, opt, f, h);
    std::vector<region_estimate> out(regions);
    const double n = static_cast<double>(passes);
    for (std::size_t r = 0; r < regions; ++r) {
        out[r].passes = passes;
        out[r].pixels = pixels[r];
        for (std::size_t c = 0; c < 3; ++c) {
            const double m = sum[r][c] / n;
            const double var = std::max(0.0, (sum2[r][c] / n - m * m) * n / (n - 1.0));
            out[r].mean[c] = m;
            out[r].se[c] = std::sqrt(var / n);
        }
    }
    return out;
}

/// \brief `region_estimates` over an nx × ny grid of equal pixel rectangles (row-major).
inline std::vector<region_estimate> grid_estimates(const iris::scene_desc& scene, const iris::renderer::options& opt,
                                                   int nx, int ny, int from = 0) {
    return region_estimates(scene, opt, static_cast<std::size_t>(nx * ny), from,
                            [&](int x, int y, int w, int h) { return (y * ny / h) * nx + x * nx / w; });
}

/// \brief Two independent estimates of the same regions compared: the largest |z| of the
/// difference of their means, (a − b)/√(se_a² + se_b²), over every region and channel. A
/// region without spread in either counts only if its means differ; a non-finite mean or
/// spread, a different region count, or means that differ without spread give +∞ (a failure).
inline double max_abs_z(const std::vector<region_estimate>& a, const std::vector<region_estimate>& b) {
    constexpr double fail = std::numeric_limits<double>::infinity();
    if (a.size() != b.size()) return fail;
    double worst = 0.0;
    for (std::size_t r = 0; r < a.size(); ++r)
        for (std::size_t c = 0; c < 3; ++c) {
            const double se = std::hypot(a[r].se[c], b[r].se[c]), d = std::fabs(a[r].mean[c] - b[r].mean[c]);
            if (!std::isfinite(se) || !std::isfinite(d)) return fail;
            if (se > 0.0) worst = std::fmax(worst, d / se);
            else if (d > 0.0) return fail;
        }
    return worst;
}

/// \brief The two-sided standard normal quantile z with P(|Z| > z) = p (bisection on erfc;
/// enough for thresholds).
inline double normal_quantile_two_sided(double p) {
    double lo = 0.0, hi = 40.0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// \brief The per-test threshold for m tests at family-wise error rate alpha (Šidák).
inline double sidak_z(double alpha, std::size_t m) {
    return normal_quantile_two_sided(1.0 - std::pow(1.0 - alpha, 1.0 / static_cast<double>(m)));
}

}  // namespace iris_test
