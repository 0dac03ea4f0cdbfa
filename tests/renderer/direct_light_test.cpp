// Exact direct lighting: a diffuse plane (reflectance 0.5, flat) under one polygonal
// Lambertian emitter (black, so nothing else lights it), compared zone by zone with the
// closed-form irradiance of the polygon (Lambert's formula), for every preset.
//
// The plane's radiance is L_r(x) = ρ/π · E(x), E(x) = L_e · Φ(x), where Φ is the projected
// solid angle of the polygon seen from x: Φ = ½ |Σ_i θ_i n · γ_i| over its edges, θ_i the
// angle the edge subtends at x and γ_i the unit normal of the plane through x and the edge
// (Lambert 1760; Arvo 1995, "Applications of irradiance tensors"). A one-sided emitter
// lights x only if x lies in front of it. Each pixel's exact value is its box-filter mean,
// integrated with 8 × 8 sub-pixel rays; pixels within a pixel of the lamp's image, or whose
// footprint leaves the plane, are left out. Zones are rings around the point under the lamp (the distances of
// issue 18's measurements), so an error that grows away from the lamp's axis shows.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <iris/render/camera.hpp>
#include <iris/renderer/renderer.hpp>
#include <iris/scene/scene.hpp>
#include <iris/spectrum/color.hpp>

#include "region_stats.hpp"
#include "oracle_presets.hpp"

namespace {

using dvec3 = glm::dvec3;

/// \brief Projected solid angle of a convex planar polygon seen from x with unit normal n
/// (the polygon wholly above x's tangent plane).
double projected_solid_angle(const dvec3& x, const dvec3& n, const std::vector<dvec3>& poly) {
    double s = 0.0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const dvec3 a = glm::normalize(poly[i] - x), b = glm::normalize(poly[(i + 1) % poly.size()] - x);
        const dvec3 g = glm::cross(a, b);
        const double len = glm::length(g);
        if (len > 0.0) s += std::atan2(len, glm::dot(a, b)) * glm::dot(n, g / len);
    }
    return 0.5 * std::fabs(s);
}

/// \brief Does the segment from o along d (t > 0) cross the convex planar polygon?
bool ray_hits_polygon(const dvec3& o, const dvec3& d, const std::vector<dvec3>& poly) {
    const dvec3 n = glm::cross(poly[1] - poly[0], poly[2] - poly[0]);
    const double den = glm::dot(n, d);
    if (den == 0.0) return false;
    const double t = glm::dot(n, poly[0] - o) / den;
    if (!(t > 0.0)) return false;
    const dvec3 p = o + t * d;
    bool pos = false, neg = false;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const double side = glm::dot(n, glm::cross(poly[(i + 1) % poly.size()] - poly[i], p - poly[i]));
        pos |= side > 0.0;
        neg |= side < 0.0;
    }
    return !(pos && neg);
}

/// \brief One configuration: the lamp's corners (world space; listed counter-clockwise
/// seen from the side it emits to) and whether it emits from both sides.
struct lamp {
    std::string name;
    std::vector<dvec3> corners;
    bool two_sided = false;
};

constexpr double rho = 0.5, receiver_half = 1.5, luminance = 10.0;

/// \brief The scene: the 3 m × 3 m plane y = 0 and the lamp, camera as in issue 18.
iris::scene_desc make_scene(const lamp& l) {
    const std::string json = std::string(R"({"camera": {"position": [0, 2.2, 2.2], "look_at": [0, 0, 0], "fov": 60, "resolution": [96, 72]},
      "materials": {"r": {"type": "diffuse", "reflectance": 0.5}, "black": {"type": "diffuse", "reflectance": 0}},
      "emitters": {"l": {"spd": "D65", "luminance": 10, "two_sided": )") +
                             (l.two_sided ? "true" : "false") + R"(}},
      "shapes": [{"type": "quad", "size": [3, 3], "material": "r"},
                 {"type": "quad", "size": [1, 1], "material": "black", "emitter": "l"}]})";
    auto s = iris::scene::parse_scene(json, "direct_light_test", ".");
    // replace the placeholder quad by the lamp's polygon (a fan of triangles; luminance,
    // unlike power, does not depend on the area)
    auto& m = s.shapes[1].mesh;
    m.positions.clear();
    m.triangles.clear();
    m.uvs.clear();  // the quad's texture coordinates belong to its four vertices
    for (const auto& c : l.corners) m.positions.emplace_back(c);
    for (std::uint32_t i = 1; i + 1 < l.corners.size(); ++i) m.triangles.push_back({0, i, i + 1});
    return s;
}

/// \brief XYZ of the emitter's radiance over the renderer's domain (fine midpoint sum).
std::array<double, 3> emitter_xyz(const iris::scene_desc& s) {
    std::array<double, 3> v{};
    const double step = 0.05;
    for (double l = s.lambda_min + 0.5 * step; l < s.lambda_max; l += step) {
        const double e = s.emitters[0].radiance(static_cast<float>(l)) * step;
        v[0] += e * iris::cie::x_bar(l);
        v[1] += e * iris::cie::y_bar(l);
        v[2] += e * iris::cie::z_bar(l);
    }
    for (auto& c : v) c /= iris::cie::y_integral;
    return v;
}

