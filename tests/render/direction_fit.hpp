#pragma once
// χ² of a direction sampler against the density it claims (light_test.cpp, bsdf_test.cpp).
//
// `draws` directions (a fixed seed) are binned into `z_bands` bands of equal z ×
// `phi_sectors` sectors of φ: cells of equal solid angle (Archimedes). The expected count
// of a cell is draws · ∫ pdf dω over it, by a `sub_z` × `sub_phi` midpoint rule of the
// claimed pdf; one more cell holds the failed samples, expected draws · (1 − ∫ pdf). Cells
// are pooled to ≥ 5 expected (stats.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <numbers>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <iris/sampling/random.hpp>

#include "stats.hpp"

namespace iris::test {

struct direction_grid {
    int draws = 200000;
    int z_bands = 24, phi_sectors = 48;
    int sub_z = 64, sub_phi = 8;  ///< midpoint rule per cell
};

inline chi2_result direction_fit(const std::function<std::optional<glm::vec3>(glm::vec2)>& sample,
                                 const std::function<double(const glm::vec3&)>& pdf, std::uint64_t seed,
                                 const direction_grid& g = {}) {
    constexpr double pi = std::numbers::pi;
    const auto cells = static_cast<std::size_t>(g.z_bands * g.phi_sectors);
    const auto cell_of = [&](const glm::vec3& d) {
        const double z = std::clamp(static_cast<double>(d.z), -1.0, 1.0);
        double phi = std::atan2(static_cast<double>(d.y), static_cast<double>(d.x));
        if (phi < 0.0) phi += 2.0 * pi;
        const int iz = std::min(g.z_bands - 1, static_cast<int>((z + 1.0) * 0.5 * g.z_bands));
        const int ip = std::min(g.phi_sectors - 1, static_cast<int>(phi / (2.0 * pi) * g.phi_sectors));
        return static_cast<std::size_t>(iz * g.phi_sectors + ip);
    };
    std::vector<double> expected(cells + 1, 0.0), observed(cells + 1, 0.0);
    const double cell_omega = 4.0 * pi / static_cast<double>(cells);
    double mass = 0.0;
    for (int iz = 0; iz < g.z_bands; ++iz)
        for (int ip = 0; ip < g.phi_sectors; ++ip) {
            double s = 0.0;
            for (int a = 0; a < g.sub_z; ++a)
                for (int b = 0; b < g.sub_phi; ++b) {
                    const double z = -1.0 + 2.0 * (iz + (a + 0.5) / g.sub_z) / g.z_bands;
                    const double phi = 2.0 * pi * (ip + (b + 0.5) / g.sub_phi) / g.phi_sectors;
                    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
                    s += pdf(glm::vec3(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
                                       static_cast<float>(z)));
                }
            const double e = s / (static_cast<double>(g.sub_phi) * g.sub_z) * cell_omega;
            expected[static_cast<std::size_t>(iz * g.phi_sectors + ip)] = e * g.draws;
            mass += e;
        }
    expected[cells] = std::max(0.0, 1.0 - mass) * g.draws;
    iris::counter_rng rng(seed, 0);
    for (int i = 0; i < g.draws; ++i) {
        const glm::vec2 u(rng.next(), rng.next());
        const auto d = sample(u);
        observed[d ? cell_of(*d) : cells] += 1.0;
    }
    if (std::getenv("IRIS_TEST_VERBOSE"))
        for (std::size_t i = 0; i < cells; ++i)
            if ((observed[i] - expected[i]) * (observed[i] - expected[i]) / std::max(1.0, expected[i]) > 12.0)
                std::printf("cell z%zu phi%zu: expected %.1f observed %.0f\n", i / static_cast<std::size_t>(g.phi_sectors),
                            i % static_cast<std::size_t>(g.phi_sectors), expected[i], observed[i]);
    return chi_square(expected, observed);
}

}  // namespace iris::test
