#pragma once
/// \file
/// \brief The scene description the integrator renders: camera, spectral materials,
/// emitters, triangle shapes, and the feature summary that picks the instantiation.
///
/// Pure data, no ray tracing: the `scene` module fills it (JSON or built-in scenes) and
/// builds an `Intersector` (render/intersector.hpp) over the same shapes, in the same
/// order, so that a hit's shape index is an index into `scene_desc::shapes`.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <glm/vec3.hpp>

#include "iris/spectrum/ior.hpp"
#include "iris/spectrum/tabulated.hpp"

namespace iris {

/// \brief A pinhole camera. `fov_y_degrees` is the full vertical field of view.
struct pinhole_camera {
    glm::vec3 position{0.0f, 0.0f, 5.0f};
    glm::vec3 look_at{0.0f, 0.0f, 0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fov_y_degrees = 40.0f;
    int width = 512;
    int height = 512;
};

/// \brief A wavelength-independent index of refraction (no dispersion).
struct constant_ior {
    double value = 1.5;
    constexpr double n(double /*lambda_nm*/) const noexcept { return value; }
};

/// \brief The refractive index models a dielectric can use.
using ior_model = std::variant<constant_ior, cauchy_ior, sellmeier_ior>;

/// \brief n(λ) of any `ior_model`.
inline double refractive_index(const ior_model& m, double lambda_nm) noexcept {
    return std::visit([&](const auto& x) { return x.n(lambda_nm); }, m);
}

/// \brief Does n depend on λ? (A Cauchy model with B = 0 does not.)
inline bool is_dispersive(const ior_model& m) noexcept {
    if (std::holds_alternative<constant_ior>(m)) return false;
    if (const auto* c = std::get_if<cauchy_ior>(&m)) return c->b_um2 != 0.0;
    return true;
}

namespace material {

/// \brief Lambertian reflector with spectral albedo in [0, 1].
struct diffuse {
    tabulated_spectrum reflectance;
};

/// \brief Glass-like interface. roughness = 0: smooth (specular, a delta BSDF);
/// roughness > 0: GGX microfacet with α = roughness. Dispersive if the IOR model is.
struct dielectric {
    ior_model ior = constant_ior{1.5};
    float roughness = 0.0f;
};

/// \brief Perfect specular reflector (mirror, polished metal) with spectral reflectance.
struct conductor {
    tabulated_spectrum reflectance;
};

}  // namespace material

using material_desc = std::variant<material::diffuse, material::dielectric, material::conductor>;

/// \brief An emitter's spectral radiance L(λ) (W·sr⁻¹·m⁻²·nm⁻¹ up to a constant),
/// already scaled (by luminance or power) when the description is built. Emission leaves
/// the front side of the triangles only (the side their normal points to) unless two-sided.
struct emitter_desc {
    std::string spd_name;        ///< e.g. "D65", "LED-B1", "blackbody:3000", "tabulated"
    tabulated_spectrum radiance; ///< L(λ), outside::zero beyond the table
    bool two_sided = false;
};

/// \brief A triangle mesh: positions and counter-clockwise (outward) index triples.
struct triangle_mesh {
    std::vector<glm::vec3> positions;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::size_t triangle_count() const noexcept { return triangles.size(); }
};

/// \brief One shape: its triangles (world space), its material and optionally the
/// emitter that makes it an area light.
struct shape_desc {
    std::string name;
    triangle_mesh mesh;
    std::uint32_t material = 0;
    std::optional<std::uint32_t> emitter;
};

/// \brief A constant radiance arriving from every direction that escapes the scene.
struct environment_desc {
    std::string spd_name;
    tabulated_spectrum radiance;
};

/// \brief What a scene contains, so the renderer instantiates only what it needs.
struct scene_features {
    bool dispersive_specular = false;  ///< a smooth dielectric with λ-dependent n
    bool dispersive_rough = false;     ///< a rough dielectric with λ-dependent n
    bool has_specular = false;         ///< any delta BSDF (mirror, smooth glass)
    bool has_environment = false;
    std::vector<std::string> emitter_spds;  ///< distinct SPD names of all emitters

    bool dispersive() const noexcept { return dispersive_specular || dispersive_rough; }
};

/// \brief Everything the integrator needs to render one image, minus the ray tracer.
struct scene_desc {
    std::string name;
    pinhole_camera camera;
    float lambda_min = 380.0f;  ///< spectral domain, nm
    float lambda_max = 780.0f;
    std::vector<std::string> material_names;  ///< parallel to `materials`
    std::vector<material_desc> materials;
    std::vector<emitter_desc> emitters;
    std::vector<shape_desc> shapes;
    std::optional<environment_desc> environment;

    std::size_t triangle_count() const noexcept {
        std::size_t n = 0;
        for (const auto& s : shapes) n += s.mesh.triangle_count();
        return n;
    }

    /// \brief The feature summary (only materials that some shape uses count).
    scene_features features() const {
        scene_features f;
        std::vector<bool> used(materials.size(), false);
        for (const auto& s : shapes)
            if (s.material < used.size()) used[s.material] = true;
        for (std::size_t i = 0; i < materials.size(); ++i) {
            if (!used[i]) continue;
            if (const auto* d = std::get_if<material::dielectric>(&materials[i])) {
                const bool disp = is_dispersive(d->ior);
                if (d->roughness > 0.0f) f.dispersive_rough |= disp;
                else {
                    f.dispersive_specular |= disp;
                    f.has_specular = true;
                }
            } else if (std::holds_alternative<material::conductor>(materials[i])) {
                f.has_specular = true;
            }
        }
        auto add = [&](const std::string& n) {
            for (const auto& e : f.emitter_spds)
                if (e == n) return;
            f.emitter_spds.push_back(n);
        };
        for (const auto& e : emitters) add(e.spd_name);
        if (environment) {
            f.has_environment = true;
            add(environment->spd_name);
        }
        return f;
    }
};

}  // namespace iris
