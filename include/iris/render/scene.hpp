#pragma once
/// \file
/// \brief The scene description the integrator renders: camera, spectral materials,
/// emitters, triangle shapes, lights that are not shapes (point, spot, distant), the
/// environment (uniform or an image), and a summary of the scene's features.
///
/// Pure data, no ray tracing: the `scene` module fills it (JSON or built-in scenes) and
/// builds an `Intersector` (render/intersector.hpp) over the same shapes, in the same
/// order, so that a hit's shape index is an index into `scene_desc::shapes`.

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/mat3x3.hpp>

#include "iris/image.hpp"

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

/// \brief A tabulated index of refraction n(λ) (linear between the nodes, clamped beyond):
/// a pbrt-v4 scene's inline or named η spectrum.
struct tabulated_ior {
    tabulated_spectrum table;
    double n(double lambda_nm) const noexcept { return table(lambda_nm); }
};

/// \brief The refractive index models a dielectric can use.
using ior_model = std::variant<constant_ior, cauchy_ior, sellmeier_ior, tabulated_ior>;

/// \brief n(λ) of any `ior_model`.
inline double refractive_index(const ior_model& m, double lambda_nm) noexcept {
    return std::visit([&](const auto& x) { return x.n(lambda_nm); }, m);
}

/// \brief Does n depend on λ? (A Cauchy model with B = 0 does not.)
inline bool is_dispersive(const ior_model& m) noexcept {
    if (std::holds_alternative<constant_ior>(m)) return false;
    if (const auto* c = std::get_if<cauchy_ior>(&m)) return c->b_um2 != 0.0;
    if (const auto* t = std::get_if<tabulated_ior>(&m)) {
        const auto v = t->table.values();
        return std::any_of(v.begin(), v.end(), [&](double x) { return x != v.front(); });
    }
    return true;
}

/// \brief Below this GGX α a rough dielectric or conductor is treated as smooth (numerically a
/// delta BSDF).
inline constexpr float smooth_alpha = 1e-3f;

/// \brief Scattering in a homogeneous medium (docs/method.md §10): the scattering coefficient
/// σ_s(λ) ≥ 0 per scene unit and the Henyey–Greenstein asymmetry g ∈ (−1, 1), the same at
/// every wavelength (g > 0 scatters forward, g = 0 isotropically).
struct medium_scattering {
    tabulated_spectrum sigma_s;
    float g = 0.0f;
};

/// \brief The scene's own medium (fog, haze): it fills everything outside the solids that
/// bound a medium or glass of their own (docs/method.md §10); the camera and the lights are
/// in it. Absorption σ_a(λ) and scattering, each optional.
struct medium_desc {
    std::optional<tabulated_spectrum> absorption = std::nullopt;
    std::optional<medium_scattering> scattering = std::nullopt;
};

