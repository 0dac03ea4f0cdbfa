// JSON text → scene_document: every check of docs/scene-format.md that does not need
// the geometry. Reading order: spectral domain (the IOR checks need it), camera,
// materials, named emitters, environment, shapes; then whole-scene checks.
#include "iris/scene/document.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <system_error>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "iris/render/lights/point.hpp"
#include "iris/spectrum/color.hpp"
#include "iris/spectrum/named.hpp"
#include "iris/spectrum/rgb_upsampling.hpp"
#include "reader.hpp"
#include "spectra.hpp"

namespace iris::scene {

std::string_view shape_type_name(shape_type t) noexcept {
    switch (t) {
        case shape_type::box: return "box";
        case shape_type::cube: return "cube";
        case shape_type::prism: return "prism";
        case shape_type::hollow_cube: return "hollow_cube";
        case shape_type::quad: return "quad";
        case shape_type::mesh: return "mesh";
        case shape_type::triangles: return "triangles";
        case shape_type::sphere: return "sphere";
        case shape_type::disk: return "disk";
        case shape_type::subdivision: return "subdivision";
    }
    return "?";
}

namespace {

using detail::describe;
using detail::join;
using detail::json;
using detail::reader;
using detail::source_context;

constexpr double max_coordinate = 1e6;  ///< |x| of positions and sizes, in scene units
constexpr long long max_resolution = 16384;
constexpr double max_luminance = 1e12;
constexpr double max_power = 1e15;

constexpr std::array shape_types{shape_type::box,  shape_type::cube, shape_type::prism, shape_type::hollow_cube,
                                 shape_type::quad, shape_type::mesh, shape_type::sphere};

glm::vec3 read_point(const reader& r, std::string_view what) {
    r.expect_array(3, what);
    glm::vec3 v;
    for (glm::length_t i = 0; i < 3; ++i)
        v[i] = static_cast<float>(r.at(static_cast<std::size_t>(i)).number_in(-max_coordinate, max_coordinate, false, false, "a coordinate"));
    return v;
}

float read_size(const reader& r) {
    return static_cast<float>(r.number_in(0.0, max_coordinate, true, false, "a size"));
}

// ---- spectral domain and camera ------------------------------------------------------

detail::domain read_domain(const reader& root) {
    detail::domain d;
    if (!root.has("spectral_domain")) return d;
    const reader r = root.at("spectral_domain");
    r.expect_array(2, "a spectral domain [min, max] in nm");
    d.min = r.at(0).number_in(cie::cmf_lambda_min, cie::cmf_lambda_max, false, false, "a wavelength in nm");
    d.max = r.at(1).number_in(cie::cmf_lambda_min, cie::cmf_lambda_max, false, false, "a wavelength in nm");
    if (!(d.max - d.min >= 1.0))
        r.fail("the spectral domain must span at least 1 nm (min < max), got [" + reader::shortest(d.min) + ", " +
               reader::shortest(d.max) + "]");
    return d;
}

pinhole_camera read_camera(const reader& root) {
    const reader r = root.at("camera");
    r.expect_object({"position", "look_at", "up", "fov", "resolution"}, "a camera object");
    pinhole_camera c;
    c.position = read_point(r.at("position"), "a position [x, y, z]");
    c.look_at = read_point(r.at("look_at"), "a point [x, y, z]");
    c.up = r.has("up") ? read_point(r.at("up"), "an up vector [x, y, z]") : glm::vec3(0.0f, 1.0f, 0.0f);
    c.fov_y_degrees = r.has("fov") ? static_cast<float>(r.at("fov").number_in(0.0, 180.0, true, true,
                                                                               "a vertical field of view in degrees"))
                                   : 40.0f;
    c.width = c.height = 256;
    if (r.has("resolution")) {
        const reader res = r.at("resolution");
        res.expect_array(2, "a resolution [width, height]");
        c.width = static_cast<int>(res.at(0).integer_in(1, max_resolution, "a width in pixels"));
        c.height = static_cast<int>(res.at(1).integer_in(1, max_resolution, "a height in pixels"));
    }
    const glm::vec3 view = c.look_at - c.position;
    const float len = glm::length(view);
    if (!(len > 1e-6f * std::max(1.0f, glm::length(c.position))))
        r.at("look_at").fail("the camera looks at its own position; look_at must differ from position");
    const glm::vec3 side = glm::cross(view / len, c.up);
    if (!(glm::length(side) > 1e-4f * glm::length(c.up)) || !(glm::length(c.up) > 0.0f))
        r.at(r.has("up") ? "up" : "look_at").fail("the up vector must not be zero or parallel to the viewing direction");
    return c;
}

// ---- materials and emitters -------------------------------------------------------------

/// A path the document names, relative to its directory, that must be an existing file.
std::filesystem::path existing_file(const reader& f, const std::filesystem::path& base_dir, const std::string& what) {
    const std::string name = f.string();
    if (name.empty()) f.fail("expected the file name of " + what + ", got an empty string");
    std::filesystem::path p(name);
    if (p.is_relative()) p = base_dir / p;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec))
        f.fail(what + " '" + name + "' not found (looked for " + p.lexically_normal().string() + ")");
    return p;
}

