// A loaded scene in pbrt-v4's format (docs/pbrt-export.md): the camera, the film and every
// shape, material, emitter and light, with each spectrum written as an inline (λ, value)
// list, so that pbrt-v4 renders the spectra iris renders — not its own upsampling of an RGB
// colour or its own normalisation of a named illuminant. For the comparisons with pbrt-v4
// (bench/pbrt), and the round trip through the pbrt-v4 importer once it exists.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <set>
#include <span>
#include <sstream>
#include <string>
#include <variant>

#include <fmt/core.h>
#include <glm/geometric.hpp>

#include "iris/exr/exr.hpp"
#include "iris/scene/scene.hpp"
#include "iris/spectrum/color.hpp"

namespace iris::scene {
namespace {

/// Up to float's round-trip precision, with no trailing zeros.
std::string num(double v) { return fmt::format("{:.9g}", v); }

std::string point(const glm::vec3& p) { return num(p.x) + " " + num(p.y) + " " + num(p.z); }

/// The wavelengths at which a piecewise-linear function with knots `knots` is written on
/// [lo, hi]: every integer nanometre, the ends and the knots inside (so that pbrt-v4's
/// linear interpolation reproduces iris's exactly).
std::vector<double> sample_points(double lo, double hi, std::span<const double> knots) {
    std::set<double> xs{lo, hi};
    for (double x = std::ceil(lo); x <= hi; x += 1.0) xs.insert(x);
    for (double k : knots)
        if (k > lo && k < hi) xs.insert(k);
    return {xs.begin(), xs.end()};
}

template <class F>
std::string spectrum_list(const std::vector<double>& xs, F&& f) {
    std::string s = "[";
    for (std::size_t i = 0; i < xs.size(); ++i) s += (i % 8 == 0 ? "\n     " : " ") + num(xs[i]) + " " + num(f(xs[i]));
    return s + " ]";
}

/// A spectrum iris renders only inside its domain: written on [λmin, λmax]. pbrt-v4's inline
/// spectra are 0 outside their list, as iris's emission is outside its domain.
std::string domain_spectrum(const scene_desc& s, const tabulated_spectrum& t) {
    return spectrum_list(sample_points(s.lambda_min, s.lambda_max, t.wavelengths()), [&](double x) { return t(x); });
}

/// An index of refraction: pbrt-v4 reads it at all its wavelengths (360–830 nm) even where no
/// light is, and 0 there would be a division by zero in its Fresnel terms: iris's values are
/// held constant beyond its domain.
template <class F>
std::string ior_spectrum(const scene_desc& s, std::span<const double> knots, F&& n) {
    const double lo = cie::cmf_lambda_min, hi = cie::cmf_lambda_max;
    return spectrum_list(sample_points(lo, hi, knots), [&](double x) {
        return n(std::clamp(x, static_cast<double>(s.lambda_min), static_cast<double>(s.lambda_max)));
    });
}

/// pbrt-v4 divides a light's spectrum by its photometric integral Σ ȳ(λ) L(λ) (1 nm,
/// 360–830 nm) before multiplying by "scale", and its film's Y is ∫ ȳ L dλ; iris's film
/// divides by ∫ȳ (iris/spectrum/color.hpp, the same 1-nm sums). Writing Σ ȳ L / ∫ȳ — iris's
/// luminance of L — as the scale makes pbrt-v4's radiance L(λ)/∫ȳ, and its pixels iris's.
std::string light_scale(const scene_desc& s, const tabulated_spectrum& l, const std::string& what) {
    const auto inside = [&](double x) { return x >= s.lambda_min && x <= s.lambda_max ? l(x) : 0.0; };
    const double y = luminance(inside);
    if (!(y > 0.0))
        throw error(s.name, 0, "", what + " has no luminance in the domain: pbrt-v4 normalises a light by its luminance, "
                                          "which would be a division by zero");
    return num(y);
}

/// A name pbrt-v4 reads back inside quotes: letters, digits, '-', '_' and '.'; the index
/// keeps two names that clean up to the same string apart.
std::string sanitize(const std::string& name) {
    std::string out;
    for (char c : name)
        out += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.') ? c : '_';
    return out;
}
std::string clean_name(std::size_t i, const std::string& name) { return std::to_string(i) + "-" + sanitize(name); }

std::string roughness(float alpha) {
    // iris's roughness is GGX's α; pbrt-v4 would take the square root of a "roughness" unless
    // told not to remap it
    return fmt::format("\"float roughness\" [ {} ] \"bool remaproughness\" [ false ]", num(alpha));
}

struct material_writer {
    const scene_desc& s;
    const std::string& name;
    std::string operator()(const material::diffuse& d) const {
        if (d.texture)
            throw error(s.name, 0, "", "material '" + name +
                                           "' has an image texture: iris-scene export --pbrt writes constant "
                                           "spectra only (textures are not exported yet)");
        return "\"string type\" [ \"diffuse\" ]\n    \"spectrum reflectance\" " + domain_spectrum(s, d.reflectance);
    }
    std::string operator()(const material::dielectric& d) const {
        if (d.absorption)
            throw error(s.name, 0, "", "material '" + name +
                                           "' absorbs (an 'absorption'): pbrt-v4 expresses that as a medium inside the "
                                           "dielectric, which iris-scene export --pbrt does not write yet");
        if (d.scattering)
            throw error(s.name, 0, "", "material '" + name +
                                           "' holds a scattering medium: iris-scene export --pbrt does not write media yet");
        if (d.film)
            throw error(s.name, 0, "", "material '" + name + "' has a thin 'film', which pbrt-v4 has no material for");
        std::string out = "\"string type\" [ \"dielectric\" ]\n    ";
        if (!is_dispersive(d.ior)) out += "\"float eta\" [ " + num(refractive_index(d.ior, 550.0)) + " ]";
        else {
            const auto* t = std::get_if<tabulated_ior>(&d.ior);
            const std::span<const double> knots = t ? t->table.wavelengths() : std::span<const double>{};
            out += "\"spectrum eta\" " + ior_spectrum(s, knots, [&](double x) { return refractive_index(d.ior, x); });
        }
        if (d.roughness > 0.0f) out += "\n    " + roughness(d.roughness);
        return out;
    }
    std::string operator()(const material::conductor& c) const {
        if (c.film)
            throw error(s.name, 0, "", "material '" + name + "' has a thin 'film', which pbrt-v4 has no material for");
        std::string out = "\"string type\" [ \"conductor\" ]\n    ";
        if (c.ior) {
            out += "\"spectrum eta\" " + ior_spectrum(s, c.ior->eta.wavelengths(), [&](double x) { return c.ior->eta(x); });
            out += "\n    \"spectrum k\" " + ior_spectrum(s, c.ior->k.wavelengths(), [&](double x) { return c.ior->k(x); });
        } else {
            throw error(s.name, 0, "", "material '" + name +
                                           "' is a conductor given by its reflectance alone (an angle-independent "
                                           "mirror), which pbrt-v4 cannot express: give it a metal's eta and k");
        }
        out += "\n    " + roughness(c.roughness);
        return out;
    }
    std::string operator()(const material::coated& c) const {
        const std::string layer = fmt::format("\n    \"float thickness\" [ {} ] \"integer maxdepth\" [ {} ] \"integer nsamples\" [ {} ]",
                                              num(c.thickness), c.max_depth, c.samples);
        if (const auto* d = std::get_if<material::diffuse>(&c.base)) {
            std::string out = "\"string type\" [ \"coateddiffuse\" ]\n    " + (*this)(*d).substr(std::string("\"string type\" [ \"diffuse\" ]\n    ").size());
            return out + "\n    \"float eta\" [ " + num(c.eta) + " ]\n    " + roughness(c.roughness) + layer;
        }
        const auto& m = std::get<material::conductor>(c.base);
        if (!m.ior)
            throw error(s.name, 0, "", "material '" + name +
                                           "' is coated over a conductor given by its reflectance alone, which pbrt-v4 "
                                           "cannot express: give it a metal's eta and k");
        return "\"string type\" [ \"coatedconductor\" ]\n    \"spectrum conductor.eta\" " +
               ior_spectrum(s, m.ior->eta.wavelengths(), [&](double x) { return m.ior->eta(x); }) +
               "\n    \"spectrum conductor.k\" " + ior_spectrum(s, m.ior->k.wavelengths(), [&](double x) { return m.ior->k(x); }) +
               fmt::format("\n    \"float conductor.roughness\" [ {} ] \"float interface.roughness\" [ {} ] "
                           "\"float interface.eta\" [ {} ] \"bool remaproughness\" [ false ]",
                           num(m.roughness), num(c.roughness), num(c.eta)) +
               layer;
    }
};

struct light_writer {
    const scene_desc& s;
    std::string operator()(const light::point& p) const {
        const auto& e = s.emitters[p.emitter];
        return fmt::format("LightSource \"point\" \"point3 from\" [ {} ]\n    \"float scale\" [ {} ]\n    \"spectrum I\" {}\n",
                           point(p.position), light_scale(s, e.radiance, "emitter '" + e.spd_name + "'"), domain_spectrum(s, e.radiance));
    }
    std::string operator()(const light::spot& p) const {
        const auto& e = s.emitters[p.emitter];
        const double deg = 180.0 / std::numbers::pi;
        const double cone = std::acos(std::clamp(static_cast<double>(p.cos_total_width), -1.0, 1.0)) * deg;
        const double start = std::acos(std::clamp(static_cast<double>(p.cos_falloff_start), -1.0, 1.0)) * deg;
        return fmt::format(
            "LightSource \"spot\" \"point3 from\" [ {} ] \"point3 to\" [ {} ]\n    \"float coneangle\" [ {} ] "
            "\"float conedeltaangle\" [ {} ]\n    \"float scale\" [ {} ]\n    \"spectrum I\" {}\n",
            point(p.position), point(p.position + p.direction), num(cone), num(cone - start),
            light_scale(s, e.radiance, "emitter '" + e.spd_name + "'"), domain_spectrum(s, e.radiance));
    }
    std::string operator()(const light::distant& p) const {
        const auto& e = s.emitters[p.emitter];
        // pbrt-v4's light arrives from `from` − `to`: iris's direction is the way it travels
        return fmt::format("LightSource \"distant\" \"point3 from\" [ 0 0 0 ] \"point3 to\" [ {} ]\n    \"float scale\" [ {} ]\n"
                           "    \"spectrum L\" {}\n",
                           point(p.direction), light_scale(s, e.radiance, "emitter '" + e.spd_name + "'"), domain_spectrum(s, e.radiance));
    }
};

void write_mesh(std::ostream& out, const triangle_mesh& m) {
    out << "  Shape \"trianglemesh\"\n    \"point3 P\" [";
    for (std::size_t i = 0; i < m.positions.size(); ++i) out << (i % 4 == 0 ? "\n     " : "  ") << point(m.positions[i]);
    out << " ]\n    \"integer indices\" [";
    for (std::size_t i = 0; i < m.triangles.size(); ++i)
        out << (i % 8 == 0 ? "\n     " : "  ") << m.triangles[i][0] << ' ' << m.triangles[i][1] << ' ' << m.triangles[i][2];
    out << " ]\n";
    if (!m.normals.empty()) {
        out << "    \"normal N\" [";
        for (std::size_t i = 0; i < m.normals.size(); ++i) out << (i % 4 == 0 ? "\n     " : "  ") << point(m.normals[i]);
        out << " ]\n";
    }
    if (!m.uvs.empty()) {
        out << "    \"point2 uv\" [";
        for (std::size_t i = 0; i < m.uvs.size(); ++i)
            out << (i % 6 == 0 ? "\n     " : "  ") << num(m.uvs[i].x) << ' ' << num(m.uvs[i].y);
        out << " ]\n";
    }
}

}  // namespace

std::string pbrt_scene_text(const scene_desc& s, const pbrt_export_options& o) {
    if (o.spp < 1) throw error(s.name, 0, "", "pixel samples must be at least 1, not " + std::to_string(o.spp));
    if (o.max_depth < 0) throw error(s.name, 0, "", "max depth must be at least 0, not " + std::to_string(o.max_depth));
    static constexpr const char* integrators[] = {"volpath", "path", "bdpt", "lightpath", "simplepath", "mlt", "sppm"};
    if (std::find(std::begin(integrators), std::end(integrators), o.integrator) == std::end(integrators))
        throw error(s.name, 0, "", "unknown pbrt-v4 integrator '" + o.integrator +
                                       "'; expected volpath, path, bdpt, lightpath, simplepath, mlt or sppm");
    if (s.environment && s.environment->map)
        throw error(s.name, 0, "", "the environment is an image (" + s.environment->map->file +
                                       "): iris-scene export --pbrt writes constant spectra only (environment "
                                       "images are not exported yet)");

    std::ostringstream out;
    out << "# " << s.name << ", written by iris-scene export --pbrt (docs/pbrt-export.md): every spectrum is\n"
        << "# iris's own, inline; lights are scaled so that pbrt-v4's radiance is iris's L(lambda).\n";
    const auto& c = s.camera;
    // pbrt-v4's "fov" spans the shorter image side; iris's is vertical
    double fov = c.fov_y_degrees;
    if (c.height > c.width)
        fov = std::atan(std::tan(fov * std::numbers::pi / 360.0) * c.width / c.height) * 360.0 / std::numbers::pi;
    out << "Scale -1 1 1  # pbrt-v4's camera space is left-handed, iris's right-handed\n"
        << "LookAt " << point(c.position) << "  " << point(c.look_at) << "  " << point(c.up) << '\n'
        << "Camera \"perspective\" \"float fov\" [ " << num(fov) << " ]\n"
        << "Film \"rgb\" \"integer xresolution\" [ " << c.width << " ] \"integer yresolution\" [ " << c.height
        << " ]\n    \"string filename\" [ \"" << sanitize(s.name) << ".exr\" ]\n"
        << "PixelFilter \"box\" \"float xradius\" [ 0.5 ] \"float yradius\" [ 0.5 ]  # iris's pixel: each sample "
           "counts in its own\n"
        << "Sampler \"zsobol\" \"integer pixelsamples\" [ " << o.spp << " ]\n"
        << "Integrator \"" << o.integrator << "\" \"integer maxdepth\" [ " << o.max_depth << " ]\n"
        << "WorldBegin\n\n";

    for (std::size_t i = 0; i < s.materials.size(); ++i)
        out << "MakeNamedMaterial \"" << clean_name(i, s.material_names[i]) << "\"\n    "
            << std::visit(material_writer{s, s.material_names[i]}, s.materials[i]) << "\n";
    out << '\n';
    for (const auto& l : s.lights) out << std::visit(light_writer{s}, l);
    if (s.environment) {
        out << "LightSource \"infinite\" \"float scale\" [ " << light_scale(s, s.environment->radiance, "the environment")
            << " ]\n    \"spectrum L\" " << domain_spectrum(s, s.environment->radiance) << '\n';
    }
    for (const auto& sh : s.shapes) {
        out << "\nAttributeBegin  # " << sanitize(sh.name) << '\n'
            << "  NamedMaterial \"" << clean_name(sh.material, s.material_names.at(sh.material)) << "\"\n";
        if (sh.emitter) {
            const auto& e = s.emitters.at(*sh.emitter);
            out << "  AreaLightSource \"diffuse\" \"float scale\" [ " << light_scale(s, e.radiance, "emitter '" + e.spd_name + "'") << " ]"
                << (e.two_sided ? " \"bool twosided\" [ true ]" : "") << "\n    \"spectrum L\" "
                << domain_spectrum(s, e.radiance) << '\n';
        }
        write_mesh(out, sh.mesh);
        out << "AttributeEnd\n";
    }
    return out.str();
}

void export_pbrt(const scene_desc& s, const std::filesystem::path& path, const pbrt_export_options& o) {
    const std::string text = pbrt_scene_text(s, o);
    try {
        exr::write_atomically(path, [&](const std::filesystem::path& tmp) {
            std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
            f << text;
            f.close();
            if (!f) throw exr::error("cannot write " + tmp.string());
        });
    } catch (const exr::error& e) {
        throw error(path.string(), 0, "", std::string("cannot write the pbrt-v4 scene: ") + e.what());
    }
}

}  // namespace iris::scene