namespace material {

/// \brief A thin dielectric film on a surface (soap, oil, an anti-reflection or oxide
/// layer): `thickness_nm` ∈ (0, 10⁵] nanometres of a lossless, non-absorbing layer of index
/// `ior` (relative to the outside, ≥ 1, dispersive or not). Its reflectance is the exact
/// Airy sum of the light reflected back and forth inside the film, with the phase each
/// round trip adds, per wavelength and polarisation (docs/method.md §9): the colours of
/// interference. It changes how much is reflected and transmitted, not where light goes.
struct thin_film {
    double thickness_nm = 500.0;
    ior_model ior = constant_ior{1.33};
};

/// \brief Lambertian reflector with spectral albedo in [0, 1]: `reflectance`, or, with
/// `texture`, the image `scene_desc::textures[*texture]` looked up at the hit's uv.
struct diffuse {
    tabulated_spectrum reflectance;
    std::optional<std::uint32_t> texture = std::nullopt;
};

/// \brief Glass-like interface. roughness = 0: smooth (specular, a delta BSDF);
/// roughness > 0: GGX microfacet with α = roughness. Dispersive if the IOR model is. With
/// `absorption`, the solid it bounds absorbs: light crossing a length t of its inside keeps
/// exp(−σ_a(λ)·t), σ_a ≥ 0 per scene unit (Beer–Lambert; docs/method.md §8). Its inside is
/// the side its normals point away from. With `film`, a thin film on its outside face
/// replaces the bare interface's Fresnel reflectance R by the film's (transmission 1 − R: the
/// film is lossless), the same from both sides. With `scattering`, its inside is a
/// homogeneous scattering medium (with `absorption` as its σ_a; docs/method.md §10).
struct dielectric {
    ior_model ior = constant_ior{1.5};
    float roughness = 0.0f;
    std::optional<tabulated_spectrum> absorption = std::nullopt;
    std::optional<medium_scattering> scattering = std::nullopt;
    std::optional<thin_film> film = std::nullopt;
};

/// \brief A conductor's complex refractive index η(λ) + i·k(λ) (relative to the outside,
/// taken as vacuum), e.g. a named metal's (`find_metal`).
struct conductor_ior {
    std::string name;  ///< the metal's name, or "tabulated"
    tabulated_spectrum eta, k;
};

/// \brief A metal (or mirror): with `ior`, the exact Fresnel reflectance of a conductor of
/// complex index η + ik at every angle; without it, the angle-independent spectral
/// `reflectance` (an idealised mirror). roughness = 0: a perfect specular reflector (a
/// delta BSDF); roughness > 0: GGX microfacet reflection with α = roughness. With `film`
/// (only with `ior`, and not as a coat's base), a thin film on the metal: the film-on-metal
/// reflectance (docs/method.md §9) replaces the bare metal's Fresnel.
struct conductor {
    tabulated_spectrum reflectance;
    std::optional<conductor_ior> ior = std::nullopt;
    float roughness = 0.0f;
    std::optional<thin_film> film = std::nullopt;
};

/// \brief A base under a clear dielectric coat (pbrt-v4's `coateddiffuse` and
/// `coatedconductor`; docs/method.md §7): the base is a `diffuse` reflector (optionally
/// textured) or a `conductor`; the coat has a constant index `eta` ≥ 1, GGX roughness
/// `roughness` (smooth below `smooth_alpha`) and an absorbing thickness `thickness` (light
/// crossing it at cos θ keeps exp(−thickness/|cos θ|), pbrt-v4's convention); light is
/// followed through at most `max_depth` (≤ 100) crossings of the layer, as pbrt-v4's `maxdepth`,
/// and its random walk (rough coats) is averaged over `samples` walks.
struct coated {
    std::variant<diffuse, conductor> base;
    float eta = 1.5f;
    float roughness = 0.0f;
    float thickness = 0.01f;
    int max_depth = 10;
    int samples = 1;
    /// r_i, derived: the cosine-weighted mean, over the directions leaving the base, of the
    /// coat's internal reflectance times the round trip's transmittance exp(−2·thickness/cos θ)
    /// (`coated_internal_reflectance`, iris/render/materials/coated.hpp). The scene loader
    /// fills it; negative: each vertex that needs it computes it (slower, same value).
    float internal_reflectance = -1.0f;
};

}  // namespace material

using material_desc = std::variant<material::diffuse, material::dielectric, material::conductor, material::coated>;

/// \brief The diffuse reflector of material `m` — itself, or a coat's diffuse base — or null.
inline const material::diffuse* diffuse_part(const material_desc& m) noexcept {
    if (const auto* d = std::get_if<material::diffuse>(&m)) return d;
    if (const auto* c = std::get_if<material::coated>(&m)) return std::get_if<material::diffuse>(&c->base);
    return nullptr;
}
inline material::diffuse* diffuse_part(material_desc& m) noexcept {
    return const_cast<material::diffuse*>(diffuse_part(std::as_const(m)));
}