/// {"texture": FILE, "wrap": ..., "scale": ..., "encoding": ...}: a reflectance image.
texture_spec read_texture(const reader& r, const std::filesystem::path& base_dir) {
    r.expect_object({"texture", "wrap", "scale", "encoding", "uv_scale", "uv_offset"},
                    "a reflectance texture {\"texture\": FILE, \"wrap\": ..., \"scale\": ..., \"encoding\": ..., "
                    "\"uv_scale\": [su, sv], \"uv_offset\": [du, dv]}");
    texture_spec t;
    t.pointer = r.pointer();
    t.line = r.context().locations.find(r.pointer());
    const reader f = r.at("texture");
    t.file = existing_file(f, base_dir, "texture image");
    std::string ext = t.file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".exr" && ext != ".bmp" && ext != ".tga")
        f.fail("expected a texture image (.png, .jpg, .jpeg, .bmp, .tga: sRGB-encoded; .exr: linear), got '" +
               f.string() + "'");
    if (r.has("wrap")) {
        const reader w = r.at("wrap");
        const std::string v = w.string();
        if (v == "repeat") t.wrap = texture_wrap::repeat;
        else if (v == "clamp") t.wrap = texture_wrap::clamp;
        else if (v == "mirror") t.wrap = texture_wrap::mirror;
        else w.fail("unknown texture wrap '" + v + "'; expected repeat, clamp or mirror");
    }
    if (r.has("scale")) t.scale = r.at("scale").number_in(0.0, 1e6, true, false, "a scale of the texture's values");
    const auto pair = [&](std::string_view key, glm::vec2& out, bool nonzero) {
        if (!r.has(key)) return;
        const reader a = r.at(key);
        a.expect_array(2, nonzero ? "a uv scale [su, sv]" : "a uv offset [du, dv]");
        for (glm::length_t i = 0; i < 2; ++i) {
            const reader x = a.at(static_cast<std::size_t>(i));
            out[i] = static_cast<float>(x.number_in(-1e6, 1e6, false, false, nonzero ? "a uv scale factor" : "a uv offset"));
            if (nonzero && out[i] == 0.0f) x.fail("a uv scale factor must not be 0");
        }
    };
    pair("uv_scale", t.uv_scale, true);
    pair("uv_offset", t.uv_offset, false);
    if (r.has("encoding")) {
        const reader e = r.at("encoding");
        const std::string v = e.string();
        if (ext == ".exr") e.fail("an EXR texture is linear; 'encoding' applies to 8- and 16-bit images only");
        if (v == "srgb") t.srgb = true;
        else if (v == "linear") t.srgb = false;
        else e.fail("unknown texture encoding '" + v + "'; expected srgb or linear");
    }
    return t;
}

/// A dielectric's absorption (docs/scene-format.md): `absorption` σ_a per scene unit, or a
/// `transmittance` T (a reflectance-like spectrum in (0, 1]) kept over `transmittance_depth`
/// scene units, σ_a = −ln T / depth (T below 1e-6 is taken as 1e-6: σ_a stays finite).
std::optional<tabulated_spectrum> read_dielectric_absorption(const reader& r) {
    const bool sigma = r.has("absorption"), colour = r.has("transmittance"), depth = r.has("transmittance_depth");
    if (sigma && (colour || depth))
        r.at(colour ? "transmittance" : "transmittance_depth")
            .fail("give either 'absorption' or 'transmittance' with 'transmittance_depth', not both");
    if (sigma) return detail::read_coefficient(r.at("absorption"), detail::absorption_coefficient);
    if (colour != depth)
        r.at(colour ? "transmittance" : "transmittance_depth")
            .fail(colour ? "a 'transmittance' needs the 'transmittance_depth' (scene units) it is kept over"
                         : "a 'transmittance_depth' needs the 'transmittance' kept over it");
    if (!colour) return std::nullopt;
    const tabulated_spectrum t = detail::read_reflectance(r.at("transmittance"));
    const double dist = r.at("transmittance_depth").number_in(0.0, 1e9, true, false, "a depth in scene units");
    std::vector<double> lambda(t.wavelengths().begin(), t.wavelengths().end()), sigma_a;
    for (double v : t.values()) sigma_a.push_back(-std::log(std::max(v, 1e-6)) / dist);
    return tabulated_spectrum(std::move(lambda), std::move(sigma_a), outside::clamp);
}

/// A medium's scattering (docs/scene-format.md): {"sigma_s": σ_s, "g": asymmetry}.
medium_scattering read_scattering(const reader& r) {
    if (!r.is_object())
        r.fail("expected a scattering medium {\"sigma_s\": per scene unit, \"g\": asymmetry in (-1, 1)}, got " +
               describe(r.value()));
    r.expect_object({"sigma_s", "g"});
    medium_scattering m;
    m.sigma_s = detail::read_coefficient(r.at("sigma_s"), detail::scattering_coefficient);
    if (r.has("g"))
        m.g = static_cast<float>(r.at("g").number_in(-0.99, 0.99, false, false, "a Henyey-Greenstein asymmetry g in [-0.99, 0.99]"));
    return m;
}

