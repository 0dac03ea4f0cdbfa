// The lights' sampling routines against the densities they claim (χ²), the sphere
// parametrisations of environment maps (round trips, Jacobians), the piecewise-constant
// distributions, and the light sampler's selection by power.
//
// χ² method (environment maps: `map_fit`): N = 200 000 directions (fixed seeds) binned into 24 bands of equal z × 48
// sectors of φ (1152 cells of equal solid angle, Archimedes); the expected count of a cell
// is N ∫ pdf dω over it by a 64 × 8 midpoint rule (in z and φ) of the routine's own pdf;
// adjacent cells are pooled to ≥ 5 expected (direction_fit.hpp, stats.hpp). Family: every χ² test of this file
// (m = 8) at family-wise α = 0.01, Šidák: α' = 1 − 0.99^(1/8) ≈ 1.3e-3. The negative
// controls (a cone sampled against the pdf of a slightly wider one; an environment map
// sampled against a distribution with one texel's weight changed) must be rejected at α'.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <functional>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include <iris/render/lights.hpp>
#include <iris/render/lights/directions.hpp>
#include <iris/sampling/piecewise.hpp>
#include <iris/sampling/random.hpp>

#include "direction_fit.hpp"
#include "stats.hpp"
#include "test_scenes.hpp"

namespace {

using iris::test::chi2_result;
constexpr double family_alpha = 0.01;
constexpr std::size_t family_size = 8;
const double alpha_test = iris::test::sidak(family_alpha, family_size);
constexpr int draws = 200000;
constexpr double pi_d = std::numbers::pi;

using iris::test::direction_fit;

void expect_fit(const chi2_result& r, const char* what) {
    EXPECT_TRUE(r.impossible.empty()) << what << ": " << r.impossible;
    EXPECT_GT(r.p_value, alpha_test) << what << ": χ² " << r.statistic << " dof " << r.dof;
}

}  // namespace

TEST(LightSampling, UniformSphereConeAndCosineMatchTheirDensities) {
    using namespace iris::lights;
    expect_fit(direction_fit([](glm::vec2 u) { return std::optional(uniform_sphere(u)); },
                             [](const glm::vec3&) { return 1.0 / (4.0 * pi_d); }, 1),
               "uniform sphere");
    const float cmax = 1.0f - 2.0f / 12.0f;  // on a band edge: the quadrature sees no step inside a band
    expect_fit(direction_fit([&](glm::vec2 u) { return std::optional(uniform_cone(u, cmax)); },
                             [&](const glm::vec3& d) { return d.z >= cmax ? 1.0 / (2.0 * pi_d * (1.0 - cmax)) : 0.0; }, 2),
               "uniform cone");
    expect_fit(direction_fit([](glm::vec2 u) { return std::optional(cosine_hemisphere(u)); },
                             [](const glm::vec3& d) { return d.z > 0.0f ? d.z / pi_d : 0.0; }, 3),
               "cosine hemisphere");
    // negative control: the cone's samples against a cone of 25 % more solid angle
    const float wider = 1.0f - 2.5f / 12.0f;
    const auto bad = direction_fit([&](glm::vec2 u) { return std::optional(uniform_cone(u, cmax)); },
                                   [&](const glm::vec3& d) { return d.z >= wider ? 1.0 / (2.0 * pi_d * (1.0 - wider)) : 0.0; }, 4);
    EXPECT_LT(bad.p_value, alpha_test) << "a cone against a wider cone's pdf must be rejected";
}

TEST(LightSampling, SphereMapsRoundTripAndHaveTheirJacobians) {
    using namespace iris::lights;
    iris::counter_rng rng(7, 0);
    for (int i = 0; i < 20000; ++i) {
        const glm::vec2 p(rng.next(), rng.next());
        const glm::vec3 a = equal_area_to_direction(p);
        EXPECT_NEAR(glm::length(a), 1.0f, 1e-5f);
        const glm::vec2 q = direction_to_equal_area(a);
        EXPECT_NEAR(q.x, p.x, 2e-4f) << p.x << "," << p.y;
        EXPECT_NEAR(q.y, p.y, 2e-4f) << p.x << "," << p.y;
        const glm::vec3 b = latlong_to_direction(p);
        const glm::vec2 r = direction_to_latlong(b);
        EXPECT_NEAR(r.x, p.x, 2e-4f);
        EXPECT_NEAR(r.y, p.y, 2e-4f);
    }
    // iris's +y is the equal-area square's centre and the latlong map's top row
    EXPECT_NEAR(equal_area_to_direction({0.5f, 0.5f}).y, 1.0f, 1e-6f);
    EXPECT_NEAR(latlong_to_direction({0.3f, 0.0f}).y, 1.0f, 1e-6f);
    // equal area: uniform points on the square are uniform on the sphere
    expect_fit(direction_fit([](glm::vec2 u) { return std::optional(equal_area_to_direction(u)); },
                             [](const glm::vec3&) { return 1.0 / (4.0 * pi_d); }, 5),
               "equal-area square");
}