/// \brief An emitter's spectral radiance L(λ) (W·sr⁻¹·m⁻²·nm⁻¹ up to a constant),
/// already scaled (by luminance or power) when the description is built. Emission leaves
/// the front side of the triangles only (the side their normal points to) unless two-sided.
struct emitter_desc {
    std::string spd_name;        ///< e.g. "D65", "LED-B1", "blackbody:3000", "tabulated"
    tabulated_spectrum radiance; ///< L(λ), outside::zero beyond the table
    bool two_sided = false;
};

namespace light {

/// \brief An isotropic point light at `position`: intensity I(λ) (W·sr⁻¹·nm⁻¹ up to a
/// constant) is `scene_desc::emitters[emitter].radiance`; irradiance I cos θ / r².
struct point {
    glm::vec3 position{0.0f};
    std::uint32_t emitter = 0;
};

/// \brief A spot light: a point light whose intensity is I(λ)·s(cos θ) around the unit
/// axis `direction`, s = 1 inside the cone of half-angle acos(`cos_falloff_start`), 0
/// outside acos(`cos_total_width`), a smoothstep in cos θ between (pbrt-v4's falloff).
struct spot {
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, -1.0f, 0.0f};
    float cos_falloff_start = 1.0f;
    float cos_total_width = 0.0f;
    std::uint32_t emitter = 0;
};

/// \brief Parallel light travelling along the unit `direction`: irradiance E(λ) (the
/// emitter's `radiance` table) on a surface facing it.
struct distant {
    glm::vec3 direction{0.0f, -1.0f, 0.0f};
    std::uint32_t emitter = 0;
};

}  // namespace light

/// \brief The lights that are not emissive shapes.
using light_desc = std::variant<light::point, light::spot, light::distant>;