/// The scene's own medium (docs/scene-format.md): absorption (as a dielectric's) and/or scattering.
std::optional<medium_desc> read_scene_medium(const reader& top) {
    if (!top.has("medium")) return std::nullopt;
    const reader r = top.at("medium");
    if (!r.is_object())
        r.fail("expected a medium {\"absorption\": ..., \"scattering\": {\"sigma_s\": ..., \"g\": ...}}, got " +
               describe(r.value()));
    r.expect_object({"absorption", "transmittance", "transmittance_depth", "scattering"});
    medium_desc m;
    m.absorption = read_dielectric_absorption(r);
    if (r.has("scattering")) m.scattering = read_scattering(r.at("scattering"));
    if (!m.absorption && !m.scattering)
        r.fail("a medium needs an 'absorption' (or a 'transmittance' with its 'transmittance_depth') or a 'scattering'");
    return m;
}

/// A thin film (docs/scene-format.md): {"thickness_nm": d, "ior": n} — any index form of a
/// dielectric's `ior`.
material::thin_film read_film(const reader& r, const detail::domain& d) {
    if (!r.is_object())
        r.fail("expected a thin film {\"thickness_nm\": nanometres, \"ior\": index}, got " + describe(r.value()));
    r.expect_object({"thickness_nm", "ior"});
    material::thin_film f;
    f.thickness_nm = r.at("thickness_nm").number_in(0.0, 1e5, true, false, "a film thickness in nanometres");
    f.ior = detail::read_ior(r.at("ior"), d);
    return f;
}

material_desc read_material(const reader& r, const detail::domain& d, const std::filesystem::path& base_dir,
                            std::vector<texture_spec>& textures) {
    if (!r.is_object()) r.fail("expected a material object, got " + describe(r.value()));
    const std::string type = r.at("type").string();
    if (type == "diffuse") {
        r.expect_object({"type", "reflectance"});
        const reader refl = r.at("reflectance");
        if (refl.is_object() && refl.has("texture")) {
            textures.push_back(read_texture(refl, base_dir));
            // the constant stands for the texture where one number is needed (the tools' summaries)
            material::diffuse m{tabulated_spectrum({360.0, 830.0}, {0.5, 0.5}, outside::clamp)};
            m.texture = static_cast<std::uint32_t>(textures.size() - 1);
            return m;
        }
        return material::diffuse{detail::read_reflectance(refl)};
    }
    if (type == "dielectric") {
        r.expect_object({"type", "ior", "roughness", "absorption", "transmittance", "transmittance_depth", "scattering", "film"});
        material::dielectric m;
        m.ior = detail::read_ior(r.at("ior"), d);
        if (r.has("roughness"))
            m.roughness = static_cast<float>(r.at("roughness").number_in(0.0, 1.0, false, false, "a GGX roughness"));
        m.absorption = read_dielectric_absorption(r);
        if (r.has("scattering")) m.scattering = read_scattering(r.at("scattering"));
        if (r.has("film")) m.film = read_film(r.at("film"), d);
        return m;
    }
    if (type == "conductor") {
        r.expect_object({"type", "reflectance", "metal", "eta", "k", "roughness", "film"});
        const float roughness =
            r.has("roughness") ? static_cast<float>(r.at("roughness").number_in(0.0, 1.0, false, false, "a GGX roughness")) : 0.0f;
        if (auto ior = detail::read_conductor_ior(r)) {
            // its reflectance at normal incidence stands for it where one spectrum is needed (the tools)
            std::vector<double> lambda, value;
            for (std::size_t i = 0; i < cie::cmf_samples; ++i) {
                const double l = cie::cmf_lambda_min + static_cast<double>(i);
                const double e = ior->eta(l), k = ior->k(l);
                lambda.push_back(l);
                value.push_back(((e - 1.0) * (e - 1.0) + k * k) / ((e + 1.0) * (e + 1.0) + k * k));
            }
            material::conductor m{tabulated_spectrum(std::move(lambda), std::move(value), outside::clamp)};
            m.ior = std::move(ior);
            m.roughness = roughness;
            if (r.has("film")) m.film = read_film(r.at("film"), d);
            return m;
        }
        if (r.has("film"))
            r.at("film").fail("a film on a conductor needs its complex index ('metal', or 'eta' and 'k'), not a 'reflectance'");
        material::conductor m{r.has("reflectance") ? detail::read_reflectance(r.at("reflectance"))
                                                    : tabulated_spectrum({360.0, 830.0}, {1.0, 1.0}, outside::clamp)};
        m.roughness = roughness;
        return m;
    }
    if (type == "mirror") {
        r.expect_object({"type", "reflectance"});
        return material::conductor{r.has("reflectance") ? detail::read_reflectance(r.at("reflectance"))
                                                        : tabulated_spectrum({360.0, 830.0}, {1.0, 1.0}, outside::clamp)};
    }
    if (type == "coated") {
        r.expect_object({"type", "base", "eta", "roughness", "thickness", "max_depth", "samples"});
        const reader b = r.at("base");
        material::coated m{material::diffuse{}};
        material_desc base = read_material(b, d, base_dir, textures);
        if (auto* diffuse = std::get_if<material::diffuse>(&base)) m.base = std::move(*diffuse);
        else if (auto* conductor = std::get_if<material::conductor>(&base)) {
            if (conductor->film) b.at("film").fail("a coat's conductor base cannot carry a thin film (not implemented)");
            m.base = std::move(*conductor);
        } else b.fail("a coat's base must be a diffuse, conductor or mirror material");
        if (r.has("eta")) m.eta = static_cast<float>(r.at("eta").number_in(1.0, 4.0, false, false, "the coat's index of refraction"));
        if (r.has("roughness"))
            m.roughness = static_cast<float>(r.at("roughness").number_in(0.0, 1.0, false, false, "a GGX roughness"));
        if (r.has("thickness"))
            m.thickness = static_cast<float>(r.at("thickness").number_in(0.0, 1e3, false, false, "the coat's optical thickness"));
        if (r.has("max_depth"))
            m.max_depth = static_cast<int>(r.at("max_depth").integer_in(1, 100, "the layer crossings a walk may make"));
        if (r.has("samples")) m.samples = static_cast<int>(r.at("samples").integer_in(1, 256, "random walks per evaluation"));
        return m;
    }
    r.at("type").fail("unknown material type '" + type + "'; expected one of diffuse, dielectric, conductor, mirror, coated");
}