TEST(LightSampling, PiecewiseConstantSamplesItsDensity) {
    // 2-D: 5 × 3 cells with one zero cell and one zero row; every sample's pdf is its cell's
    const std::vector<float> f = {1, 2, 0, 4, 5, 0, 0, 0, 0, 0, 9, 1, 1, 1, 3};
    const iris::piecewise_constant_2d d(f, 5, 3);
    double total = 0.0;
    for (float v : f) total += v;
    EXPECT_NEAR(d.integral(), total / 15.0, 1e-6);
    std::vector<double> expected(15), observed(15, 0.0);
    for (std::size_t i = 0; i < 15; ++i) expected[i] = f[i] / total * draws;
    iris::counter_rng rng(11, 0);
    for (int i = 0; i < draws; ++i) {
        const auto s = d.sample({rng.next(), rng.next()});
        ASSERT_GE(s.p.x, 0.0f);
        ASSERT_LT(s.p.x, 1.0f);
        ASSERT_LT(s.p.y, 1.0f);
        const auto cx = static_cast<std::size_t>(s.p.x * 5), cy = static_cast<std::size_t>(s.p.y * 3);
        observed[cy * 5 + cx] += 1.0;
        ASSERT_NEAR(s.pdf, d.pdf(s.p), 1e-5f);
        ASSERT_NEAR(s.pdf, f[cy * 5 + cx] / (total / 15.0), 1e-4);
    }
    expect_fit(iris::test::chi_square(expected, observed), "piecewise constant 2-D");
    // all zero: uniform, and its pdf says so
    const std::vector<float> zeros(6, 0.0f);
    const iris::piecewise_constant_2d u(zeros, 3, 2);
    EXPECT_EQ(u.pdf({0.4f, 0.7f}), 1.0f);
    EXPECT_EQ(u.sample({0.5f, 0.5f}).pdf, 1.0f);
}

namespace {
/// \brief A scene with an environment image of w × h texels given by `texel(x, y)`.
iris::scene_desc map_scene(iris::environment_mapping mapping, int w, int h, const std::function<glm::vec3(int, int)>& texel) {
    iris::scene_desc s = iris::test::lit_floor();
    iris::environment_desc env;
    env.spd_name = "D65";
    env.radiance = iris::test::flat(1.0);
    env.basis = {iris::test::flat(0.3), iris::test::flat(0.5), iris::test::flat(0.2)};
    iris::environment_map m;
    m.mapping = mapping;
    m.width = w;
    m.height = h;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) m.weights.push_back(texel(x, y));
    env.map = std::move(m);
    s.environment = std::move(env);
    return s;
}
}  // namespace

