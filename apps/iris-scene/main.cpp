// iris-scene — list, inspect, check and export scenes.
//
//   iris-scene list                          the built-in scenes, one per line: NAME  description
//   iris-scene info NAME|FILE [--json]       triangles, materials, emitters, bounding box, camera,
//                                            spectral domain, feature summary, load time
//   iris-scene check FILE                    validate a scene file: "ok: …" (plus a warning for
//                                            each glass shape that is not a closed solid) and
//                                            exit 0, or the error (FILE:LINE: POINTER: what)
//                                            and exit 2
//   iris-scene export NAME|FILE -o OUT       every shape's triangles as one mesh; the format
//                                            follows OUT's extension: .obj, .ply or .off; or,
//                                            for OUT.pbrt, the whole scene in pbrt-v4's format
//                                            [--spp N] [--integrator NAME] [--max-depth D]
//                                            (docs/pbrt-export.md)
//
// NAME is a built-in scene (`iris-scene list`); anything else is read as a scene file
// (format: docs/scene-format.md), or a pbrt-v4 file if it ends in .pbrt (docs/pbrt-import.md;
// info and check take --strict: what the importer would approximate is an error). Bad input:
// one line on stderr, exit status 2.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include <fmt/core.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <iris/render/lights/point.hpp>
#include <iris/scene/scene.hpp>
#include <iris/spectrum/color.hpp>
#include <iris/version.hpp>

#include "cli.hpp"