struct parsed_emitter {
    emitter_desc desc;
    emitter_spec spec;
};

parsed_emitter read_emitter(const reader& r, const std::string& name, const detail::domain& d) {
    r.expect_object({"spd", "luminance", "power", "two_sided"}, "an emitter object");
    if (r.has("luminance") && r.has("power"))
        r.at("power").fail("give either 'luminance' or 'power', not both");
    const reader spd_at = r.at("spd");
    detail::named_spd spd = detail::read_spd(spd_at);
    parsed_emitter e;
    e.spec.name = name;
    e.spec.pointer = r.pointer();
    e.spec.line = r.context().locations.find(r.pointer());
    e.desc.spd_name = spd.name;
    e.desc.two_sided = r.has("two_sided") && r.at("two_sided").boolean();
    const double in_domain = detail::integrate_over(spd.table, d);
    if (!(in_domain > 0.0))
        spd_at.fail("the spectrum '" + spd.name + "' is zero over the spectral domain [" + reader::shortest(d.min) +
                    ", " + reader::shortest(d.max) + "] nm");
    if (r.has("power")) {
        const double w = r.at("power").number_in(0.0, max_power, true, false, "a radiant power in relative watts");
        e.spec.power = w;
        e.desc.radiance = spd.table.scaled(1.0 / in_domain);
    } else {
        const double y = r.has("luminance")
                             ? r.at("luminance").number_in(0.0, max_luminance, true, false, "a luminance Y")
                             : 1.0;
        const double k = white_normalisation(spd.table);
        if (!(k > 0.0) || !std::isfinite(k * y))
            spd_at.fail("the spectrum '" + spd.name + "' has no luminance (its Y over 360-830 nm is 0), so it cannot "
                        "be scaled to a luminance");
        e.desc.radiance = spd.table.scaled(k * y);
    }
    return e;
}


