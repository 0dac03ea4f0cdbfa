// scene_document → scene_desc: every shape recipe becomes world-space triangles
// (iris::geometry builds and transforms them), then power-specified emitters are scaled
// by the area they cover. Geometry failures become iris::scene::error at the shape.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>
#include <utility>
#include <variant>

#include <glm/geometric.hpp>

#include "iris/exr/exr.hpp"
#include "iris/geometry/mesh.hpp"
#include "iris/render/lights/directions.hpp"
#include "iris/render/materials/coated.hpp"
#include "iris/spectrum/rgb_upsampling.hpp"
#include "iris/scene/scene.hpp"

namespace iris::scene {
namespace {

/// The geometry module's mesh as the core's (the same layout; a copy if the types differ).
template <class Mesh>
iris::triangle_mesh to_core(Mesh&& m) {
    if constexpr (std::is_same_v<std::remove_cvref_t<Mesh>, iris::triangle_mesh>) {
        return std::forward<Mesh>(m);
    } else {
        iris::triangle_mesh c;
        c.positions = std::move(m.positions);
        c.triangles = std::move(m.triangles);
        return c;
    }
}

/// The quad recipe: size.x × size.z in the plane y = 0, centred, front face +y, uv over
/// [0, 1]² (u along +x, v along −z). Built here
/// (two triangles) so that its convention is exactly the documented one.
iris::triangle_mesh make_quad(float sx, float sz) {
    const float x = 0.5f * sx, z = 0.5f * sz;
    iris::triangle_mesh m;
    m.positions = {{-x, 0.0f, -z}, {-x, 0.0f, z}, {x, 0.0f, z}, {x, 0.0f, -z}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};  // (v1 − v0) × (v2 − v0) = +y
    m.uvs = {{0.0f, 1.0f}, {0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}};  // u along +x, v along −z: a texture reads upright from +z
    return m;
}

/// A sphere of radius r about the origin (pbrt-v4's `sphere`), tessellated: `sphere_rings`
/// rings between the poles (+z and −z, as pbrt-v4's), 2·`sphere_rings` segments each, vertices
/// on the sphere and shared (one per pole, the seam closed: a closed solid, as glass needs),
/// counter-clockwise seen from outside, with the sphere's normals. The flat facets
/// underestimate the area by about (π/segments)²/3.
constexpr int sphere_rings = 96;
iris::triangle_mesh make_sphere(float r) {
    iris::triangle_mesh m;
    const int rings = sphere_rings, segments = 2 * sphere_rings;
    const auto add = [&](double theta, double phi) {
        const glm::vec3 n(static_cast<float>(std::sin(theta) * std::cos(phi)), static_cast<float>(std::sin(theta) * std::sin(phi)),
                          static_cast<float>(std::cos(theta)));
        m.positions.push_back(r * n);
        m.normals.push_back(n);
    };
    add(0.0, 0.0);  // vertex 0: the north pole (+z)
    for (int i = 1; i < rings; ++i)
        for (int j = 0; j < segments; ++j) add(std::numbers::pi * i / rings, 2.0 * std::numbers::pi * j / segments);
    add(std::numbers::pi, 0.0);  // the south pole
    const auto south = static_cast<std::uint32_t>(m.positions.size() - 1);
    // ring i (1 … rings−1), segment j (mod segments)
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(1 + (i - 1) * segments + (j % segments)); };
    for (int j = 0; j < segments; ++j) {
        m.triangles.push_back({0, at(1, j), at(1, j + 1)});  // φ grows counter-clockwise seen from +z
        for (int i = 1; i + 1 < rings; ++i) {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
        m.triangles.push_back({at(rings - 1, j), south, at(rings - 1, j + 1)});
    }
    return m;
}

/// A disk (pbrt-v4's `disk`): radius r, an inner radius (an annulus), in the plane z = height,
/// facing +z, tessellated into 2·`sphere_rings` segments.
iris::triangle_mesh make_disk(float r, float inner, float height) {
    iris::triangle_mesh m;
    const int segments = 2 * sphere_rings;
    const bool annulus = inner > 0.0f;
    if (!annulus) {
        m.positions.emplace_back(0.0f, 0.0f, height);
        m.uvs.emplace_back(0.0f, 1.0f);
    }
    const std::uint32_t ring0 = static_cast<std::uint32_t>(m.positions.size());
    for (int j = 0; j < segments; ++j) {
        const double phi = 2.0 * std::numbers::pi * j / segments;
        const float c = static_cast<float>(std::cos(phi)), s = static_cast<float>(std::sin(phi));
        m.positions.emplace_back(r * c, r * s, height);
        m.uvs.emplace_back(static_cast<float>(j) / segments, 0.0f);
        if (annulus) {
            m.positions.emplace_back(inner * c, inner * s, height);
            m.uvs.emplace_back(static_cast<float>(j) / segments, 1.0f);
        }
    }
    for (int j = 0; j < segments; ++j) {
        const auto k = static_cast<std::uint32_t>(j), n = static_cast<std::uint32_t>((j + 1) % segments);
        if (!annulus) {
            m.triangles.push_back({0, ring0 + k, ring0 + n});  // counter-clockwise seen from +z
        } else {
            const std::uint32_t o0 = ring0 + 2 * k, i0 = o0 + 1, o1 = ring0 + 2 * n, i1 = o1 + 1;
            m.triangles.push_back({i0, o0, o1});
            m.triangles.push_back({i0, o1, i1});
        }
    }
    return m;
}

iris::triangle_mesh recipe(const shape_spec& s) {
    const glm::vec3 origin(0.0f);
    switch (s.type) {
        case shape_type::box: return to_core(geometry::make_box(-0.5f * s.size, 0.5f * s.size));
        case shape_type::cube: return to_core(geometry::make_cube(origin, s.size.x));
        case shape_type::prism: return to_core(geometry::make_prism(origin, s.size.x, s.size.z));
        case shape_type::hollow_cube:
            return to_core(geometry::make_hollow_cube(origin, s.size.x, s.size.x - 2.0f * s.wall));
        case shape_type::quad: return make_quad(s.size.x, s.size.z);
        case shape_type::mesh: return to_core(geometry::load_mesh(s.file));
        case shape_type::triangles: return s.triangles ? *s.triangles : iris::triangle_mesh{};
        case shape_type::sphere: return make_sphere(s.size.x);
        case shape_type::disk: return make_disk(s.size.x, s.size.y, s.size.z);
        case shape_type::subdivision: return s.triangles ? geometry::loop_subdivide(*s.triangles, s.levels) : iris::triangle_mesh{};
    }
    return {};
}

double triangle_area(const iris::triangle_mesh& m, const std::array<std::uint32_t, 3>& t) {
    const glm::dvec3 a(m.positions[t[0]]), b(m.positions[t[1]]), c(m.positions[t[2]]);
    return 0.5 * glm::length(glm::cross(b - a, c - a));
}

/// An environment image → per-texel weights of the three emission basis spectra: linear
/// sRGB (negative components — out of gamut — clamped to 0 and counted, for the tools'
/// warning), upsampled by the same matrix as reflectances but without their
/// [0, 1] clamp (radiance is unbounded), times the document's scale.
iris::environment_map read_environment_image(const scene_document& doc, const environment_image_spec& spec) {
    const auto fail = [&](const std::string& message) -> void {
        // a JSON document's pointer, or an imported pbrt-v4 file's line (no pointer)
        if (!spec.file_name.empty()) throw error(spec.file_name, spec.line, "", message);
        throw error(doc.source, spec.line, spec.pointer + "/image", message);
    };
    exr::loaded img;
    try {
        img = exr::read(spec.file);
    } catch (const exr::error& e) {
        fail(e.what());
    }
    iris::environment_map m;
    m.mapping = spec.mapping;
    m.to_map = spec.to_map;
    m.width = img.pixels.width();
    m.height = img.pixels.height();
    m.file = spec.file.string();
    if (m.width < 1 || m.height < 1) fail("the environment image has no pixels");
    if (spec.mapping == environment_mapping::equal_area && m.width != m.height)
        fail("an equal-area environment image must be square, got " + std::to_string(m.width) + "x" +
             std::to_string(m.height));
    double scale = spec.scale;
    if (spec.illuminance) {  // pbrt-v4's measure of an equal-area map's illuminance (document.hpp)
        double e = 0.0;
        for (int y = 0; y < m.height; ++y)
            for (int x = 0; x < m.width; ++x) {
                const glm::vec2 p{(static_cast<float>(x) + 0.5f) / static_cast<float>(m.width),
                                  (static_cast<float>(y) + 0.5f) / static_cast<float>(m.height)};
                const float up = iris::lights::equal_area_to_direction(p).y;  // the map's +z (its up)
                if (!(up > 0.0f)) continue;
                const auto& px = img.pixels(x, y);
                e += (0.2126 * px.r + 0.7152 * px.g + 0.0722 * px.b) * static_cast<double>(up);
            }
        e *= 2.0 * std::numbers::pi / (static_cast<double>(m.width) * static_cast<double>(m.height));
        if (!(e > 0.0)) fail("the environment image has no illuminance from above to scale to \"illuminance\"");
        scale *= *spec.illuminance / e;
    }
    const auto& a = iris::detail::rgb_upsampling_matrix();
    m.weights.reserve(img.pixels.pixel_count());
    double total = 0.0;
    for (const auto& p : img.pixels.pixels()) {
        if (!std::isfinite(p.r) || !std::isfinite(p.g) || !std::isfinite(p.b))
            fail("the environment image has a pixel that is not finite (NaN or infinity)");
        if (p.r < 0.0f || p.g < 0.0f || p.b < 0.0f) ++m.negative_texels;
        const double in[3] = {std::max(0.0f, p.r), std::max(0.0f, p.g), std::max(0.0f, p.b)};
        glm::vec3 w;
        for (int i = 0; i < 3; ++i) {
            const auto r = static_cast<std::size_t>(i);
            w[i] = static_cast<float>(scale * (a[r][0] * in[0] + a[r][1] * in[1] + a[r][2] * in[2]));
            if (!std::isfinite(w[i])) fail("the environment image's radiance times its scale is not finite");
        }
        total += static_cast<double>(w.x + w.y + w.z);
        m.weights.push_back(w);
    }
    if (!(total > 0.0)) fail("the environment image is black (no positive pixel)");
    return m;
}

/// A reflectance image → per-texel weights of the three reflectance basis spectra: values
/// decoded to linear sRGB (8/16-bit files from sRGB unless the document says linear; EXR
/// as stored), times the scale, clamped into [0, 1] (counted: a reflectance cannot exceed
/// 1), then upsampled as a constant reflectance is (`upsample_linear_srgb`).
iris::image_texture read_texture(const scene_document& doc, const texture_spec& spec) {
    const auto fail = [&](const std::string& message) -> void {
        // a JSON document's pointer, or an imported pbrt-v4 file's line (no pointer)
        if (!spec.file_name.empty()) throw error(spec.file_name, spec.line, "", message);
        throw error(doc.source, spec.line, spec.pointer + "/texture", message);
    };
    std::string ext = spec.file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    iris::image pixels;
    bool decode = false;
    try {
        if (ext == ".exr") {
            pixels = exr::read(spec.file).pixels;
        } else {
            pixels = exr::read_ldr(spec.file).pixels;
            decode = spec.srgb;
        }
    } catch (const exr::error& e) {
        fail(e.what());
    }
    iris::image_texture t;
    t.width = pixels.width();
    t.height = pixels.height();
    t.wrap = spec.wrap;
    t.uv_scale = spec.uv_scale;
    t.uv_offset = spec.uv_offset;
    t.file = spec.file.string();
    if (t.width < 1 || t.height < 1) fail("the texture image has no pixels");
    t.weights.reserve(pixels.pixel_count());
    for (const auto& p : pixels.pixels()) {
        double c[3] = {p.r, p.g, p.b};
        bool clipped = false;
        for (double& v : c) {
            if (!std::isfinite(v)) fail("the texture image has a pixel that is not finite (NaN or infinity)");
            if (decode) v = srgb_decode(v);
            v *= spec.scale;
            if (v < 0.0 || v > 1.0) clipped = true;
        }
        if (clipped) ++t.clipped_texels;
        const rgb_reflectance r = upsample_linear_srgb({c[0], c[1], c[2]});
        t.weights.emplace_back(static_cast<float>(r.red), static_cast<float>(r.green), static_cast<float>(r.blue));
    }
    return t;
}

}  // namespace

namespace {

bool same_table(const std::optional<tabulated_spectrum>& a, const std::optional<tabulated_spectrum>& b) {
    if (a.has_value() != b.has_value()) return false;
    return !a || (std::ranges::equal(a->wavelengths(), b->wavelengths()) && std::ranges::equal(a->values(), b->values()) &&
                  a->mode() == b->mode());
}

/// The dielectric's medium is the scene's own (the pbrt-v4 importer's glass that bounds no
/// medium, docs/pbrt-import.md): crossing its boundary changes nothing.
bool holds_the_scene_medium(const material::dielectric& d, const std::optional<medium_desc>& m) {
    if (!m || !same_table(d.absorption, m->absorption) || d.scattering.has_value() != m->scattering.has_value()) return false;
    return !d.scattering || (d.scattering->g == m->scattering->g &&
                             same_table(d.scattering->sigma_s, m->scattering->sigma_s));
}

}  // namespace

iris::scene_desc build_scene(const scene_document& doc) {
    iris::scene_desc s = doc.desc;
    s.shapes.clear();
    s.shapes.reserve(doc.shapes.size());
    std::vector<double> emitter_area(s.emitters.size(), 0.0);

    for (const auto& spec : doc.shapes) {
        const auto fail = [&](const std::string& message) -> void {
            throw error(spec.file_name.empty() ? doc.source : spec.file_name, spec.line,
                        spec.type == shape_type::mesh && !spec.pointer.empty() ? spec.pointer + "/file" : spec.pointer, message);
        };
        iris::triangle_mesh mesh;
        try {
            mesh = to_core(geometry::transformed(recipe(spec), spec.transform));
        } catch (const geometry::error& e) {
            fail(e.what());
        }
        if (spec.flip) {  // the other side out: the shading normals turn with the winding
            for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
            for (auto& n : mesh.normals) n = -n;
        }

        double area = 0.0;
        for (const auto& p : mesh.positions)
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                fail("the shape has non-finite coordinates after its transform");
        for (const auto& t : mesh.triangles) {
            if (t[0] >= mesh.positions.size() || t[1] >= mesh.positions.size() || t[2] >= mesh.positions.size())
                fail("a triangle indexes a vertex that does not exist");
            area += triangle_area(mesh, t);
        }
        if (!(area > 0.0)) fail("the shape has no triangle of non-zero area");
        if (spec.emitter) emitter_area[*spec.emitter] += area;
        // a medium is tracked by the crossings of its boundary (docs/method.md §10): it needs a
        // closed solid around it, facing out, or the rays' media go wrong without a sign
        if (spec.material < s.materials.size())
            if (const auto* d = std::get_if<material::dielectric>(&s.materials[spec.material]);
                d && (d->absorption || d->scattering) && !holds_the_scene_medium(*d, s.medium)) {
                geometry::triangle_mesh g;
                g.positions = mesh.positions;
                g.triangles = mesh.triangles;
                const auto c = geometry::check_mesh(g);
                if (!c.ok())
                    fail("its material '" + (spec.material < s.material_names.size() ? s.material_names[spec.material] : std::string("?")) +
                         "' holds a medium (" + (d->absorption ? "absorption" : "scattering") +
                         "), which needs a closed solid around it, facing out: " + (c.detail.empty() ? std::string("not a valid closed solid") : c.detail));
            }

        s.shapes.push_back({spec.name, std::move(mesh), spec.material, spec.emitter});
    }

    if (const auto& img = doc.environment_image) s.environment->map = read_environment_image(doc, *img);
    s.textures.clear();
    for (const auto& spec : doc.textures) s.textures.push_back(read_texture(doc, spec));
    // a textured material's constant reflectance: its texture's mean (what the tools report)
    for (auto& m : s.materials) {
        if (auto* c = std::get_if<material::coated>(&m)) c->internal_reflectance = coated_internal_reflectance(c->eta, c->thickness);
        auto* d = diffuse_part(m);
        if (d && d->texture) {
            const auto& t = s.textures[*d->texture];
            glm::dvec3 mean(0.0);
            for (const auto& w : t.weights) mean += glm::dvec3(w);
            mean /= static_cast<double>(t.weights.size());
            const rgb_reflectance r{mean.x, mean.y, mean.z};
            std::vector<double> lambda, value;
            for (std::size_t i = 0; i < cie::cmf_samples; ++i) {
                lambda.push_back(cie::cmf_lambda_min + static_cast<double>(i));
                value.push_back(r(lambda.back()));
            }
            d->reflectance = tabulated_spectrum(std::move(lambda), std::move(value), outside::clamp);
        }
    }

    // power → radiance: Φ = π·A·∫L dλ per side (a Lambertian emitter's exitance is π·L);
    // the document normalised the SPD to ∫L dλ = 1 over the domain
    for (std::size_t i = 0; i < s.emitters.size(); ++i) {
        const auto& spec = doc.emitters[i];
        if (!spec.power) continue;
        const double sides = s.emitters[i].two_sided ? 2.0 : 1.0;
        const double k = *spec.power / (std::numbers::pi * emitter_area[i] * sides);
        if (!(emitter_area[i] > 0.0) || !std::isfinite(k))
            throw error(doc.source, spec.line, spec.pointer + "/power",
                        "cannot scale to a power: the emitter's area is " + std::to_string(emitter_area[i]));
        s.emitters[i].radiance = s.emitters[i].radiance.scaled(k);
    }
    return s;
}

std::vector<std::string> approximations(const iris::scene_desc& s) {
    std::vector<std::string> out = s.notes;
    if (s.environment && s.environment->map && s.environment->map->negative_texels > 0) {
        const auto& m = *s.environment->map;
        out.push_back("environment image " + m.file + ": " + std::to_string(m.negative_texels) + " of " +
                      std::to_string(m.weights.size()) +
                      " texels have a negative (out-of-sRGB-gamut) component, clamped to 0");
    }
    for (const auto& t : s.textures)
        if (t.clipped_texels > 0)
            out.push_back("texture " + t.file + ": " + std::to_string(t.clipped_texels) + " of " +
                          std::to_string(t.weights.size()) + " texels are outside [0, 1] (times the scale), clamped into it");
    return out;
}

std::vector<shape_problem> check_dielectric_solids(const iris::scene_desc& s) {
    std::vector<shape_problem> out;
    for (std::size_t i = 0; i < s.shapes.size(); ++i) {
        const auto& sh = s.shapes[i];
        if (sh.material >= s.materials.size() || !std::holds_alternative<material::dielectric>(s.materials[sh.material]))
            continue;
        geometry::triangle_mesh g;
        g.positions = sh.mesh.positions;
        g.triangles = sh.mesh.triangles;
        const auto c = geometry::check_mesh(g);
        if (!c.ok()) out.push_back({i, c.detail.empty() ? std::string("not a valid closed solid") : c.detail});
    }
    return out;
}

}  // namespace iris::scene