/// \brief A triangle mesh: positions and counter-clockwise (outward) index triples, and
/// optionally per-vertex shading normals and texture coordinates (empty: none; otherwise
/// one per position, checked where the ray tracer takes the mesh). The winding decides the
/// outside; a shading normal only bends the shading frame (iris/render/interaction.hpp).
struct triangle_mesh {
    std::vector<glm::vec3> positions;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<glm::vec3> normals;  ///< empty, or one (not necessarily unit) per position
    std::vector<glm::vec2> uvs;      ///< empty, or one per position
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

/// \brief What a texture lookup does outside [0, 1]²: repeat the image (pbrt-v4's default),
/// clamp to its edge texels, or repeat it mirrored.
enum class texture_wrap : std::uint8_t { repeat, clamp, mirror };

/// \brief A reflectance image: per texel the weights of the three reflectance basis spectra
/// (iris/spectrum/rgb_upsampling.hpp), each in [0, 1], row 0 at the top; looked up
/// bilinearly at uv with v up (iris/render/texture.hpp).
struct image_texture {
    int width = 0, height = 0;
    std::vector<glm::vec3> weights;  ///< width × height
    texture_wrap wrap = texture_wrap::repeat;
    /// The surface's uv mapped to the image's: (u·scale.x + offset.x, v·scale.y + offset.y)
    /// (pbrt-v4's `uscale`, `vscale`, `udelta`, `vdelta`).
    glm::vec2 uv_scale{1.0f}, uv_offset{0.0f};
    std::string file;                ///< where it came from (for messages and `iris-scene info`)
    std::size_t clipped_texels = 0;  ///< texels outside [0, 1] (after the scale) clamped into it
};

/// \brief How an environment image covers the sphere of directions (iris's +y is up).
enum class environment_mapping : std::uint8_t {
    latlong,     ///< x: φ = 2πx, y: θ = πy from +y; direction (sin θ cos φ, cos θ, sin θ sin φ)
    equal_area,  ///< pbrt-v4's equal-area octahedral square (Clarberg 2008), its +z as iris's +y
};

/// \brief An environment image: per texel the weights of the three emission basis spectra
/// (`environment_desc::basis`), already scaled, row 0 at the top.
struct environment_map {
    environment_mapping mapping = environment_mapping::latlong;
    int width = 0, height = 0;
    std::vector<glm::vec3> weights;  ///< width × height, each ≥ 0
    /// World direction → the map's frame (orthogonal; the identity unless the scene turns
    /// the environment, as a pbrt-v4 `LightSource "infinite"` under a transform does).
    glm::mat3 to_map{1.0f};
    std::string file;                ///< where it came from (for messages and `iris-scene info`)
    std::size_t negative_texels = 0; ///< texels with a negative (out-of-gamut) component, clamped to 0
};

/// \brief Radiance arriving from every direction that escapes the scene: a constant L(λ)
/// (`radiance`), or, with `map`, L(λ, ω) = Σ_i w_i(ω)·basis_i(λ) — an RGB image whose texels
/// are upsampled linearly (iris/spectrum/rgb_upsampling.hpp: a texel of linear sRGB (1, 1, 1)
/// is D65 at luminance 1), so that the C wavelengths and the B term's bins mix three
/// precomputed spectra per lookup. `radiance` is then the white the basis sums to.
struct environment_desc {
    std::string spd_name;
    tabulated_spectrum radiance;
    std::optional<environment_map> map;
    std::array<tabulated_spectrum, 3> basis;  ///< with `map` only: red, green, blue emission spectra
};

/// \brief What a scene contains, for the tools and the tests (`iris-scene info` prints it).
/// The renderer does not read it: it compiles one instantiation per preset and instruction
/// set, whatever the scene holds.
struct scene_features {
    bool dispersive_specular = false;  ///< a smooth dielectric with λ-dependent n
    bool dispersive_rough = false;     ///< a rough dielectric with λ-dependent n
    bool has_specular = false;         ///< any delta BSDF (mirror, smooth glass)
    bool has_environment = false;
    bool has_environment_map = false;
    bool has_delta_lights = false;     ///< point, spot or distant lights (no BSDF-only estimate)
    bool absorbing = false;            ///< a dielectric with `absorption`
    bool thin_film = false;            ///< a dielectric or conductor with a `film`
    bool scattering = false;           ///< a dielectric with `scattering`, or a scene medium that scatters
    bool scene_medium = false;         ///< the scene's own medium (`scene_desc::medium`)
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
    std::vector<light_desc> lights;  ///< emit through `emitters[light.emitter]`
    std::optional<environment_desc> environment;
    std::optional<medium_desc> medium;  ///< the medium outside every solid (fog), if any
    std::vector<image_texture> textures;  ///< indexed by the materials that use them
    /// What loading approximated or ignored, one sentence each (a pbrt-v4 file's lens, pixel
    /// filter, …): the tools print them as warnings (`iris::scene::approximations`).
    std::vector<std::string> notes;
    int default_spp = 0;        ///< the file's suggested samples per pixel (pbrt-v4's Sampler), 0: none
    int default_max_depth = 0;  ///< the file's suggested path length (pbrt-v4's Integrator), 0: none

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
                f.absorbing |= d->absorption.has_value();
                f.scattering |= d->scattering.has_value();
                f.thin_film |= d->film.has_value();
                const bool disp = is_dispersive(d->ior);
                if (d->roughness >= smooth_alpha) f.dispersive_rough |= disp;
                else {
                    f.dispersive_specular |= disp;
                    f.has_specular = true;
                }
            } else if (const auto* c = std::get_if<material::conductor>(&materials[i])) {
                f.has_specular |= c->roughness < smooth_alpha;
                f.thin_film |= c->film.has_value();
            } else if (const auto* k = std::get_if<material::coated>(&materials[i])) {
                f.has_specular |= k->roughness < smooth_alpha || k->eta == 1.0f;
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
            f.has_environment_map = environment->map.has_value();
            add(environment->spd_name);
        }
        f.has_delta_lights = !lights.empty();
        if (medium) {
            f.scene_medium = true;
            f.scattering |= medium->scattering.has_value();
        }
        return f;
    }
};

}  // namespace iris