std::optional<environment_desc> read_environment(const reader& root, const detail::domain& d,
                                                 const std::filesystem::path& base_dir,
                                                 std::optional<environment_image_spec>& image) {
    if (!root.has("environment")) return std::nullopt;
    const reader r = root.at("environment");
    if (r.has("image")) {
        r.expect_object({"image", "mapping", "scale", "rotation"},
                        "an environment image {\"image\": FILE.exr, \"mapping\": ..., \"scale\": ..., \"rotation\": ...}");
        environment_image_spec spec;
        spec.pointer = r.pointer();
        spec.line = r.context().locations.find(r.pointer());
        const reader f = r.at("image");
        const std::string name = f.string();
        std::filesystem::path p(name);
        std::string ext = p.extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (name.empty() || ext != ".exr")
            f.fail("expected an OpenEXR image file (.exr, linear sRGB), got '" + name + "'");
        if (p.is_relative()) p = base_dir / p;
        std::error_code ec;
        if (!std::filesystem::is_regular_file(p, ec))
            f.fail("environment image '" + name + "' not found (looked for " + p.lexically_normal().string() + ")");
        spec.file = p;
        if (r.has("mapping")) {
            const reader m = r.at("mapping");
            const std::string v = m.string();
            if (v == "latlong") spec.mapping = environment_mapping::latlong;
            else if (v == "equal-area") spec.mapping = environment_mapping::equal_area;
            else m.fail("unknown environment mapping '" + v + "'; expected latlong or equal-area");
        }
        if (r.has("scale"))
            spec.scale = r.at("scale").number_in(0.0, max_luminance, true, false, "a scale of the image's radiance");
        if (r.has("rotation")) {  // rows of the matrix taking the map's directions to the world's
            const reader m = r.at("rotation");
            m.expect_array(3, "a rotation: three rows [[a, b, c], [d, e, f], [g, h, i]]");
            glm::mat3 to_world;
            for (glm::length_t i = 0; i < 3; ++i) {
                const glm::vec3 row = read_point(m.at(static_cast<std::size_t>(i)), "a row [a, b, c] of the rotation");
                for (glm::length_t j = 0; j < 3; ++j) to_world[j][i] = row[j];  // glm: [column][row]
            }
            const glm::mat3 e = glm::transpose(to_world) * to_world;
            for (glm::length_t i = 0; i < 3; ++i)
                for (glm::length_t j = 0; j < 3; ++j)
                    if (std::fabs(e[i][j] - (i == j ? 1.0f : 0.0f)) > 1e-4f)
                        m.fail("the rotation must be orthogonal (its rows unit length and perpendicular, to 1e-4)");
            spec.to_map = glm::transpose(to_world);
        }
        image = spec;
        const auto d65 = find_illuminant("D65");
        environment_desc env;
        env.spd_name = "D65";
        env.radiance = d65->spectrum().scaled(white_normalisation(d65->spectrum()));
        env.basis = detail::environment_basis(d65->spectrum());
        return env;
    }
    r.expect_object({"spd", "luminance"}, "an environment object {\"spd\": ..., \"luminance\": ...} or {\"image\": FILE.exr, ...}");
    const reader spd_at = r.at("spd");
    detail::named_spd spd = detail::read_spd(spd_at);
    if (!(detail::integrate_over(spd.table, d) > 0.0))
        spd_at.fail("the spectrum '" + spd.name + "' is zero over the spectral domain");
    const double y = r.has("luminance") ? r.at("luminance").number_in(0.0, max_luminance, true, false, "a luminance Y") : 1.0;
    const double k = white_normalisation(spd.table);
    if (!(k > 0.0) || !std::isfinite(k * y)) spd_at.fail("the spectrum '" + spd.name + "' has no luminance");
    return environment_desc{spd.name, spd.table.scaled(k * y), std::nullopt, {}};
}

// ---- lights that are not shapes ------------------------------------------------------

/// One point, spot or distant light: its geometry into `s.lights`, its spectrum as a new
/// emitter (I(λ) or E(λ), scaled here: nothing about it depends on the meshes).
void read_light(const reader& r, const detail::domain& d, scene_document& doc) {
    if (!r.is_object()) r.fail("expected a light object {\"type\": \"point\"|\"spot\"|\"distant\", ...}, got " + describe(r.value()));
    const std::string type = r.at("type").string();
    scene_desc& s = doc.desc;
    const auto emitter = static_cast<std::uint32_t>(s.emitters.size());
    double solid_angle = 0.0;  // ∫s dω of a point or spot light, for "power"
    std::string_view scale_key;
    if (type == "point") {
        r.expect_object({"type", "position", "spd", "intensity", "power"}, "a point light");
        s.lights.push_back(light::point{read_point(r.at("position"), "a position [x, y, z]"), emitter});
        solid_angle = 4.0 * std::numbers::pi;
        scale_key = "intensity";
    } else if (type == "spot") {
        r.expect_object({"type", "position", "look_at", "cone_angle", "falloff_angle", "spd", "intensity", "power"},
                        "a spot light");
        light::spot sp;
        sp.position = read_point(r.at("position"), "a position [x, y, z]");
        const glm::vec3 target = read_point(r.at("look_at"), "a point [x, y, z] the spot is aimed at");
        const glm::vec3 axis = target - sp.position;
        if (!(glm::length(axis) > 0.0f)) r.at("look_at").fail("the spot's look_at must differ from its position");
        sp.direction = glm::normalize(axis);
        const double cone = r.at("cone_angle").number_in(0.0, 180.0, true, false, "the cone's half-angle in degrees");
        const double falloff = r.has("falloff_angle")
                                   ? r.at("falloff_angle").number_in(0.0, cone, false, false,
                                                                     "the half-angle in degrees where the falloff starts (at most cone_angle)")
                                   : cone;
        sp.cos_total_width = static_cast<float>(std::cos(cone * std::numbers::pi / 180.0));
        sp.cos_falloff_start = static_cast<float>(std::cos(falloff * std::numbers::pi / 180.0));
        if (!(sp.cos_total_width < 1.0f))
            r.at("cone_angle").fail("the cone is too narrow: at " + reader::shortest(cone) +
                                    " degrees it holds no direction in single precision (give at least 0.015 degrees)");
        sp.emitter = emitter;
        s.lights.push_back(sp);
        solid_angle = std::numbers::pi * static_cast<double>(lights::point_light::from(sp).solid_angle_over_pi());
        scale_key = "intensity";
    } else if (type == "distant") {
        r.expect_object({"type", "direction", "spd", "irradiance"}, "a distant light");
        const glm::vec3 dir = read_point(r.at("direction"), "the direction [x, y, z] the light travels");
        if (!(glm::length(dir) > 0.0f)) r.at("direction").fail("the direction must not be zero");
        s.lights.push_back(light::distant{glm::normalize(dir), emitter});
        scale_key = "irradiance";
    } else {
        r.at("type").fail("unknown light type '" + type + "'; expected one of point, spot, distant");
    }
    if (r.has(scale_key) && r.has("power")) r.at("power").fail("give either '" + std::string(scale_key) + "' or 'power', not both");
    const reader spd_at = r.at("spd");
    detail::named_spd spd = detail::read_spd(spd_at);
    const double in_domain = detail::integrate_over(spd.table, d);
    if (!(in_domain > 0.0))
        spd_at.fail("the spectrum '" + spd.name + "' is zero over the spectral domain [" + reader::shortest(d.min) + ", " +
                    reader::shortest(d.max) + "] nm");
    emitter_desc e;
    e.spd_name = spd.name;
    emitter_spec spec;
    spec.name = type + " light";
    spec.pointer = r.pointer();
    spec.line = r.context().locations.find(r.pointer());
    if (r.has("power")) {  // Φ = ∫s dω · ∫I dλ
        const double w = r.at("power").number_in(0.0, max_power, true, false, "a radiant power in relative watts");
        const double k = w / (solid_angle * in_domain);
        if (!(k > 0.0) || !std::isfinite(k))
            r.at("power").fail("cannot scale to a power of " + reader::shortest(w) + ": the light's intensity would not be finite");
        e.radiance = spd.table.scaled(k);
    } else {
        const double y = r.has(scale_key) ? r.at(scale_key).number_in(0.0, max_luminance, true, false,
                                                                      "a luminance Y (of the intensity or irradiance)")
                                          : 1.0;
        const double k = white_normalisation(spd.table);
        if (!(k > 0.0) || !std::isfinite(k * y))
            spd_at.fail("the spectrum '" + spd.name + "' has no luminance (its Y over 360-830 nm is 0), so it cannot "
                        "be scaled to a luminance");
        e.radiance = spd.table.scaled(k * y);
    }
    s.emitters.push_back(std::move(e));
    doc.emitters.push_back(std::move(spec));
}