namespace {

using iris::app::usage_error;

struct loaded {
    std::string source;  ///< "built-in (data/scenes/NAME.json)" or the file path
    iris::scene::scene_document doc;
    iris::scene_desc scene;
    double seconds = 0.0;
};

/// Parse and mesh, timing both; scene errors are the user's input → exit 2.
loaded load(const std::string& name_or_path, bool strict = false) {
    try {
        const auto t0 = std::chrono::steady_clock::now();
        loaded l;
        l.doc = iris::scene::load_scene_document(name_or_path, {.strict = strict});
        l.scene = iris::scene::build_scene(l.doc);
        l.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        l.source = iris::scene::builtin_scene_text(name_or_path) ? "built-in (data/scenes/" + name_or_path + ".json)"
                                                                 : l.doc.source;
        return l;
    } catch (const iris::scene::error& e) {
        throw usage_error(e.what());
    }
}

std::string film_summary(const std::optional<iris::material::thin_film>& f) {
    if (!f) return {};
    return fmt::format(" film={:g}nm n(550)={:.4f}", f->thickness_nm, iris::refractive_index(f->ior, 550.0));
}

std::string scattering_summary(const std::optional<iris::medium_scattering>& m) {
    if (!m) return {};
    return fmt::format(" scattering sigma_s(450/550/650)={:.4g}/{:.4g}/{:.4g} per unit g={:g}", m->sigma_s(450.0),
                       m->sigma_s(550.0), m->sigma_s(650.0), m->g);
}

std::string material_summary(const iris::scene_desc& s, const iris::material_desc& m) {
    struct summary {  // one call per alternative: a new material does not compile without its own
        const iris::scene_desc& s;
        std::string operator()(const iris::material::diffuse& d) const {
            if (!d.texture) return "diffuse";
            const auto& t = s.textures[*d.texture];
            const char* wrap = t.wrap == iris::texture_wrap::repeat ? "repeat" : t.wrap == iris::texture_wrap::clamp ? "clamp" : "mirror";
            std::string mapped;
            if (t.uv_scale != glm::vec2(1.0f) || t.uv_offset != glm::vec2(0.0f))
                mapped = fmt::format(" uv_scale={},{} uv_offset={},{}", t.uv_scale.x, t.uv_scale.y, t.uv_offset.x, t.uv_offset.y);
            return fmt::format("diffuse texture={} {}x{} wrap={}{}", t.file, t.width, t.height, wrap, mapped);
        }
        std::string operator()(const iris::material::conductor& c) const {
            const std::string rough = c.roughness > 0.0f ? fmt::format(" roughness={:g}", c.roughness) : std::string(" smooth");
            if (!c.ior) return "conductor" + rough;
            return fmt::format("conductor {} eta(550)={:.4g} k(550)={:.4g} R0(550)={:.4f}{}{}", c.ior->name, c.ior->eta(550.0),
                               c.ior->k(550.0), c.reflectance(550.0), rough, film_summary(c.film));
        }
        std::string operator()(const iris::material::dielectric& d) const {
            const char* model = std::holds_alternative<iris::constant_ior>(d.ior)  ? "constant"
                                : std::holds_alternative<iris::cauchy_ior>(d.ior)    ? "cauchy"
                                : std::holds_alternative<iris::sellmeier_ior>(d.ior) ? "sellmeier"
                                                                                     : "tabulated";
            return fmt::format("dielectric {} n(550)={:.4f}{}{}{}{}", model, iris::refractive_index(d.ior, 550.0),
                               iris::is_dispersive(d.ior) ? " dispersive" : "",
                               d.roughness > 0.0f ? fmt::format(" roughness={:g}", d.roughness) : std::string(" smooth"),
                               d.absorption ? fmt::format(" absorbing sigma_a(450/550/650)={:.4g}/{:.4g}/{:.4g} per unit",
                                                          (*d.absorption)(450.0), (*d.absorption)(550.0),
                                                          (*d.absorption)(650.0))
                                            : std::string(),
                               scattering_summary(d.scattering) + film_summary(d.film));
        }
        std::string operator()(const iris::material::coated& c) const {
            return fmt::format("coated eta={:g} {} thickness={:g} max_depth={}{} over {}", c.eta,
                               c.roughness > 0.0f ? fmt::format("roughness={:g}", c.roughness) : std::string("smooth"),
                               c.thickness, c.max_depth, c.samples > 1 ? fmt::format(" samples={}", c.samples) : std::string(),
                               std::visit(*this, c.base));
        }
    };
    return std::visit(summary{s}, m);
}


std::string light_summary(const iris::light_desc& l) {
    struct summary {  // one call per alternative: a new light does not compile without its own
        std::string operator()(const iris::light::point& p) const {
            return fmt::format("point position=[{:g}, {:g}, {:g}]", p.position.x, p.position.y, p.position.z);
        }
        std::string operator()(const iris::light::spot& p) const {
            return fmt::format("spot position=[{:g}, {:g}, {:g}] direction=[{:.4g}, {:.4g}, {:.4g}] cone={:.4g} "
                               "falloff={:.4g} degrees",
                               p.position.x, p.position.y, p.position.z, p.direction.x, p.direction.y, p.direction.z,
                               std::acos(p.cos_total_width) * 180.0 / std::numbers::pi,
                               std::acos(p.cos_falloff_start) * 180.0 / std::numbers::pi);
        }
        std::string operator()(const iris::light::distant& p) const {
            return fmt::format("distant direction=[{:.4g}, {:.4g}, {:.4g}]", p.direction.x, p.direction.y, p.direction.z);
        }
    };
    return std::visit(summary{}, l);
}

std::string environment_summary(const iris::scene_desc& s) {
    if (!s.environment) return "none";
    if (const auto& m = s.environment->map)
        return fmt::format("image {} {}x{} {}{}", m->file, m->width, m->height,
                           m->mapping == iris::environment_mapping::latlong ? "latlong" : "equal-area",
                           m->to_map != glm::mat3(1.0f) ? " turned" : "");
    return s.environment->spd_name;
}

struct emitter_stats {
    double area = 0.0;
    std::size_t shapes = 0;
    double luminance = 0.0;
    double power = 0.0;  ///< π·A·∫L dλ × sides, relative watts
};

std::vector<emitter_stats> emitter_statistics(const iris::scene_desc& s) {
    std::vector<emitter_stats> out(s.emitters.size());
    for (const auto& sh : s.shapes) {
        if (!sh.emitter) continue;
        auto& e = out[*sh.emitter];
        ++e.shapes;
        for (const auto& t : sh.mesh.triangles) {
            const glm::vec3 a = sh.mesh.positions[t[0]], b = sh.mesh.positions[t[1]], c = sh.mesh.positions[t[2]];
            e.area += 0.5 * static_cast<double>(glm::length(glm::cross(b - a, c - a)));
        }
    }
    for (std::size_t i = 0; i < out.size(); ++i) {
        const auto& l = s.emitters[i].radiance;
        out[i].luminance = iris::luminance(l);
        double integral = 0.0;
        for (double x = s.lambda_min; x < s.lambda_max; x += 1.0) {
            const double step = std::min(1.0, static_cast<double>(s.lambda_max) - x);
            integral += 0.5 * (l(x) + l(x + step)) * step;
        }
        out[i].power = std::numbers::pi * out[i].area * integral * (s.emitters[i].two_sided ? 2.0 : 1.0);
        for (const auto& li : s.lights)  // a point or spot light's power is its intensity times its solid angle
            std::visit(
                [&](const auto& x) {
                    using L = std::decay_t<decltype(x)>;
                    if constexpr (!std::is_same_v<L, iris::light::distant>)
                        if (x.emitter == i)
                            out[i].power = std::numbers::pi *
                                           static_cast<double>(iris::lights::point_light::from(x).solid_angle_over_pi()) *
                                           integral;
                },
                li);
    }
    return out;
}

struct bounds {
    glm::vec3 lo{std::numeric_limits<float>::infinity()}, hi{-std::numeric_limits<float>::infinity()};
};
bounds bounding_box(const iris::scene_desc& s) {
    bounds b;
    for (const auto& sh : s.shapes)
        for (const auto& p : sh.mesh.positions) {
            b.lo = glm::min(b.lo, p);
            b.hi = glm::max(b.hi, p);
        }
    return b;
}

void list() {
    for (const auto& b : iris::scene::builtin_scenes()) fmt::print("{:<18} {}\n", b.name, b.description);
}

void info(const std::string& name, bool json, bool strict) {
    const loaded l = load(name, strict);
    const auto& s = l.scene;
    const auto f = s.features();
    const auto es = emitter_statistics(s);
    const bounds b = bounding_box(s);
    if (json) {
        nlohmann::ordered_json j;
        j["name"] = s.name;
        j["description"] = l.doc.description;
        j["source"] = l.source;
        j["triangles"] = s.triangle_count();
        j["shapes"] = s.shapes.size();
        j["materials"] = nlohmann::ordered_json::array();
        for (std::size_t i = 0; i < s.materials.size(); ++i)
            j["materials"].push_back({{"name", s.material_names[i]}, {"type", material_summary(s, s.materials[i])}});
        j["emitters"] = s.emitters.size();
        j["emitter_list"] = nlohmann::ordered_json::array();
        for (std::size_t i = 0; i < s.emitters.size(); ++i)
            j["emitter_list"].push_back({{"name", l.doc.emitters[i].name},
                                         {"spd", s.emitters[i].spd_name},
                                         {"luminance", es[i].luminance},
                                         {"power", es[i].power},
                                         {"area", es[i].area},
                                         {"shapes", es[i].shapes},
                                         {"two_sided", s.emitters[i].two_sided}});
        j["environment"] = s.environment ? nlohmann::ordered_json(environment_summary(s)) : nlohmann::ordered_json();
        j["lights"] = nlohmann::ordered_json::array();
        for (const auto& li : s.lights) j["lights"].push_back(light_summary(li));
        j["bounds"] = {{"min", {b.lo.x, b.lo.y, b.lo.z}}, {"max", {b.hi.x, b.hi.y, b.hi.z}}};
        j["camera"] = {{"position", {s.camera.position.x, s.camera.position.y, s.camera.position.z}},
                       {"look_at", {s.camera.look_at.x, s.camera.look_at.y, s.camera.look_at.z}},
                       {"fov", s.camera.fov_y_degrees},
                       {"resolution", {s.camera.width, s.camera.height}}};
        j["spectral_domain"] = {s.lambda_min, s.lambda_max};
        j["dispersive_specular"] = f.dispersive_specular;
        j["dispersive_rough"] = f.dispersive_rough;
        j["has_specular"] = f.has_specular;
        j["has_environment"] = f.has_environment;
        j["has_environment_map"] = f.has_environment_map;
        j["has_delta_lights"] = f.has_delta_lights;
        j["absorbing"] = f.absorbing;
        j["thin_film"] = f.thin_film;
        j["scattering"] = f.scattering;
        j["scene_medium"] = f.scene_medium;
        j["emitter_spds"] = f.emitter_spds;
        j["approximated"] = iris::scene::approximations(s);
        j["load_seconds"] = l.seconds;
        fmt::print("{}\n", j.dump(2));
        return;
    }
    fmt::print("scene        {}\n", s.name);
    if (!l.doc.description.empty()) fmt::print("description  {}\n", l.doc.description);
    fmt::print("source       {}\n", l.source);
    fmt::print("triangles    {} in {} shapes\n", s.triangle_count(), s.shapes.size());
    fmt::print("materials    {}\n", s.materials.size());
    for (std::size_t i = 0; i < s.materials.size(); ++i)
        fmt::print("  {:<14} {}\n", s.material_names[i], material_summary(s, s.materials[i]));
    fmt::print("emitters     {}\n", s.emitters.size());
    for (std::size_t i = 0; i < s.emitters.size(); ++i)
        fmt::print("  {:<14} {} luminance={:g} power={:g} area={:g} shapes={}{}\n", l.doc.emitters[i].name,
                   s.emitters[i].spd_name, es[i].luminance, es[i].power, es[i].area, es[i].shapes,
                   s.emitters[i].two_sided ? " two-sided" : "");
    fmt::print("lights       {}\n", s.lights.size());
    for (const auto& li : s.lights) fmt::print("  {}\n", light_summary(li));
    fmt::print("environment  {}\n", environment_summary(s));
    if (s.medium)
        fmt::print("medium       {}{}\n",
                   s.medium->absorption ? fmt::format("absorbing sigma_a(450/550/650)={:.4g}/{:.4g}/{:.4g} per unit",
                                                      (*s.medium->absorption)(450.0), (*s.medium->absorption)(550.0),
                                                      (*s.medium->absorption)(650.0))
                                        : std::string("non-absorbing"),
                   scattering_summary(s.medium->scattering));
    for (const auto& m : iris::scene::approximations(s)) fmt::print("approximated {}\n", m);
    fmt::print("bounds       [{:g}, {:g}, {:g}] - [{:g}, {:g}, {:g}]\n", b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z);
    fmt::print("camera       {}x{} fov={:g} position=[{:g}, {:g}, {:g}] look_at=[{:g}, {:g}, {:g}]\n", s.camera.width,
               s.camera.height, s.camera.fov_y_degrees, s.camera.position.x, s.camera.position.y, s.camera.position.z,
               s.camera.look_at.x, s.camera.look_at.y, s.camera.look_at.z);
    fmt::print("domain       {:g}-{:g} nm\n", s.lambda_min, s.lambda_max);
    std::string spds;
    for (const auto& n : f.emitter_spds) spds += (spds.empty() ? "" : ",") + n;
    fmt::print("features     dispersive_specular={} dispersive_rough={} has_specular={} has_environment={} "
               "has_environment_map={} has_delta_lights={} absorbing={} thin_film={} scattering={} scene_medium={} "
               "emitter_spds={}\n",
               f.dispersive_specular, f.dispersive_rough, f.has_specular, f.has_environment, f.has_environment_map,
               f.has_delta_lights, f.absorbing, f.thin_film, f.scattering, f.scene_medium, spds);
    fmt::print("load         {:.2f} ms\n", l.seconds * 1e3);
}

void check(const std::string& file, bool strict) {
    const loaded l = load(file, strict);
    fmt::print("ok: {} ({} triangles, {} shapes, {} emitters)\n", l.scene.name, l.scene.triangle_count(),
               l.scene.shapes.size(), l.scene.emitters.size());
    for (const auto& m : iris::scene::approximations(l.scene)) fmt::print("warning: {}\n", m);
    // not errors (the scene renders), but glass without an inside refracts nonsense
    for (const auto& p : iris::scene::check_dielectric_solids(l.scene))
        fmt::print("warning: shape {} '{}' is glass but not a closed outward solid: {}\n", p.shape,
                   l.scene.shapes[p.shape].name, p.detail);
}

bool is_pbrt(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".pbrt";
}

/// `pbrt_flags`: the pbrt-only options given, refused for a mesh export.
/// `width`, `height`: the image's (0: the scene's).
void export_scene(const std::string& name, const std::string& out, const iris::scene::pbrt_export_options& pbrt,
                  const std::vector<std::string>& pbrt_flags, int width, int height) {
    if (!is_pbrt(out) && !pbrt_flags.empty())
        throw usage_error(pbrt_flags.front() + " applies to a pbrt-v4 export only (-o FILE.pbrt), not to " + out);
    loaded l = load(name);
    if (width > 0) l.scene.camera.width = width;
    if (height > 0) l.scene.camera.height = height;
    try {
        if (is_pbrt(out)) iris::scene::export_pbrt(l.scene, out, pbrt);
        else iris::scene::export_scene_mesh(l.scene, out);
    } catch (const iris::scene::error& e) {
        throw usage_error(e.what());
    }
    fmt::print("wrote {} ({} triangles)\n", out, l.scene.triangle_count());
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"iris-scene: list, inspect, check and export iris scenes", "iris-scene"};
    app.set_version_flag("--version", std::string(iris::version));
    app.require_subcommand(1);