namespace {
/// \brief χ² of an environment map's sampled directions, binned in the map's own square
/// (2 × 2 bins a texel), against N ∫ pdf(ω(p)) |J(p)| dp over each bin (8 × 8 midpoint
/// rule; the density is constant in p inside a texel, so the rule is exact up to rounding).
/// Binned on the sphere instead, every texel edge would cut the bins and a midpoint rule
/// would misjudge the bins a bright texel's edge crosses.
chi2_result map_fit(const iris::lights::environment_light& sampler, const iris::lights::environment_light& reference,
                    iris::environment_mapping mapping, int w, int h, std::uint64_t seed) {
    using namespace iris::lights;
    const bool ll = mapping == iris::environment_mapping::latlong;
    const auto to_square = [&](const glm::vec3& d) { return ll ? direction_to_latlong(d) : direction_to_equal_area(d); };
    const auto to_dir = [&](glm::vec2 p) { return ll ? latlong_to_direction(p) : equal_area_to_direction(p); };
    const auto jacobian = [&](glm::vec2 p) { return ll ? 2.0 * pi_d * pi_d * std::sin(pi_d * p.y) : 4.0 * pi_d; };
    const int bw = 2 * w, bh = 2 * h;
    std::vector<double> expected(static_cast<std::size_t>(bw * bh) + 1, 0.0), observed(expected.size(), 0.0);
    double mass = 0.0;
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            double sum = 0.0;
            for (int a = 0; a < 8; ++a)
                for (int b = 0; b < 8; ++b) {
                    const glm::vec2 p{(static_cast<float>(bx) + (static_cast<float>(a) + 0.5f) / 8.0f) / static_cast<float>(bw),
                                      (static_cast<float>(by) + (static_cast<float>(b) + 0.5f) / 8.0f) / static_cast<float>(bh)};
                    sum += static_cast<double>(reference.pdf(to_dir(p))) * jacobian(p);
                }
            const double e = sum / 64.0 / (bw * bh);
            expected[static_cast<std::size_t>(by * bw + bx)] = e * draws;
            mass += e;
        }
    expected.back() = std::max(0.0, 1.0 - mass) * draws;
    iris::counter_rng rng(seed, 0);
    int checked = 0;
    for (int i = 0; i < draws; ++i) {
        const auto d = sampler.sample({rng.next(), rng.next()});
        if (!d) {
            observed.back() += 1.0;
            continue;
        }
        if (checked++ < 2000) {
            EXPECT_NEAR(d->pdf, sampler.pdf(d->dir), 2e-3f * d->pdf);  // sample() reports pdf()
        }
        const glm::vec2 p = to_square(d->dir);
        const int bx = std::min(bw - 1, static_cast<int>(p.x * static_cast<float>(bw)));
        const int by = std::min(bh - 1, static_cast<int>(p.y * static_cast<float>(bh)));
        observed[static_cast<std::size_t>(by * bw + bx)] += 1.0;
    }
    return iris::test::chi_square(expected, observed);
}
}  // namespace

// The environment light's sampled directions against its own pdf(dir), for both maps.
TEST(LightSampling, EnvironmentMapsSampleTheirDensity) {
    const auto bumpy = [](int x, int y) {
        const float v = (x == 7 && y == 3) ? 40.0f : 0.2f + 0.1f * static_cast<float>((x * 7 + y * 3) % 5);
        return glm::vec3(v, 0.5f * v, (y == 5) ? 0.0f : 0.1f);
    };
    for (const auto mapping : {iris::environment_mapping::latlong, iris::environment_mapping::equal_area}) {
        const int w = 16, h = mapping == iris::environment_mapping::latlong ? 8 : 16;
        const auto s = map_scene(mapping, w, h, bumpy);
        const iris::lights::environment_light env(*s.environment, 0);
        expect_fit(map_fit(env, env, mapping, w, h, 6 + static_cast<int>(mapping)),
                   mapping == iris::environment_mapping::latlong ? "latlong map" : "equal-area map");
    }
    // negative control: the same samples against the pdf of a map whose bright texel is 30 % dimmer
    const auto s = map_scene(iris::environment_mapping::latlong, 16, 8, bumpy);
    const auto t = map_scene(iris::environment_mapping::latlong, 16, 8, [&](int x, int y) {
        return (x == 7 && y == 3) ? 0.7f * bumpy(x, y) : bumpy(x, y);
    });
    const iris::lights::environment_light a(*s.environment, 0), b(*t.environment, 0);
    const auto bad = map_fit(a, b, iris::environment_mapping::latlong, 16, 8, 8);
    EXPECT_LT(bad.p_value, alpha_test) << "a map's samples against another map's pdf must be rejected";
}

// ∫ pdf dω = 1 over the sphere for both maps (midpoint rule over 512 × 1024 directions in
// z and φ), and the flux integral of a constant map is 4π times its value.
TEST(LightSampling, EnvironmentDensityAndFluxIntegrate) {
    for (const auto mapping : {iris::environment_mapping::latlong, iris::environment_mapping::equal_area}) {
        const auto s = map_scene(mapping, 32, mapping == iris::environment_mapping::latlong ? 16 : 32,
                                 [](int x, int y) { return glm::vec3(0.1f + static_cast<float>((x + 2 * y) % 7), 0.0f, 1.0f); });
        const iris::lights::environment_light env(*s.environment, 0);
        double sum = 0.0;
        constexpr int nz = 512, np = 1024;
        for (int i = 0; i < nz; ++i)
            for (int j = 0; j < np; ++j) {
                const double z = -1.0 + 2.0 * (i + 0.5) / nz, phi = 2.0 * pi_d * (j + 0.5) / np, r = std::sqrt(1.0 - z * z);
                sum += env.pdf(glm::vec3(static_cast<float>(r * std::cos(phi)), static_cast<float>(z),
                                         static_cast<float>(r * std::sin(phi))));
            }
        EXPECT_NEAR(sum * 4.0 * pi_d / (nz * np), 1.0, 2e-3);
        const auto c = map_scene(mapping, 8, mapping == iris::environment_mapping::latlong ? 4 : 8,
                                 [](int, int) { return glm::vec3(2.0f, 0.0f, 0.5f); });
        const glm::dvec3 flux = iris::lights::environment_light(*c.environment, 0).integral();
        // the equal-area map's Jacobian is constant: exact; latlong by the midpoint rule in θ
        const double tol = mapping == iris::environment_mapping::equal_area ? 1e-5 : 0.03;
        EXPECT_NEAR(flux.x / (4.0 * pi_d), 2.0, 2.0 * tol);
        EXPECT_NEAR(flux.z / (4.0 * pi_d), 0.5, 0.5 * tol);
    }
}