// ---- shapes -------------------------------------------------------------------------

glm::mat4 read_transform(const reader& r) {
    if (!r.is_array())
        r.fail("expected a list of steps [{\"scale\": ...}, {\"rotate\": {...}}, {\"translate\": [...]}], got " +
               describe(r.value()));
    glm::mat4 m(1.0f);
    for (std::size_t i = 0; i < r.size(); ++i) {
        const reader step = r.at(i);
        step.expect_object({"translate", "scale", "rotate"}, "a transform step");
        if (step.size() != 1) step.fail("a transform step has exactly one of 'translate', 'scale', 'rotate'");
        glm::mat4 s(1.0f);
        if (step.has("translate")) {
            s = glm::translate(glm::mat4(1.0f), read_point(step.at("translate"), "a translation [x, y, z]"));
        } else if (step.has("scale")) {
            const reader k = step.at("scale");
            glm::vec3 v;
            if (k.is_number()) {
                v = glm::vec3(static_cast<float>(k.number_in(0.0, max_coordinate, true, false, "a scale factor")));
            } else {
                v = read_point(k, "a scale [x, y, z]");
                for (glm::length_t c = 0; c < 3; ++c)
                    if (!(std::fabs(v[c]) >= 1e-6f))
                        k.at(static_cast<std::size_t>(c)).fail("a scale factor must not be 0 (|s| >= 1e-6)");
            }
            s = glm::scale(glm::mat4(1.0f), v);
        } else {
            const reader rot = step.at("rotate");
            rot.expect_object({"axis", "degrees"}, "a rotation {\"axis\": [x, y, z], \"degrees\": D}");
            const glm::vec3 axis = read_point(rot.at("axis"), "an axis [x, y, z]");
            if (!(glm::length(axis) > 1e-6f)) rot.at("axis").fail("the rotation axis must not be zero");
            const double deg = rot.at("degrees").number_in(-1e6, 1e6, false, false, "an angle in degrees");
            s = glm::rotate(glm::mat4(1.0f), static_cast<float>(glm::radians(deg)), glm::normalize(axis));
        }
        m = s * m;  // steps apply in the order listed
    }
    return m;
}

std::filesystem::path resolve_mesh(const reader& r, const std::filesystem::path& base_dir) {
    const std::string name = r.string();
    if (name.empty()) r.fail("expected a mesh file name, got an empty string");
    std::filesystem::path p(name);
    std::string ext = p.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext != ".obj" && ext != ".ply" && ext != ".off")
        r.fail("unsupported mesh format '" + p.extension().string() + "' of '" + name + "'; expected .obj, .ply or .off");
    if (p.is_relative()) p = base_dir / p;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec))
        r.fail("mesh file '" + name + "' not found (looked for " + p.lexically_normal().string() + ")");
    return p;
}