    struct options {
        std::string scene, out;
        bool json = false, strict = false;
        iris::scene::pbrt_export_options pbrt;
        int width = 0, height = 0;  ///< 0: the scene's
    };
    auto o = std::make_shared<options>();

    app.add_subcommand("list", "List the built-in scenes with a short description")->callback(list);

    auto* info_cmd = app.add_subcommand("info", "Triangles, materials, emitters, bounds and feature summary of a scene");
    info_cmd->add_option("SCENE", o->scene, "built-in scene name or scene file")->required();
    info_cmd->add_flag("--json", o->json, "print one JSON object instead of text");
    info_cmd->add_flag("--strict", o->strict, "a pbrt-v4 scene: what the importer would approximate is an error");
    info_cmd->callback([o] { info(o->scene, o->json, o->strict); });

    auto* check_cmd = app.add_subcommand("check", "Validate a scene file: exit 0 if valid, 2 with the error otherwise");
    check_cmd->add_option("FILE", o->scene, "scene file (or built-in name)")->required();
    check_cmd->add_flag("--strict", o->strict, "a pbrt-v4 scene: what the importer would approximate is an error");
    check_cmd->callback([o] { check(o->scene, o->strict); });

    auto* export_cmd = app.add_subcommand(
        "export", "Write the scene's geometry as one mesh (.obj, .ply or .off), or the whole scene for pbrt-v4 (.pbrt)");
    export_cmd->add_option("SCENE", o->scene, "built-in scene name or scene file")->required();
    export_cmd->add_option("-o,--output", o->out, "output file; its extension picks the format")->required();
    auto* spp = export_cmd->add_option("--spp", o->pbrt.spp, "pbrt-v4 only: pixel samples (zsobol)")
                    ->check(CLI::Range(1, 1 << 30))->default_val(64);
    auto* integrator = export_cmd->add_option("--integrator", o->pbrt.integrator, "pbrt-v4 only: its integrator")
                           ->check(CLI::IsMember({"volpath", "path", "bdpt", "lightpath", "simplepath", "mlt", "sppm"}))
                           ->default_val("volpath");
    auto* depth = export_cmd->add_option("--max-depth", o->pbrt.max_depth, "pbrt-v4 only: its maxdepth")
                      ->check(CLI::Range(0, 1 << 20))->default_val(32);
    auto* width = export_cmd->add_option("--width", o->width, "pbrt-v4 only: image width (default: the scene's)")
                      ->check(CLI::Range(1, 1 << 16));
    auto* height = export_cmd->add_option("--height", o->height, "pbrt-v4 only: image height (default: the scene's)")
                       ->check(CLI::Range(1, 1 << 16));
    export_cmd->callback([o, spp, integrator, depth, width, height] {
        std::vector<std::string> given;
        for (const auto* opt : {spp, integrator, depth, width, height})
            if (opt->count() > 0) given.push_back(opt->get_name());
        export_scene(o->scene, o->out, o->pbrt, given, o->width, o->height);
    });

    return iris::app::run(app, argc, argv);
}