// An environment turned by `to_map` (a pbrt-v4 infinite light under a transform) is the same
// map seen through the rotation: its radiance and density at d are the unturned map's at
// to_map·d, and its samples are the unturned ones turned back (a mirror included).
TEST(LightSampling, ATurnedEnvironmentIsTheSameMapSeenThroughItsRotation) {
    for (const auto mapping : {iris::environment_mapping::latlong, iris::environment_mapping::equal_area}) {
        const int w = 16, h = mapping == iris::environment_mapping::latlong ? 8 : 16;
        const auto texel = [](int x, int y) { return glm::vec3(0.1f + static_cast<float>((x * 3 + y) % 5), (x == 3 && y == 2) ? 30.0f : 0.2f, 0.3f); };
        const auto plain = map_scene(mapping, w, h, texel);
        auto turned = map_scene(mapping, w, h, texel);
        // a rotation about (1, 2, 3) by 50° followed by a mirror in x: orthogonal, det −1
        const glm::vec3 k = glm::normalize(glm::vec3(1.0f, 2.0f, 3.0f));
        const float c = std::cos(0.87266f), sn = std::sin(0.87266f);
        glm::mat3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const float kk = k[i] * k[j] * (1.0f - c);
                const float cross = (i == j) ? 0.0f : sn * ((i + 1) % 3 == j ? -k[3 - i - j] : k[3 - i - j]);
                r[j][i] = (i == j ? c : 0.0f) + kk + cross;
            }
        r = glm::mat3(glm::vec3(-1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0.0f, 0.0f, 1.0f)) * r;
        turned.environment->map->to_map = r;
        const iris::lights::environment_light a(*plain.environment, 0), b(*turned.environment, 0);
        iris::counter_rng rng(17, 0);
        int edges = 0;
        for (int i = 0; i < 2000; ++i) {
            const glm::vec3 d = iris::lights::uniform_sphere({rng.next(), rng.next()});
            const glm::vec3 m = r * d;
            EXPECT_NEAR(b.pdf(d), a.pdf(m), 1e-4f * a.pdf(m) + 1e-7f);
            const auto eb = b.emission(d), ea = a.emission(m);
            for (int j = 0; j < 3; ++j) EXPECT_NEAR(eb.weight[j], ea.weight[j], 1e-4f * (1.0f + ea.weight[j]));
            const glm::vec2 u{rng.next(), rng.next()};
            const auto sb = b.sample(u), sa = a.sample(u);
            ASSERT_EQ(sb.has_value(), sa.has_value());
            if (!sa) continue;
            EXPECT_LT(glm::length(r * sb->dir - sa->dir), 1e-5f);
            EXPECT_NEAR(sb->pdf, sa->pdf, 1e-6f * sa->pdf);
            // sample() reports pdf(), except where turning the direction back and forth moves it
            // across a texel's edge by a rounding (the density is piecewise constant there), or,
            // for the latitude-longitude map, within 0.01 rad of a pole, where θ = acos(y) loses
            // precision (a rounding of y near 1 moves θ, and the 1/sin θ of the density, by up to a few %)
            if (std::fabs(b.pdf(sb->dir) - sb->pdf) > 2e-3f * sb->pdf) {
                const glm::vec3 m2 = r * sb->dir;
                const bool ll = mapping == iris::environment_mapping::latlong;
                const glm::vec2 p = ll ? iris::lights::direction_to_latlong(m2) : iris::lights::direction_to_equal_area(m2);
                const float ex = p.x * static_cast<float>(w), ey = p.y * static_cast<float>(h);
                const bool edge = std::min(std::fabs(ex - std::round(ex)), std::fabs(ey - std::round(ey))) < 1e-3f;
                const bool pole = ll && std::fabs(m2.y) > std::cos(0.01f);
                EXPECT_TRUE(edge || pole) << "a sample's pdf differs from pdf(dir) away from a texel edge and a pole: p " << p.x
                                          << "," << p.y;
                ++edges;
            }
        }
        EXPECT_LE(edges, 20) << "more than 1 % of the samples on a texel edge or at a pole";
        // flux does not turn
        const glm::dvec3 fa = a.integral(), fb = b.integral();
        EXPECT_EQ(fa, fb);
    }
}

