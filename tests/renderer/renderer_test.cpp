// The renderer end to end on built-in scenes: determinism, extremes, bad options.
#include <gtest/gtest.h>

#include <cmath>

#include <iris/renderer/renderer.hpp>
#include <iris/scene/scene.hpp>

namespace {

struct rendered {
    iris::film film{1, 1};
    iris::renderer::status status;
};

rendered render(const iris::scene_desc& s, const std::string& preset, int spp, int w, int h, std::uint64_t seed = 1,
                int threads = 2, int nthold = 512, const std::string& isa = "auto") {
    iris::renderer::options o;
    o.preset = preset;
    o.spp = spp;
    o.width = w;
    o.height = h;
    o.seed = seed;
    o.threads = threads;
    o.nthold = nthold;
    o.isa = isa;
    rendered r;
    r.status = iris::renderer::render(s, o, r.film);
    return r;
}

bool identical(const iris::film& a, const iris::film& b) {
    if (a.width() != b.width() || a.height() != b.height()) return false;
    for (std::size_t i = 0; i < static_cast<std::size_t>(a.width() * a.height()); ++i) {
        const auto x = a.mean(i), y = b.mean(i);
        if (x.x != y.x || x.y != y.y || x.z != y.z) return false;
    }
    return true;
}

TEST(Renderer, SameSeedSameImageWhateverTheThreadCount) {
    const auto s = iris::scene::builtin_scene("falling-cubes");
    const auto one = render(s, "paper", 4, 40, 30, 7, 1, 2);
    const auto two = render(s, "paper", 4, 40, 30, 7, 2, 2);
    const auto again = render(s, "paper", 4, 40, 30, 7, 2, 2);
    EXPECT_TRUE(identical(one.film, two.film));
    EXPECT_TRUE(identical(two.film, again.film));
    EXPECT_EQ(one.status.rays, two.status.rays);
    const auto other = render(s, "paper", 4, 40, 30, 8, 2, 2);
    EXPECT_FALSE(identical(two.film, other.film));  // the seed matters
}

// The hot loop is compiled once per instruction set (render_loop.hpp); with no fused
// multiply–add and fixed-order reductions every copy must give the very same pixels, for
// every preset (the B term's 80-wide loops are where the copies differ most) on scenes
// with glass, a diffuse floor and an environment. Would fail with -ffp-contract=fast.
TEST(Renderer, EveryInstructionSetGivesIdenticalPixels) {
    const auto sets = iris::renderer::instruction_sets();
    ASSERT_EQ(sets.front(), "baseline");
    for (const char* scene : {"falling-cubes", "rubik", "prism"}) {
        const auto s = iris::scene::builtin_scene(scene);
        for (const auto& info : iris::renderer::presets()) {
            const std::string& p = info.name;
            const auto base = render(s, p, 3, 24, 18, 5, 2, 4, "baseline");
            for (const auto& isa : sets) {
                const auto r = render(s, p, 3, 24, 18, 5, 2, 4, isa);
                EXPECT_EQ(r.status.isa, info.isa_copy ? isa : std::string("baseline")) << p;
                EXPECT_TRUE(identical(base.film, r.film)) << scene << " " << p << " " << isa;
                EXPECT_EQ(base.status.rays, r.status.rays) << scene << " " << p << " " << isa;
            }
        }
    }
    if (sets.size() == 1) GTEST_SKIP() << "this CPU or build has only the baseline loop: nothing to compare";
}

TEST(Renderer, EveryPresetRendersEveryBuiltInSceneWithoutNonFiniteSamples) {
    for (const auto& info : iris::scene::builtin_scenes()) {
        const auto s = iris::scene::builtin_scene(info.name);
        for (const auto& p : iris::renderer::preset_names()) {
            const auto r = render(s, p, 2, 12, 10, 3, 2, 1);
            EXPECT_EQ(r.status.spp_done, 2) << info.name << " " << p;
            EXPECT_EQ(r.status.nan_inf, 0u) << info.name << " " << p;
            EXPECT_GT(r.status.rays, 0u);
        }
    }
}

// Cancellation and option validation do not depend on the scene: they are tested once, in
// renderer_core_test.cpp (RendererCore.CancelKeepsTheLastCompletePass, .BadOptionsNameWhatIsAccepted).

TEST(Renderer, ExtremeIorsAndGrazingCamerasStayFinite) {
    auto s = iris::scene::builtin_scene("falling-cubes");
    for (double eta : {1.0, 4.0}) {
        for (auto& m : s.materials)
            if (auto* d = std::get_if<iris::material::dielectric>(&m)) d->ior = iris::constant_ior{eta};
        const auto r = render(s, "paper", 2, 16, 12);
        EXPECT_EQ(r.status.nan_inf, 0u) << "eta " << eta;
    }
    // grazing: camera almost in the floor's plane, looking along it
    auto g = iris::scene::builtin_scene("cornell");
    g.camera.look_at = g.camera.position + glm::vec3(0.0f, -1e-4f, -1.0f);
    const auto r = render(g, "paper", 2, 16, 12);
    EXPECT_EQ(r.status.nan_inf, 0u);
}

}  // namespace