const std::array<double, 7> zone_edges = {0.0, 0.1, 0.25, 0.5, 0.9, 1.4, 2.2};
constexpr std::size_t zones = zone_edges.size() - 1;

/// \brief Per pixel: the zone (−1: left out) and the exact mean of ρ/π · Φ over its footprint.
struct pixel_truth {
    std::vector<int> zone;
    std::vector<double> phi;
};
pixel_truth exact(const iris::scene_desc& s, const lamp& l) {
    const int w = s.camera.width, h = s.camera.height;
    const iris::camera_rays cam(s.camera, w, h);
    const dvec3 up(0, 1, 0), o(cam.origin());
    dvec3 centre(0.0);
    for (const auto& c : l.corners) centre += c;
    centre /= static_cast<double>(l.corners.size());
    const dvec3 ln = glm::normalize(glm::cross(l.corners[1] - l.corners[0], l.corners[2] - l.corners[0]));
    pixel_truth t{std::vector<int>(static_cast<std::size_t>(w * h), -1), std::vector<double>(static_cast<std::size_t>(w * h))};
    constexpr int sub = 8;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // leave out pixels near the lamp's image (a two-sided lamp's top emits towards
            // the camera): rays over a 3 × 3-pixel neighbourhood must all miss it
            bool ok = true;
            for (int a = 0; a <= 12 && ok; ++a)
                for (int b = 0; b <= 12 && ok; ++b) {
                    const dvec3 d(cam.direction(x, y, {-1.0f + 3.0f * static_cast<float>(a) / 12.0f,
                                                       -1.0f + 3.0f * static_cast<float>(b) / 12.0f}));
                    ok = !ray_hits_polygon(o, d, l.corners);
                }
            double sum = 0.0, r_min = 1e9, r_max = 0.0;
            for (int a = 0; a < sub && ok; ++a)
                for (int b = 0; b < sub && ok; ++b) {
                    const dvec3 d(cam.direction(x, y, {(static_cast<float>(a) + 0.5f) / sub, (static_cast<float>(b) + 0.5f) / sub}));
                    if (!(d.y < 0.0)) {
                        ok = false;
                        break;
                    }
                    const dvec3 p = o + (-o.y / d.y) * d;
                    if (std::fabs(p.x) > receiver_half || std::fabs(p.z) > receiver_half) {
                        ok = false;
                        break;
                    }
                    const bool lit = l.two_sided || glm::dot(ln, p - l.corners[0]) > 0.0;
                    sum += lit ? projected_solid_angle(p, up, l.corners) : 0.0;
                    const double r = std::hypot(p.x - centre.x, p.z - centre.z);
                    r_min = std::min(r_min, r);
                    r_max = std::max(r_max, r);
                }
            if (!ok) continue;
            // a pixel counts in a zone only if its whole footprint lies in it
            for (std::size_t z = 0; z < zones; ++z)
                if (r_min >= zone_edges[z] && r_max < zone_edges[z + 1]) t.zone[static_cast<std::size_t>(y * w + x)] = static_cast<int>(z);
            t.phi[static_cast<std::size_t>(y * w + x)] = rho / std::numbers::pi * sum / (sub * sub);
        }
    return t;
}

std::vector<lamp> lamps() {
    const auto rect = [](double half_x, double half_z, double y) {  // horizontal, emitting downwards
        return std::vector<dvec3>{{-half_x, y, -half_z}, {half_x, y, -half_z}, {half_x, y, half_z}, {-half_x, y, half_z}};
    };
    std::vector<lamp> v;
    v.push_back({"0.2 m square at 0.3 m (issue 18)", rect(0.1, 0.1, 0.3)});
    v.push_back({"0.05 m square at 0.15 m (small, near)", rect(0.025, 0.025, 0.15)});
    v.push_back({"0.3 m square at 1 m (far)", rect(0.15, 0.15, 1.0)});
    v.push_back({"1 m x 0.6 m at 0.4 m (large)", rect(0.5, 0.3, 0.4)});
    v.push_back({"triangle at 0.25 m", {{-0.15, 0.25, -0.1}, {0.15, 0.25, -0.1}, {0.0, 0.25, 0.15}}});
    // vertical, two-sided: the plane sees it edge-on along x and at grazing angles
    v.push_back({"vertical 0.4 m square, two-sided, 0.1-0.5 m up",
                 {{-0.2, 0.1, 0.0}, {0.2, 0.1, 0.0}, {0.2, 0.5, 0.0}, {-0.2, 0.5, 0.0}}, true});
    // tilted 60 degrees, one-sided: half the plane sees only its unlit back
    const double c = std::cos(std::numbers::pi / 3.0) * 0.15, sy = std::sin(std::numbers::pi / 3.0) * 0.15;
    v.push_back({"0.3 m square tilted 60 degrees, one-sided",
                 {{-0.15, 0.35 + sy, -c}, {0.15, 0.35 + sy, -c}, {0.15, 0.35 - sy, c}, {-0.15, 0.35 - sy, c}}});
    v.push_back({"triangle 0.4 m, two-sided, at 0.2 m", {{-0.2, 0.2, -0.15}, {0.2, 0.2, -0.15}, {0.0, 0.2, 0.25}}, true});
    return v;
}

}  // namespace

