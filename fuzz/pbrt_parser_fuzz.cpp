// Fuzz target: the pbrt-v4 importer (iris::scene_document, no CGAL; docs/pbrt-import.md) on
// arbitrary bytes, reading no file (`read_files` off). Properties: parsing either succeeds
// or throws iris::scene::error naming the file (never another exception, never a crash); a
// parsed scene has shapes and a light, material and emitter indices in range, finite
// non-negative emission, a valid camera, unit light directions and ordered spot cones.
#include <cmath>
#include <cstdint>
#include <string_view>
#include <variant>

#include <glm/geometric.hpp>

#include <iris/scene/document.hpp>

#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const auto doc = iris::scene::parse_pbrt_document(text, "fuzz.pbrt", "/nonexistent-iris-fuzz-dir",
                                                          {.strict = false, .read_files = false});
        const auto& s = doc.desc;
        if (doc.shapes.empty()) iris::fuzz::fail("a scene without shapes was accepted");
        bool light = !s.lights.empty() || s.environment.has_value();
        for (const auto& sh : doc.shapes) {
            if (sh.material >= s.materials.size()) iris::fuzz::fail("material index out of range");
            if (sh.emitter && *sh.emitter >= s.emitters.size()) iris::fuzz::fail("emitter index out of range");
            light |= sh.emitter.has_value();
            if (sh.type == iris::scene::shape_type::triangles && !sh.triangles) iris::fuzz::fail("a mesh without triangles");
        }
        if (!light) iris::fuzz::fail("a scene without light was accepted");
        if (doc.emitters.size() != s.emitters.size()) iris::fuzz::fail("emitter specs out of step");
        if (s.materials.size() != s.material_names.size()) iris::fuzz::fail("material names out of step");
        for (const auto& e : s.emitters)
            for (const double v : e.radiance.values())
                if (!std::isfinite(v) || v < 0.0) iris::fuzz::fail("non-finite or negative emission");
        if (!(s.camera.fov_y_degrees > 0.0f && s.camera.fov_y_degrees < 180.0f)) iris::fuzz::fail("bad fov accepted");
        if (s.camera.width < 1 || s.camera.height < 1) iris::fuzz::fail("bad resolution accepted");
        for (const auto& l : s.lights) {
            const std::uint32_t e = std::visit([](const auto& x) { return x.emitter; }, l);
            if (e >= s.emitters.size()) iris::fuzz::fail("light emitter index out of range");
            if (const auto* sp = std::get_if<iris::light::spot>(&l)) {
                if (!(sp->cos_total_width <= sp->cos_falloff_start && sp->cos_falloff_start < 1.0f &&
                      sp->cos_total_width >= -1.0f))
                    iris::fuzz::fail("a spot's cone and falloff out of order");
                if (!(std::fabs(glm::length(sp->direction) - 1.0f) < 1e-4f)) iris::fuzz::fail("a spot's axis is not unit");
            }
            if (const auto* d = std::get_if<iris::light::distant>(&l))
                if (!(std::fabs(glm::length(d->direction) - 1.0f) < 1e-4f)) iris::fuzz::fail("a distant direction is not unit");
        }
        (void)s.features();
    } catch (const iris::scene::error& e) {
        if (e.file() != "fuzz.pbrt") iris::fuzz::fail("an error that does not name the file");
    }
    return 0;
}
