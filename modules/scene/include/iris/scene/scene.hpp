#pragma once
/// \file
/// \brief iris::scene — scene files (JSON, docs/scene-format.md) and the built-in scenes,
/// loaded into an `iris::scene_desc` (include/iris/render/scene.hpp) with world-space
/// triangle meshes.
///
/// Every error in the input — syntax, unknown keys, types, materials or glasses,
/// out-of-range or non-numeric values, missing mesh files, empty scenes, scenes without
/// an emitter — throws `iris::scene::error` naming the file, the line and the JSON
/// pointer of the value and what was expected. Nothing else is thrown for bad input.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "iris/render/scene.hpp"
#include "iris/scene/document.hpp"
#include "iris/scene/error.hpp"

namespace iris::scene {

/// \brief Mesh a checked document: generate or load every shape, apply its transform,
/// check it, scale power-specified emitters by their area. \throws error (a mesh file that
/// cannot be read or holds no valid triangles).
iris::scene_desc build_scene(const scene_document& doc);

/// \brief Parse a scene from JSON text. `source_name` appears in messages; relative mesh
/// paths are resolved against `base_dir`.
iris::scene_desc parse_scene(std::string_view json_text, const std::string& source_name,
                             const std::filesystem::path& base_dir);

/// \brief Read and parse a scene file (mesh paths relative to the file's directory): a
/// pbrt-v4 file if its extension is .pbrt (docs/pbrt-import.md; `options`), JSON otherwise.
iris::scene_desc load_scene_file(const std::filesystem::path& path, const pbrt_import_options& options = {});

/// \brief A built-in scene (`builtin_scenes()`), from JSON compiled into the library: no
/// file is read. \throws error listing the valid names.
iris::scene_desc builtin_scene(std::string_view name);

/// \brief A built-in scene if `name_or_path` names one, else the scene file at that path.
iris::scene_desc load_scene(std::string_view name_or_path, const pbrt_import_options& options = {});

/// \brief The document (description, recipes) behind `load_scene`, for tools that report
/// on a scene without meshing it.
scene_document load_scene_document(std::string_view name_or_path, const pbrt_import_options& options = {});

/// \brief A 64-bit fingerprint (FNV-1a) of everything a render of `scene` depends on: the
/// camera, the spectral domain, every material, emitter, triangle and the environment, as
/// their exact bits — not how the scene was written (a reformatted file is the same scene,
/// a moved vertex is another). Stable across runs, builds and machines of one byte order;
/// a checkpoint stores it (iris/renderer/checkpoint.hpp).
std::uint64_t fingerprint(const iris::scene_desc& scene);

/// \brief A shape that is not what its material needs.
struct shape_problem {
    std::size_t shape = 0;  ///< index into scene_desc::shapes
    std::string detail;     ///< what iris::geometry::check_mesh found
};

/// \brief The dielectric shapes whose mesh is not a closed, manifold, outward-facing,
/// self-intersection-free solid (glass needs an inside and an outside). Built-in shapes
/// always pass; a mesh file may not. A warning, not an error: such a scene still renders.
std::vector<shape_problem> check_dielectric_solids(const iris::scene_desc& scene);

/// \brief What a scene's loading approximated, one sentence each (e.g. an environment
/// image's negative texels clamped to 0): the tools print them as warnings.
std::vector<std::string> approximations(const iris::scene_desc& scene);

/// \brief Write every shape's triangles as one mesh (CGAL IO); the format follows the
/// extension of `path`: .obj, .ply or .off. \throws error naming the path if it cannot be
/// written or the extension is not one of those.
void export_scene_mesh(const iris::scene_desc& scene, const std::filesystem::path& path);

/// \brief What `export_pbrt` writes besides the scene: pbrt-v4's sampler, integrator and depth.
struct pbrt_export_options {
    int spp = 64;                       ///< "zsobol" pixel samples
    std::string integrator = "volpath"; ///< pbrt-v4's integrator (volpath, path, bdpt, lightpath, …)
    int max_depth = 32;                 ///< its "maxdepth" (iris's default path length)
};

/// \brief The scene in pbrt-v4's format (docs/pbrt-export.md): camera, box-filtered film,
/// materials, emitters, lights and triangles, every spectrum iris's own as an inline
/// (λ, value) list and every light scaled so that pbrt-v4's radiance is iris's. \throws
/// error for what pbrt-v4 cannot be given exactly yet (image textures, environment images,
/// reflectance-only conductors) or bad options.
std::string pbrt_scene_text(const iris::scene_desc& scene, const pbrt_export_options& options = {});

/// \brief `pbrt_scene_text` written atomically to `path`. \throws error
void export_pbrt(const iris::scene_desc& scene, const std::filesystem::path& path,
                 const pbrt_export_options& options = {});

}  // namespace iris::scene