// (Passes: 256 for the path tracer, 64 for bdpt.) Family: every lamp × preset × zone × channel, at family-wise α = 0.001 (Šidák). Each
// zone's mean is over ≥ 256 passes of ≥ 8 pixels; the per-pass zone means are independent,
// so their spread gives the standard error (normal approximation). Presets biased before
// N_thold (restriction without propagation) are judged on the passes after it only.
namespace {
void every_preset_matches_the_exact_irradiance(const std::string& estimator, const std::vector<lamp>& all, int nthold,
                                               int passes) {
    const auto presets = iris_test::oracle_presets();
    const int spp_unbiased = passes, spp_biased = nthold + passes;
    constexpr std::size_t min_pixels = 8;
    const double z_max = iris_test::sidak_z(0.001, all.size() * presets.size() * zones * 3);
    std::printf("threshold |z| <= %.2f (%zu lamps x %zu presets x %zu zones x 3 channels, family-wise alpha 0.001)\n",
                z_max, all.size(), presets.size(), zones);
    for (const auto& l : all) {
        const auto s = make_scene(l);
        const auto truth = exact(s, l);
        const auto e = emitter_xyz(s);
        ASSERT_NEAR(e[1], luminance, 1e-3 * luminance);
        std::array<double, zones> phi{};
        std::array<std::size_t, zones> count{};
        for (std::size_t i = 0; i < truth.zone.size(); ++i)
            if (truth.zone[i] >= 0) {
                phi[static_cast<std::size_t>(truth.zone[i])] += truth.phi[i];
                ++count[static_cast<std::size_t>(truth.zone[i])];
            }
        for (const auto& p : presets) {
            iris::renderer::options o;
            o.estimator = estimator;
            o.preset = p.name;
            o.nthold = nthold;
            o.spp = p.unbiased_before_nthold ? spp_unbiased : spp_biased;
            o.seed = 18;
            const int from = p.unbiased_before_nthold ? 0 : nthold;
            const auto est = iris_test::region_estimates(s, o, zones, from, [&](int x, int y, int w, int) {
                return truth.zone[static_cast<std::size_t>(y * w + x)];
            });
            for (std::size_t z = 0; z < zones; ++z) {
                if (count[z] < min_pixels) continue;
                ASSERT_EQ(est[z].pixels, count[z]);
                for (std::size_t c = 0; c < 3; ++c) {
                    const double want = e[c] * phi[z] / static_cast<double>(count[z]);
                    const double zscore = (est[z].mean[c] - want) / est[z].se[c];
                    if (c == 1 && p.name == "hwss")
                        std::printf("%-8s %-50s %-14s zone %.2f-%.2f m: Y %.5f exact %.5f ratio %.4f z %+.2f\n", estimator.c_str(), l.name.c_str(),
                                    p.name.c_str(), zone_edges[z], zone_edges[z + 1], est[z].mean[c], want,
                                    est[z].mean[c] / want, zscore);
                    EXPECT_LE(std::fabs(zscore), z_max)
                        << l.name << ", " << p.name << ", zone " << zone_edges[z] << "-" << zone_edges[z + 1] << " m, channel "
                        << "XYZ"[c] << ": " << est[z].mean[c] << " vs exact " << want << " (ratio " << est[z].mean[c] / want
                        << ", se " << est[z].se[c] << ")";
                }
            }
        }
    }
}
}  // namespace

TEST(DirectLight, EveryPresetMatchesTheExactIrradianceOfPolygonalLamps) { every_preset_matches_the_exact_irradiance("nee-mis", lamps(), 64, 256); }

// The same under bidirectional path tracing: a pixel of the plane is lit by paths of three
// vertices, made by three strategies — the camera ray's BSDF sample hitting the lamp (0, 3),
// next-event estimation (1, 2) and the lamp's light subpath joined to the camera (2, 1) — so
// the exact irradiance checks their weights and the light tracing's splats together. Four
// of the lamps (one-sided, two-sided, small and near, tilted).
TEST(DirectLight, EveryPresetUnderBdptMatchesTheExactIrradianceOfPolygonalLamps) {
    const auto all = lamps();
    every_preset_matches_the_exact_irradiance("bdpt", {all[0], all[1], all[5], all[6]}, 16, 64);
}
