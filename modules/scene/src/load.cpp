// Where scenes come from: files, the embedded built-ins, or either by name.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

#include "iris/gzip.hpp"
#include "iris/scene/scene.hpp"

namespace iris::scene {
namespace {

std::string read_text(const std::filesystem::path& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw error(path.string(), 0, "", "is a directory, not a scene file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw error(path.string(), 0, "", std::string("cannot open the scene file: ") + std::strerror(errno));
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw error(path.string(), 0, "", "cannot read the scene file");
    return text.str();
}

scene_document builtin_document(std::string_view name) {
    const auto text = builtin_scene_text(name);
    if (!text)
        throw error("builtin:" + std::string(name), 0, "",
                    "unknown built-in scene '" + std::string(name) + "'; expected one of " + builtin_scene_names());
    // built-ins use built-in shapes only, so there is no directory to resolve against
    return parse_scene_document(*text, std::string(name) + ".json", {});
}

std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

/// A JSON scene file, or a pbrt-v4 one (by its extension: .pbrt, or .pbrt.gz compressed).
scene_document file_document(const std::filesystem::path& path, const pbrt_import_options& options) {
    const std::string ext = lower_extension(path);
    if (ext == ".gz" && lower_extension(path.stem()) == ".pbrt") {
        std::string why;
        auto text = gunzip_bytes(read_text(path), std::size_t{4} << 30, why);
        if (!text) throw error(path.string(), 0, "", why);
        return parse_pbrt_document(*text, path.string(), path.parent_path(), options);
    }
    if (ext == ".pbrt") return parse_pbrt_document(read_text(path), path.string(), path.parent_path(), options);
    return parse_scene_document(read_text(path), path.string(), path.parent_path());
}

}  // namespace

iris::scene_desc parse_scene(std::string_view json_text, const std::string& source_name,
                             const std::filesystem::path& base_dir) {
    return build_scene(parse_scene_document(json_text, source_name, base_dir));
}

iris::scene_desc load_scene_file(const std::filesystem::path& path, const pbrt_import_options& options) {
    return build_scene(file_document(path, options));
}

iris::scene_desc builtin_scene(std::string_view name) { return build_scene(builtin_document(name)); }

scene_document load_scene_document(std::string_view name_or_path, const pbrt_import_options& options) {
    if (builtin_scene_text(name_or_path)) return builtin_document(name_or_path);
    const std::filesystem::path p(name_or_path);
    std::error_code ec;
    if (!std::filesystem::exists(p, ec))
        throw error(std::string(name_or_path), 0, "",
                    "no such scene file, and not a built-in scene (" + builtin_scene_names() + ")");
    return file_document(p, options);
}

iris::scene_desc load_scene(std::string_view name_or_path, const pbrt_import_options& options) {
    return build_scene(load_scene_document(name_or_path, options));
}

}  // namespace iris::scene