// Selection by power: a triangle lamp, a point light and a distant light, each chosen in
// proportion to Φ/π (A∫L, 4∫I, R²∫E), and every sample's pdf is its light's probability
// (delta lights) or p·r²/|cos| (the triangle).
TEST(LightSampling, LightsAreChosenByPower) {
    iris::scene_desc s = iris::test::lit_floor();  // lamp 0.4 × 0.4, L = 10 × flat
    s.emitters.push_back({"p", iris::test::flat(2.0), false});
    s.lights.push_back(iris::light::point{{0.5f, 1.0f, 0.0f}, 1});
    s.emitters.push_back({"d", iris::test::flat(0.5), false});
    s.lights.push_back(iris::light::distant{{0.0f, -1.0f, 0.0f}, 2});
    const iris::light_sampler ls(s);
    const auto power = [&](std::size_t e) { return iris::integrate_over_domain(s.emitters[e].radiance, s.lambda_min, s.lambda_max); };
    const double r2 = static_cast<double>(ls.bounds().radius) * ls.bounds().radius;
    const double w_lamp = 0.16 * power(0), w_point = 4.0 * power(1), w_dist = r2 * power(2);
    const double total = w_lamp + w_point + w_dist;
    int n_lamp = 0, n_point = 0, n_dist = 0;
    const iris::surface_point ref{{0.0f, 0.0f, 0.0f}, glm::vec3(1e-6f)};
    iris::counter_rng rng(3, 0);
    constexpr int n = 100000;
    for (int i = 0; i < n; ++i) {
        const auto l = ls.sample_li(ref, {0.0f, 1.0f, 0.0f}, rng.next(), {rng.next(), rng.next()});
        ASSERT_TRUE(l.has_value());
        if (!l->delta) {
            ++n_lamp;
            const float d = 0.8f / l->wi.y;  // distance to the lamp plane y = 0.8
            EXPECT_NEAR(l->pdf, static_cast<float>(w_lamp / total) / 0.16f * d * d / l->wi.y, 1e-3f * l->pdf);
        } else if (l->le.first == 1) {
            ++n_point;
            EXPECT_FLOAT_EQ(l->pdf, static_cast<float>(w_point / total));
            EXPECT_NEAR(l->le.weight[0], 1.0f / 1.25f, 1e-6f);  // 1/r², r² = 0.5² + 1²
        } else {
            ++n_dist;
            EXPECT_FLOAT_EQ(l->pdf, static_cast<float>(w_dist / total));
            EXPECT_EQ(l->wi, glm::vec3(0.0f, 1.0f, 0.0f));
        }
    }
    const std::vector<double> expected = {w_lamp / total * n, w_point / total * n, w_dist / total * n};
    expect_fit(iris::test::chi_square(expected, {double(n_lamp), double(n_point), double(n_dist)}), "selection by power");
}

// A spot light's falloff and its flux per unit intensity (∫ s dω, by quadrature).
TEST(LightSampling, SpotFalloffIntegratesToItsSolidAngle) {
    const iris::light::spot sp{{0, 0, 0}, {0, -1, 0}, std::cos(0.3f), std::cos(0.5f), 0};
    const auto p = iris::lights::point_light::from(sp);
    EXPECT_EQ(p.falloff(1.0f), 1.0f);
    EXPECT_EQ(p.falloff(std::cos(0.6f)), 0.0f);
    EXPECT_GT(p.falloff(std::cos(0.4f)), 0.0f);
    EXPECT_LT(p.falloff(std::cos(0.4f)), 1.0f);
    double sum = 0.0;
    constexpr int n = 200000;
    for (int i = 0; i < n; ++i) sum += p.falloff(-1.0f + 2.0f * (static_cast<float>(i) + 0.5f) / n);
    EXPECT_NEAR(sum * 2.0 / n * 2.0 * pi_d / pi_d, p.solid_angle_over_pi(), 1e-4);
    EXPECT_EQ(iris::lights::point_light::from(iris::light::point{}).solid_angle_over_pi(), 4.0f);
}
