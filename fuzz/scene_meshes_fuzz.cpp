// Fuzz target: a scene file together with the mesh file it loads (iris::scene, with CGAL's
// checks of glass solids). The input is the JSON text, a NUL byte, one byte choosing the
// mesh's format (obj/off/ply), then the mesh's bytes, which are written as mesh.<ext> in a
// private directory the scene is resolved against. Properties: parse_scene either
// succeeds with every shape non-empty, every index in range and every coordinate finite,
// or throws iris::scene::error naming the scene file; check_dielectric_solids never throws
// and names a shape in range.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <unistd.h>

#include <iris/scene/scene.hpp>

#include "fuzz_input.hpp"

namespace {

const std::filesystem::path& work_dir() {
    static const std::filesystem::path dir = [] {
        auto d = std::filesystem::temp_directory_path() / ("iris-fuzz-scene-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view all(reinterpret_cast<const char*>(data), size);
    const std::size_t nul = all.find('\0');
    const std::string_view json = all.substr(0, nul);
    std::string_view rest = nul == std::string_view::npos ? std::string_view{} : all.substr(nul + 1);
    static constexpr const char* exts[] = {"obj", "off", "ply"};
    const char* ext = exts[rest.empty() ? 0 : static_cast<unsigned char>(rest[0]) % 3];
    if (!rest.empty()) rest.remove_prefix(1);
    const auto& dir = work_dir();
    for (const char* e : exts) std::filesystem::remove(dir / (std::string("mesh.") + e));
    {
        std::ofstream out(dir / (std::string("mesh.") + ext), std::ios::binary);
        out.write(rest.data(), static_cast<std::streamsize>(rest.size()));
    }
    try {
        const auto s = iris::scene::parse_scene(json, "fuzz.json", dir);
        for (const auto& sh : s.shapes) {
            if (sh.mesh.triangles.empty()) iris::fuzz::fail("an empty shape was accepted");
            if (sh.material >= s.materials.size()) iris::fuzz::fail("material index out of range");
            for (const auto& p : sh.mesh.positions)
                if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                    iris::fuzz::fail("a non-finite vertex was accepted");
            for (const auto& t : sh.mesh.triangles)
                for (const auto i : t)
                    if (i >= sh.mesh.positions.size()) iris::fuzz::fail("a vertex index out of range was accepted");
        }
        for (const auto& p : iris::scene::check_dielectric_solids(s))
            if (p.shape >= s.shapes.size()) iris::fuzz::fail("a problem names a shape out of range");
    } catch (const iris::scene::error& e) {
        if (e.file() != "fuzz.json") iris::fuzz::fail("an error that does not name the scene file");
    }
    return 0;
}