shape_type read_shape_type(const reader& r) {
    const std::string t = r.string();
    for (const auto s : shape_types)
        if (shape_type_name(s) == t) return s;
    std::vector<std::string_view> names;
    for (const auto s : shape_types) names.push_back(shape_type_name(s));
    r.fail("unknown shape type '" + t + "'; expected one of " + join(names));
}

}  // namespace

scene_document parse_scene_document(std::string_view text, const std::string& source_name,
                                    const std::filesystem::path& base_dir) {
    source_context ctx;
    ctx.name = source_name;
    json root;
    try {
        root = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
    } catch (const nlohmann::json::parse_error& e) {
        // e.byte is 1-based: the position of the character that broke the syntax
        const auto p = detail::position_of(text, e.byte > 0 ? e.byte - 1 : 0);
        std::string msg = e.what();
        // "[json.exception.parse_error.101] parse error at line 2, column 7: syntax error while …"
        if (const auto colon = msg.find(": "); colon != std::string::npos && msg.rfind("[json.", 0) == 0)
            msg = msg.substr(colon + 2);
        throw error(source_name, p.line, "", msg + " (column " + std::to_string(p.column) + ")");
    } catch (const nlohmann::json::exception& e) {
        // number overflow ("number overflow parsing '1e999'") carries no position: find the literal
        std::string msg = e.what();
        std::size_t line = 0;
        if (const auto q = msg.find('\''); q != std::string::npos) {
            const auto q2 = msg.find('\'', q + 1);
            if (q2 != std::string::npos) {
                const auto at = text.find(std::string_view(msg).substr(q + 1, q2 - q - 1));
                if (at != std::string_view::npos) line = detail::position_of(text, at).line;
            }
        }
        if (const auto b = msg.find("] "); b != std::string::npos) msg = msg.substr(b + 2);
        throw error(source_name, line, "", msg + " (a number outside the range of a double)");
    }
    ctx.locations = detail::locate_json_values(text);
    if (!ctx.locations.duplicates.empty()) {
        const auto& d = ctx.locations.duplicates.front();
        throw error(source_name, d.line, d.pointer.substr(0, d.pointer.rfind('/')),
                    "duplicate key '" + d.pointer.substr(d.pointer.rfind('/') + 1) + "'");
    }

    const reader top(root, "", ctx);
    top.expect_object({"name", "description", "spectral_domain", "camera", "materials", "emitters", "environment", "lights",
                       "medium", "shapes"},
                      "a scene object {\"camera\": ..., \"materials\": ..., \"shapes\": [...]}");

    scene_document doc;
    doc.source = source_name;
    scene_desc& s = doc.desc;
    s.name = top.has("name") ? top.at("name").string() : std::filesystem::path(source_name).stem().string();
    if (s.name.empty()) top.at("name").fail("the scene name must not be empty");
    if (top.has("description")) doc.description = top.at("description").string();

    const detail::domain dom = read_domain(top);
    s.lambda_min = static_cast<float>(dom.min);
    s.lambda_max = static_cast<float>(dom.max);
    s.camera = read_camera(top);

    // materials: an object, name → material; indices follow the file's order
    std::map<std::string, std::uint32_t> material_index;
    if (top.has("materials")) {
        const reader mats = top.at("materials");
        if (!mats.is_object()) mats.fail("expected an object of named materials, got " + describe(mats.value()));
        for (const auto& [name, v] : mats.value().items()) {
            if (name.empty()) mats.fail("a material name must not be empty");
            s.materials.push_back(read_material(mats.at(name), dom, base_dir, doc.textures));
            s.material_names.push_back(name);
            material_index[name] = static_cast<std::uint32_t>(s.materials.size() - 1);
        }
    }

    // named emitters: parsed now, kept only if a shape uses them (in order of first use)
    std::map<std::string, parsed_emitter> named;
    std::vector<std::string> named_order;
    if (top.has("emitters")) {
        const reader ems = top.at("emitters");
        if (!ems.is_object()) ems.fail("expected an object of named emitters, got " + describe(ems.value()));
        for (const auto& [name, v] : ems.value().items()) {
            if (name.empty()) ems.fail("an emitter name must not be empty");
            named.emplace(name, read_emitter(ems.at(name), name, dom));
            named_order.push_back(name);
        }
    }
    std::map<std::string, std::uint32_t> used_named;

    s.environment = read_environment(top, dom, base_dir, doc.environment_image);
    s.medium = read_scene_medium(top);

    if (!top.has("shapes")) top.fail("missing key 'shapes' (the list of shapes); an empty scene cannot be rendered");
    const reader shapes = top.at("shapes");
    if (!shapes.is_array()) shapes.fail("expected an array of shapes, got " + describe(shapes.value()));
    if (shapes.size() == 0) shapes.fail("the scene is empty: 'shapes' has no shapes");

    for (std::size_t i = 0; i < shapes.size(); ++i) {
        const reader r = shapes.at(i);
        if (!r.is_object()) r.fail("expected a shape object, got " + describe(r.value()));
        shape_spec sh;
        sh.type = read_shape_type(r.at("type"));
        sh.pointer = r.pointer();
        sh.line = ctx.locations.find(r.pointer());
        switch (sh.type) {
            case shape_type::box:
                r.expect_object({"name", "type", "material", "emitter", "transform", "flip", "size"});
                sh.size = read_point(r.at("size"), "a size [x, y, z]");
                for (glm::length_t c = 0; c < 3; ++c)
                    if (!(sh.size[c] > 0.0f)) r.at("size").at(static_cast<std::size_t>(c)).fail("expected a size > 0, got " + reader::shortest(sh.size[c]));
                break;
            case shape_type::cube:
                r.expect_object({"name", "type", "material", "emitter", "transform", "flip", "size"});
                sh.size = glm::vec3(read_size(r.at("size")));
                break;
            case shape_type::quad: {
                r.expect_object({"name", "type", "material", "emitter", "transform", "flip", "size"});
                const reader sz = r.at("size");
                sz.expect_array(2, "a size [x, z]");
                sh.size = glm::vec3(read_size(sz.at(0)), 0.0f, read_size(sz.at(1)));
                break;
            }
            case shape_type::prism:
                r.expect_object({"name", "type", "material", "emitter", "transform", "flip", "side", "length"});
                sh.size = glm::vec3(read_size(r.at("side")), 0.0f, read_size(r.at("length")));
                break;
            case shape_type::hollow_cube: {
                r.expect_object({"name", "type", "material", "emitter", "transform", "flip", "size", "wall"});
                sh.size = glm::vec3(read_size(r.at("size")));
                const reader w = r.at("wall");
                sh.wall = read_size(w);
                if (!(sh.wall < 0.5f * sh.size.x))
                    w.fail("expected a wall thickness below half the size (" + reader::shortest(0.5 * sh.size.x) +
                           "), got " + reader::shortest(sh.wall));
                break;
            }
            case shape_type::mesh:
                r.expect_object({"name", "type", "material", "emitter", "transform", "flip", "file"});
                sh.file = resolve_mesh(r.at("file"), base_dir);
                break;
            case shape_type::sphere:
                r.expect_object({"name", "type", "material", "emitter", "transform", "flip", "radius"});
                sh.size = glm::vec3(read_size(r.at("radius")));
                break;
            case shape_type::triangles:
            case shape_type::disk:
            case shape_type::subdivision:
                break;  // a pbrt-v4 file's shapes: not in `shape_types`, never read from JSON
        }
        sh.name = r.has("name") ? r.at("name").string()
                                : std::string(shape_type_name(sh.type)) + "." + std::to_string(i);
        if (r.has("transform")) sh.transform = read_transform(r.at("transform"));
        if (r.has("flip")) sh.flip = r.at("flip").boolean();

        const reader m = r.at("material");
        const std::string mname = m.string();
        const auto mi = material_index.find(mname);
        if (mi == material_index.end())
            m.fail("unknown material '" + mname + "'; " +
                   (s.material_names.empty() ? std::string("the scene defines no materials")
                                             : "expected one of " + join(s.material_names)));
        sh.material = mi->second;

        if (r.has("emitter")) {
            const reader e = r.at("emitter");
            if (e.is_string()) {
                const std::string ename = e.string();
                if (const auto u = used_named.find(ename); u != used_named.end()) {
                    sh.emitter = u->second;
                } else {
                    const auto it = named.find(ename);
                    if (it == named.end())
                        e.fail("unknown emitter '" + ename + "'; " +
                               (named_order.empty() ? std::string("the scene defines no \"emitters\"")
                                                    : "expected one of " + join(named_order)) +
                               " (or an inline emitter object)");
                    s.emitters.push_back(it->second.desc);
                    doc.emitters.push_back(it->second.spec);
                    sh.emitter = used_named[ename] = static_cast<std::uint32_t>(s.emitters.size() - 1);
                }
            } else {
                parsed_emitter pe = read_emitter(e, sh.name, dom);
                s.emitters.push_back(std::move(pe.desc));
                doc.emitters.push_back(std::move(pe.spec));
                sh.emitter = static_cast<std::uint32_t>(s.emitters.size() - 1);
            }
        }
        doc.shapes.push_back(std::move(sh));
    }

    // lights after the shapes, so that the shapes' emitters keep their indices
    if (top.has("lights")) {
        const reader ls = top.at("lights");
        if (!ls.is_array()) ls.fail("expected an array of lights [{\"type\": \"point\", ...}], got " + describe(ls.value()));
        for (std::size_t i = 0; i < ls.size(); ++i) read_light(ls.at(i), dom, doc);
    }

    if (s.emitters.empty() && !s.environment)
        ctx.fail_at("/shapes", "",
                    "the scene has no emitter: give a shape an \"emitter\", add a \"lights\" entry or an \"environment\"");
    return doc;
}

}  // namespace iris::scene
