#pragma once
/// \file
/// \brief The CGAL-free half of scene loading: JSON text → `scene_document`, a checked
/// description whose shapes are still recipes (type, sizes, transform), not triangles.
///
/// Everything a scene file can get wrong except what needs the geometry (a missing or
/// broken mesh file) is reported here, so this half alone is what the fuzzer exercises
/// (target `iris::scene_document`, linked without CGAL). `iris::scene::build_scene`
/// (scene.hpp) turns a document into an `iris::scene_desc` with meshes.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "iris/render/scene.hpp"
#include "iris/scene/error.hpp"

namespace iris::scene {

/// \brief The shape recipes a scene file can name (`"type"` of a shape).
enum class shape_type {
    box,          ///< axis-aligned box centred at the origin, `size` = full extents
    cube,         ///< box with equal sides `size.x`
    prism,        ///< triangular prism: equilateral cross-section of side `size.x` in the
                  ///< xy-plane (one edge at the bottom), extruded along z by `size.z`
    hollow_cube,  ///< cube of side `size.x` with a concentric cubic cavity; walls `wall` thick
    quad,         ///< rectangle `size.x` × `size.z` in the plane y = 0, front face +y
    mesh,         ///< triangles from `file` (OBJ, PLY or OFF)
    triangles,    ///< the triangles given in `triangles` (a pbrt-v4 file's `trianglemesh`, …)
    sphere,       ///< a sphere of radius `size.x` about the origin, tessellated (pbrt-v4's `sphere`)
    disk,         ///< a disk of radius `size.x`, inner radius `size.y`, in the plane z = `size.z`,
                  ///< facing +z, tessellated (pbrt-v4's `disk`)
    subdivision,  ///< the control mesh `triangles` after `levels` steps of Loop subdivision, at its
                  ///< limit surface (pbrt-v4's `loopsubdiv`; iris::geometry::loop_subdivide)
};

/// \brief The JSON name of a shape type (`"hollow_cube"`, …).
std::string_view shape_type_name(shape_type t) noexcept;

/// \brief One shape as the file describes it.
struct shape_spec {
    std::string name;
    std::string pointer;  ///< JSON pointer, e.g. "/shapes/3", for messages
    std::size_t line = 0; ///< 1-based line of the shape in the file (0 if unknown)
    std::string file_name;  ///< the file the shape was read from, if not the document's (a pbrt-v4 Include)
    shape_type type = shape_type::box;
    glm::vec3 size{1.0f};
    float wall = 0.0f;
    std::filesystem::path file;   ///< `mesh` only: absolute, or relative to the working directory
    std::shared_ptr<const iris::triangle_mesh> triangles;  ///< `triangles`, `subdivision` (shared by instances)
    int levels = 0;               ///< `subdivision` only
    glm::mat4 transform{1.0f};    ///< object → world, applied after the recipe
    bool flip = false;            ///< reverse every triangle (normals point the other way)
    std::uint32_t material = 0;
    std::optional<std::uint32_t> emitter;
};

/// \brief How an emitter's radiance is to be scaled once its area is known.
struct emitter_spec {
    std::string name;
    std::string pointer;
    std::size_t line = 0;
    /// Set for `"power": W`: `scene_desc::emitters[i].radiance` then holds the unscaled SPD
    /// normalised to ∫L dλ = 1 over the spectral domain, and `build_scene` multiplies it by
    /// W / (π·A·sides). Unset: the radiance is final (luminance-scaled).
    std::optional<double> power;
};

/// \brief An environment image the document names: read by `build_scene` (its texels
/// become `environment_map::weights`, linear sRGB upsampled and multiplied by `scale`).
struct environment_image_spec {
    std::filesystem::path file;  ///< absolute, or relative to the working directory
    environment_mapping mapping = environment_mapping::latlong;
    double scale = 1.0;
    glm::mat3 to_map{1.0f};  ///< world direction → the map's frame (orthogonal)
    /// pbrt-v4's "illuminance" E_v: the texels are scaled so that pbrt-v4's measure of the
    /// map's illuminance (2π/(W·H)·Σ Y·cos θ over the texels of its upper hemisphere) is E_v.
    std::optional<double> illuminance;
    std::string pointer;
    std::size_t line = 0;
    std::string file_name;  ///< the file that names it, when not the document's source (an included pbrt file)
};

/// \brief A reflectance image a material names: read by `build_scene` into
/// `scene_desc::textures` (same index). PNG/JPEG/BMP/TGA values are sRGB-encoded unless
/// `srgb` is false; EXR values are linear.
struct texture_spec {
    std::filesystem::path file;  ///< absolute, or relative to the working directory
    texture_wrap wrap = texture_wrap::repeat;
    double scale = 1.0;
    bool srgb = true;  ///< decode 8/16-bit values from sRGB (ignored for EXR, always linear)
    glm::vec2 uv_scale{1.0f}, uv_offset{0.0f};  ///< the image's uv = surface uv · scale + offset
    std::string pointer;
    std::size_t line = 0;
    std::string file_name;  ///< the file that names it, when not the document's source (an included pbrt file)
};

/// \brief A parsed, checked scene that has not been meshed yet.
struct scene_document {
    std::string source;           ///< the name used in messages (file path or builtin:NAME)
    std::string description;      ///< the file's `"description"`, may be empty
    scene_desc desc;              ///< camera, domain, materials, emitters, environment; no shapes
    std::vector<emitter_spec> emitters;  ///< parallel to `desc.emitters`
    std::vector<shape_spec> shapes;
    std::optional<environment_image_spec> environment_image;
    std::vector<texture_spec> textures;  ///< what becomes `desc.textures`
};

/// \brief Parse and check a scene. `source_name` is used in messages; relative mesh paths
/// are resolved against `base_dir`. \throws iris::scene::error (never anything else for
/// bad input; std::bad_alloc stays possible).
scene_document parse_scene_document(std::string_view json_text, const std::string& source_name,
                                    const std::filesystem::path& base_dir);

/// \brief How the pbrt-v4 importer treats what it can only approximate.
struct pbrt_import_options {
    bool strict = false;      ///< an approximation (a note) is an error
    bool read_files = true;   ///< false: `Include`, `Import` and .spd files are errors (the fuzzer's setting)
};

/// \brief Parse a pbrt-v4 scene (docs/pbrt-import.md): the subset iris renders, everything
/// else an error at `FILE:LINE:COLUMN`, or a note in `desc.notes` where an approximation is
/// reasonable (an error with `strict`). `Include`/`Import`, .spd and mesh files are resolved
/// against `base_dir` (the main file's directory), as pbrt-v4 resolves them. \throws
/// iris::scene::error
scene_document parse_pbrt_document(std::string_view text, const std::string& source_name,
                                   const std::filesystem::path& base_dir, const pbrt_import_options& options = {});

/// \brief A scene compiled into the library (its JSON text is `data/scenes/NAME.json`).
struct builtin_info {
    std::string_view name;
    std::string_view description;
};

/// \brief The built-in scenes, in a fixed order.
std::span<const builtin_info> builtin_scenes() noexcept;

/// \brief The embedded JSON text of a built-in scene, or nullopt for an unknown name.
std::optional<std::string_view> builtin_scene_text(std::string_view name) noexcept;

/// \brief `"a, b, c"`: the built-in names, for messages.
std::string builtin_scene_names();

}  // namespace iris::scene
