#pragma once
// Small analytic scenes and a brute-force intersector for testing the integrator without
// Embree (the scene module's Embree intersector is tested against it elsewhere).
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <iris/render/intersector.hpp>
#include <iris/render/scene.hpp>
#include <iris/spectrum/color.hpp>

namespace iris::test {

/// \brief Möller–Trumbore over every triangle of every shape: slow, obviously right.
class brute_force_intersector {
public:
    explicit brute_force_intersector(const scene_desc& s) : m_scene(&s) {}

    std::optional<ray_hit> intersect(const glm::vec3& o, const glm::vec3& d, float t_max) const noexcept {
        std::optional<ray_hit> best;
        float t_best = t_max;
        for (std::uint32_t si = 0; si < m_scene->shapes.size(); ++si) {
            const auto& m = m_scene->shapes[si].mesh;
            for (std::uint32_t ti = 0; ti < m.triangles.size(); ++ti) {
                const auto& tr = m.triangles[ti];
                const glm::vec3 a = m.positions[tr[0]], b = m.positions[tr[1]], c = m.positions[tr[2]];
                const glm::vec3 e1 = b - a, e2 = c - a, pv = glm::cross(d, e2);
                const float det = glm::dot(e1, pv);
                if (std::fabs(det) < 1e-12f) continue;
                const float inv = 1.0f / det;
                const glm::vec3 tv = o - a;
                const float u = glm::dot(tv, pv) * inv;
                if (u < 0.0f || u > 1.0f) continue;
                const glm::vec3 qv = glm::cross(tv, e1);
                const float v = glm::dot(d, qv) * inv;
                if (v < 0.0f || u + v > 1.0f) continue;
                const float t = glm::dot(e2, qv) * inv;
                if (t > 0.0f && t < t_best) {
                    t_best = t;
                    best = ray_hit{t, si, ti, u, v, glm::cross(e1, e2)};
                }
            }
        }
        return best;
    }
    bool occluded(const glm::vec3& o, const glm::vec3& d, float t_max) const noexcept {
        return intersect(o, d, t_max).has_value();
    }

private:
    const scene_desc* m_scene;
};
static_assert(Intersector<brute_force_intersector>);

/// \brief An axis-aligned box with triangles facing inwards (seen from inside, CCW).
inline triangle_mesh inward_box(glm::vec3 lo, glm::vec3 hi) {
    triangle_mesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
    // outward-facing quads (CCW from outside), then flipped
    const std::array<std::array<std::uint32_t, 4>, 6> faces{{{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                                             {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}}};
    for (const auto& f : faces) {
        m.triangles.push_back({f[0], f[2], f[1]});
        m.triangles.push_back({f[0], f[3], f[2]});
    }
    return m;
}

inline tabulated_spectrum flat(double v) { return tabulated_spectrum({300.0, 900.0}, {v, v}, outside::clamp); }

/// \brief White furnace: a closed box, every wall diffuse with albedo `a` and emitting a
/// flat spectrum of luminance 1 inwards. Radiance everywhere: Y = 1 / (1 − a).
inline scene_desc furnace(double albedo = 0.8) {
    scene_desc s;
    s.name = "test-furnace";
    s.camera = {{0.1f, 0.2f, 0.3f}, {1.0f, 0.5f, -0.2f}, {0, 1, 0}, 60.0f, 4, 4};
    s.materials.push_back(material::diffuse{flat(albedo)});
    s.material_names.push_back("wall");
    const auto e = flat(1.0);
    s.emitters.push_back({"flat", e.scaled(white_normalisation(e)), false});
    s.shapes.push_back({"box", inward_box({-1, -1, -1}, {1, 1, 1}), 0, 0u});
    return s;
}

/// \brief The furnace with a dispersive glass cube (N-BK7 Sellmeier, or any IOR) inside.
/// A lossless dielectric in a uniform radiance field leaves it uniform at every
/// wavelength (radiance invariance, with the 1/η² scaling across the interface), so the
/// camera still sees Y = 1 / (1 − a) — through the glass as well.
inline scene_desc furnace_with_cube(double albedo, material_desc m, const std::string& name) {
    scene_desc s = furnace(albedo);
    s.camera.look_at = {0.0f, 0.0f, 0.0f};
    s.camera.position = {0.9f, 0.8f, 0.85f};
    s.materials.push_back(std::move(m));
    s.material_names.push_back(name);
    triangle_mesh cube = inward_box({-0.3f, -0.3f, -0.3f}, {0.3f, 0.3f, 0.3f});
    for (auto& t : cube.triangles) std::swap(t[1], t[2]);  // outward
    s.shapes.push_back({name + "-cube", cube, 1, std::nullopt});
    return s;
}
inline scene_desc furnace_with_glass(double albedo, ior_model ior, float roughness = 0.0f) {
    return furnace_with_cube(albedo, material::dielectric{ior, roughness}, "glass");
}

/// \brief A diffuse floor (albedo 0.5, 6 × 6) lit from 0.8 above by a small one-sided square
/// lamp (0.4 × 0.4, flat spectrum), seen from the side: direct light on a smooth, caustic-free
/// integrand, for the samplers' convergence test. The lamp is outside the view.
inline scene_desc lit_floor() {
    scene_desc s;
    s.name = "test-lit-floor";
    s.camera = {{0.0f, 0.6f, 1.6f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 40.0f, 8, 8};
    s.materials.push_back(material::diffuse{flat(0.5)});
    s.material_names.push_back("floor");
    const auto e = flat(1.0);
    s.emitters.push_back({"lamp", e.scaled(10.0 * white_normalisation(e)), false});
    auto quad = [](float half, float y, bool down) {
        triangle_mesh m;
        m.positions = {{-half, y, -half}, {-half, y, half}, {half, y, half}, {half, y, -half}};
        if (down)
            m.triangles = {{0, 2, 1}, {0, 3, 2}};  // normal −y
        else
            m.triangles = {{0, 1, 2}, {0, 2, 3}};  // normal +y
        return m;
    };
    s.shapes.push_back({"floor", quad(3.0f, 0.0f, false), 0, std::nullopt});
    s.shapes.push_back({"lamp", quad(0.2f, 0.8f, true), 0, 0u});
    return s;
}

}  // namespace iris::test
