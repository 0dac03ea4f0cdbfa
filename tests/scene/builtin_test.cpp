// The built-in scenes load, their closed shapes are valid solids, their feature summaries
// are what the scenes are for, and the claims docs/scene-format.md makes about their
// design hold (the furnace faces inwards, the prism's lamp lights only the prism, …).
// Also: mesh files, power scaling, export, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <string>

#include <glm/geometric.hpp>

#include <iris/geometry/mesh.hpp>
#include <iris/embree/intersector.hpp>
#include <iris/scene/scene.hpp>
#include <iris/spectrum/color.hpp>

namespace {

namespace fs = std::filesystem;

iris::geometry::triangle_mesh as_geometry(const iris::triangle_mesh& m) {
    iris::geometry::triangle_mesh g;
    g.positions = m.positions;
    g.triangles = m.triangles;
    return g;
}

std::size_t shape_index(const iris::scene_desc& s, const std::string& name) {
    for (std::size_t i = 0; i < s.shapes.size(); ++i)
        if (s.shapes[i].name == name) return i;
    ADD_FAILURE() << "no shape " << name << " in " << s.name;
    return 0;
}

glm::vec3 centroid(const iris::triangle_mesh& m) {
    glm::vec3 c(0.0f);
    for (const auto& p : m.positions) c += p;
    return c / static_cast<float>(m.positions.size());
}

/// Signed enclosed volume Σ v0 · (v1 × v2) / 6: positive for a closed outward mesh,
/// negative for an inside-out one (independent of iris::geometry's own orientation test).
double signed_volume(const iris::triangle_mesh& m) {
    double v = 0.0;
    for (const auto& t : m.triangles) {
        const glm::dvec3 a(m.positions[t[0]]), b(m.positions[t[1]]), c(m.positions[t[2]]);
        v += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return v;
}

fs::path temp_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("iris-scene-test-" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

TEST(BuiltinScenes, ListIsTheSixScenesInOrder) {
    std::vector<std::string> names;
    for (const auto& b : iris::scene::builtin_scenes()) {
        names.emplace_back(b.name);
        EXPECT_FALSE(b.description.empty()) << b.name;
    }
    EXPECT_EQ(names, (std::vector<std::string>{"falling-cubes", "falling-cubes-led", "falling-cubes-rgb", "falling-cubes-laser", "rubik", "prism", "cornell", "furnace"}));
}

TEST(BuiltinScenes, EveryOneLoadsWithLightCameraAndTriangles) {
    for (const auto& b : iris::scene::builtin_scenes()) {
        SCOPED_TRACE(std::string(b.name));
        const auto s = iris::scene::builtin_scene(b.name);
        EXPECT_EQ(s.name, b.name);
        EXPECT_FALSE(s.shapes.empty());
        EXPECT_FALSE(s.emitters.empty());
        EXPECT_GT(s.triangle_count(), 0u);
        EXPECT_LE(s.triangle_count(), 5000u);  // cheap by design
        EXPECT_FLOAT_EQ(s.lambda_min, 380.0f);
        EXPECT_FLOAT_EQ(s.lambda_max, 780.0f);
        const bool paper_aspect = b.name.starts_with("falling-cubes");
        EXPECT_EQ(s.camera.width, paper_aspect ? 320 : 256);
        EXPECT_EQ(s.camera.height, paper_aspect ? 240 : 256);
        for (const auto& e : s.emitters)
            for (double v : e.radiance.values()) ASSERT_TRUE(std::isfinite(v) && v >= 0.0);
    }
    EXPECT_THROW(iris::scene::builtin_scene("cornel"), iris::scene::error);
    try {
        iris::scene::builtin_scene("cornel");
    } catch (const iris::scene::error& e) {
        EXPECT_NE(std::string(e.what()).find("expected one of falling-cubes, falling-cubes-led, falling-cubes-rgb, falling-cubes-laser, rubik, prism, cornell, furnace"),
                  std::string::npos)
            << e.what();
    }
}

TEST(BuiltinScenes, ClosedShapesAreValidSolids) {
    // every shape except the open quads must be a closed, manifold, outward-facing,
    // self-intersection-free solid (glass needs it; the rest is good hygiene)
    std::size_t checked = 0;
    for (const auto& b : iris::scene::builtin_scenes()) {
        const auto doc = iris::scene::load_scene_document(b.name);
        const auto s = iris::scene::build_scene(doc);
        for (std::size_t i = 0; i < s.shapes.size(); ++i) {
            if (doc.shapes[i].type == iris::scene::shape_type::quad) continue;
            const auto c = iris::geometry::check_mesh(as_geometry(s.shapes[i].mesh));
            const double volume = signed_volume(s.shapes[i].mesh);
            if (doc.shapes[i].flip) {  // the furnace: closed and manifold, but facing in
                EXPECT_TRUE(c.closed && c.manifold && c.self_intersection_free) << b.name << "/" << s.shapes[i].name;
                EXPECT_LT(volume, 0.0) << b.name << "/" << s.shapes[i].name;
            } else {
                EXPECT_TRUE(c.ok()) << b.name << "/" << s.shapes[i].name << ": " << c.detail;
                EXPECT_GT(volume, 0.0) << b.name << "/" << s.shapes[i].name;
            }
            ++checked;
        }
    }
    EXPECT_GE(checked, 5u + 5u + 27u + 1u + 2u + 1u);
}

struct expected_features {
    const char* scene;
    bool dispersive_specular, dispersive_rough, has_specular;
    std::vector<std::string> spds;
};

TEST(BuiltinScenes, FeatureSummariesAreRight) {
    const expected_features table[] = {
        {"falling-cubes", true, false, true, {"D65"}}, {"falling-cubes-led", true, false, true, {"LED-B1"}},
        {"falling-cubes-rgb", true, false, true, {"LED-RGB1"}}, {"falling-cubes-laser", true, false, true, {"tabulated"}},
        {"rubik", true, false, true, {"D65"}},         {"prism", true, false, true, {"D65"}},
        {"cornell", true, false, true, {"D65"}},       {"furnace", false, false, false, {"D65"}},
    };
    for (const auto& e : table) {
        SCOPED_TRACE(e.scene);
        const auto f = iris::scene::builtin_scene(e.scene).features();
        EXPECT_EQ(f.dispersive_specular, e.dispersive_specular);
        EXPECT_EQ(f.dispersive_rough, e.dispersive_rough);
        EXPECT_EQ(f.has_specular, e.has_specular);
        EXPECT_FALSE(f.has_environment);
        EXPECT_EQ(f.emitter_spds, e.spds);
    }
}

TEST(BuiltinScenes, CornellIsDispersiveOnlyThroughItsGlassCube) {
    const auto s = iris::scene::builtin_scene("cornell");
    std::set<std::string> dispersive;
    for (const auto& sh : s.shapes) {
        const auto* d = std::get_if<iris::material::dielectric>(&s.materials[sh.material]);
        if (d) {
            EXPECT_EQ(d->roughness, 0.0f);
            if (iris::is_dispersive(d->ior)) dispersive.insert(sh.name);
        }
    }
    EXPECT_EQ(dispersive, (std::set<std::string>{"glass-cube"}));
    // and without it, nothing dispersive is left
    auto without = s;
    without.shapes.erase(without.shapes.begin() + static_cast<std::ptrdiff_t>(shape_index(s, "glass-cube")));
    EXPECT_FALSE(without.features().dispersive());
}

TEST(BuiltinScenes, FurnaceIsAClosedInwardEmitterOfLuminanceOneAndAlbedoPointEight) {
    const auto s = iris::scene::builtin_scene("furnace");
    ASSERT_EQ(s.shapes.size(), 1u);
    const auto& m = s.shapes[0].mesh;
    const glm::vec3 c = centroid(m);
    for (const auto& t : m.triangles) {
        const glm::vec3 a = m.positions[t[0]], b = m.positions[t[1]], d = m.positions[t[2]];
        const glm::vec3 n = glm::cross(b - a, d - a);
        EXPECT_LT(glm::dot(n, (a + b + d) / 3.0f - c), 0.0f);  // every triangle faces the inside
    }
    ASSERT_TRUE(s.shapes[0].emitter);
    const auto& e = s.emitters[*s.shapes[0].emitter];
    EXPECT_FALSE(e.two_sided);
    EXPECT_NEAR(iris::luminance(e.radiance), 1.0, 1e-9);
    const auto& r = std::get<iris::material::diffuse>(s.materials[s.shapes[0].material]).reflectance;
    for (double l = 360.0; l <= 830.0; l += 10.0) EXPECT_DOUBLE_EQ(r(l), 0.8);
    // the camera is inside the box
    const iris::embree::intersector tracer(s);
    for (const glm::vec3 d : {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, -1, 0),
                              glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)})
        EXPECT_TRUE(tracer.intersect(s.camera.position, d, 1e3f)) << d.x << d.y << d.z;
}

TEST(BuiltinScenes, FallingCubesVariantsDifferOnlyInTheirSpd) {
    const auto a = iris::scene::builtin_scene("falling-cubes");
    for (const auto* variant : {"falling-cubes-rgb", "falling-cubes-laser"}) {
        SCOPED_TRACE(variant);
        const auto v = iris::scene::builtin_scene(variant);
        ASSERT_EQ(a.shapes.size(), v.shapes.size());
        for (std::size_t i = 0; i < a.shapes.size(); ++i) EXPECT_EQ(a.shapes[i].mesh.positions, v.shapes[i].mesh.positions);
        EXPECT_EQ(a.materials.size(), v.materials.size());
        EXPECT_NEAR(iris::luminance(a.emitters[0].radiance), iris::luminance(v.emitters[0].radiance), 1e-9);
    }
    const auto b = iris::scene::builtin_scene("falling-cubes-led");
    ASSERT_EQ(a.shapes.size(), b.shapes.size());
    for (std::size_t i = 0; i < a.shapes.size(); ++i) {
        EXPECT_EQ(a.shapes[i].mesh.positions, b.shapes[i].mesh.positions);
        EXPECT_EQ(a.shapes[i].mesh.triangles, b.shapes[i].mesh.triangles);
    }
    EXPECT_EQ(a.camera.position, b.camera.position);
    EXPECT_EQ(a.emitters[0].spd_name, "D65");
    EXPECT_EQ(b.emitters[0].spd_name, "LED-B1");
    EXPECT_NEAR(iris::luminance(a.emitters[0].radiance), iris::luminance(b.emitters[0].radiance), 1e-9);
}

TEST(BuiltinScenes, PrismLampLightsThePrismThroughTheSlitAndNothingElse) {
    const auto s = iris::scene::builtin_scene("prism");
    const iris::embree::intersector tracer(s);
    const auto lamp = shape_index(s, "lamp"), prism = shape_index(s, "prism"), screen = shape_index(s, "screen");
    const glm::vec3 lamp_c = centroid(s.shapes[lamp].mesh), screen_c = centroid(s.shapes[screen].mesh);
    // from the middle of the prism's entry face the lamp is in plain view, through the slit
    const glm::vec3 entry(-0.1f, 0.0f, 0.057735f);
    const auto h = tracer.intersect(entry + 1e-3f * glm::normalize(lamp_c - entry), lamp_c - entry, 2.0f);
    ASSERT_TRUE(h);
    EXPECT_EQ(h->shape, lamp);
    // the screen cannot see the lamp directly (the housing and the prism are in the way)
    for (float y : {-0.4f, 0.0f, 0.4f})
        for (float dz : {-0.2f, 0.0f, 0.2f}) {
            const glm::vec3 p = screen_c + glm::vec3(0.0f, y, dz);
            const glm::vec3 q = lamp_c + glm::vec3(0.0f, 0.8f * y, 0.0f);
            const auto blocker = tracer.intersect(p + 1e-3f * glm::normalize(q - p), q - p, 1.0f);
            ASSERT_TRUE(blocker);
            EXPECT_NE(blocker->shape, lamp);
        }
    // the camera looks at the screen, past the prism
    const auto c = tracer.intersect(s.camera.position, s.camera.look_at - s.camera.position, 10.0f);
    ASSERT_TRUE(c);
    EXPECT_EQ(c->shape, screen);
    // smooth glass: the band on the screen is a specular caustic
    EXPECT_EQ(std::get<iris::material::dielectric>(s.materials[s.shapes[prism].material]).roughness, 0.0f);
}

TEST(SceneFiles, EveryGeneratedShapeIsAValidSolidUnderAnyTransform) {
    // each closed recipe, plain, rotated + scaled, and mirrored (negative scale: re-wound)
    const char* recipes[] = {R"("type": "box", "size": [1, 2, 0.5])", R"("type": "cube", "size": 0.7)",
                             R"("type": "prism", "side": 0.4, "length": 1.2)",
                             R"("type": "hollow_cube", "size": 0.5, "wall": 0.06)"};
    const char* transforms[] = {"[]", R"([{"rotate": {"axis": [1, 2, 3], "degrees": 37}}, {"scale": [2, 1, 0.5]}, {"translate": [1, 2, 3]}])",
                                R"([{"scale": [-1, 1, 1]}])", R"([{"scale": [-1, -2, -1]}, {"rotate": {"axis": [0, 1, 0], "degrees": 90}}])"};
    for (const char* r : recipes)
        for (const char* t : transforms) {
            SCOPED_TRACE(std::string(r) + " " + t);
            const auto s = iris::scene::parse_scene(
                std::string(R"({"camera": {"position": [0, 0, 9], "look_at": [0, 0, 0]},
                  "materials": {"g": {"type": "dielectric", "ior": "N-BK7"}}, "environment": {"spd": "D65"},
                  "shapes": [{)") + r + R"(, "material": "g", "transform": )" + t + "}]}",
                "shape.json", {});
            const auto c = iris::geometry::check_mesh(as_geometry(s.shapes[0].mesh));
            EXPECT_TRUE(c.ok()) << c.detail;
            EXPECT_GT(signed_volume(s.shapes[0].mesh), 0.0);
            EXPECT_TRUE(iris::scene::check_dielectric_solids(s).empty());
        }
    // the open quad: two triangles facing +y, before its transform
    const auto q = iris::scene::parse_scene(R"({"camera": {"position": [0, 0, 9], "look_at": [0, 0, 0]},
        "materials": {"m": {"type": "diffuse", "reflectance": 0.5}}, "environment": {"spd": "D65"},
        "shapes": [{"type": "quad", "size": [2, 3], "material": "m"}]})",
                                            "quad.json", {});
    const auto& m = q.shapes[0].mesh;
    ASSERT_EQ(m.triangle_count(), 2u);
    for (const auto& t : m.triangles) {
        const glm::vec3 n = glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
        EXPECT_GT(n.y, 0.0f);
        EXPECT_FLOAT_EQ(glm::length(n), 6.0f);  // |cross| = 2 × area, each triangle half of 2 × 3
    }
    EXPECT_FALSE(iris::geometry::check_mesh(as_geometry(m)).closed);
}

TEST(SceneFiles, GlassThatIsNotAClosedSolidIsReported) {
    const auto s = iris::scene::parse_scene(R"({"camera": {"position": [0, 0, 9], "look_at": [0, 0, 0]},
        "materials": {"g": {"type": "dielectric", "ior": 1.5}, "m": {"type": "diffuse", "reflectance": 0.5}},
        "environment": {"spd": "D65"},
        "shapes": [{"type": "quad", "size": [1, 1], "material": "m"},
                   {"type": "quad", "size": [1, 1], "material": "g"},
                   {"type": "cube", "size": 1, "material": "g"}]})",
                                            "glass.json", {});
    const auto p = iris::scene::check_dielectric_solids(s);
    ASSERT_EQ(p.size(), 1u);  // the glass quad only: a diffuse quad is fine, the cube is a solid
    EXPECT_EQ(p[0].shape, 1u);
    EXPECT_FALSE(p[0].detail.empty());
}

TEST(SceneFiles, MeshFilesAreReadRelativeToTheSceneFile) {
    const fs::path dir = temp_dir("mesh");
    fs::create_directories(dir / "meshes");
    std::ofstream(dir / "meshes" / "tet.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::ofstream(dir / "scene.json") << R"({
      "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
      "materials": {"glass": {"type": "dielectric", "ior": 1.5}},
      "environment": {"spd": "D65"},
      "shapes": [{"type": "mesh", "file": "meshes/tet.obj", "material": "glass",
                  "transform": [{"scale": [2, -1, 1]}]}]
    })";
    const auto s = iris::scene::load_scene_file(dir / "scene.json");
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_EQ(s.shapes[0].mesh.triangle_count(), 4u);
    // mirrored by the negative scale, and re-wound: still a valid outward solid
    EXPECT_TRUE(iris::geometry::check_mesh(as_geometry(s.shapes[0].mesh)).ok());
    EXPECT_FLOAT_EQ(s.shapes[0].mesh.positions[1].x, 2.0f);
    EXPECT_FLOAT_EQ(s.shapes[0].mesh.positions[2].y, -1.0f);

    std::ofstream(dir / "meshes" / "broken.obj") << "v 0 0 0\nf 1 2 3\n";
    std::ofstream(dir / "broken.json") << R"({
      "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
      "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
      "environment": {"spd": "D65"},
      "shapes": [
        {"type": "cube", "size": 1, "material": "m"},
        {"type": "mesh", "file": "meshes/broken.obj", "material": "m"}
      ]
    })";
    try {
        iris::scene::load_scene_file(dir / "broken.json");
        FAIL() << "a broken mesh file was accepted";
    } catch (const iris::scene::error& e) {
        EXPECT_EQ(e.line(), 7u) << e.what();
        EXPECT_EQ(e.pointer(), "/shapes/1/file") << e.what();
        EXPECT_NE(std::string(e.what()).find("broken.obj"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

TEST(SceneFiles, PowerScalingGivesTheRequestedRadiantPower) {
    for (const bool two_sided : {false, true}) {
        const auto s = iris::scene::parse_scene(
            std::string(R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
              "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
              "emitters": {"e": {"spd": "A", "power": 12, "two_sided": )") +
                (two_sided ? "true" : "false") + R"(}},
              "shapes": [{"type": "quad", "size": [2, 0.5], "material": "m", "emitter": "e"},
                         {"type": "quad", "size": [1, 1], "material": "m", "emitter": "e",
                          "transform": [{"translate": [0, 3, 0]}]}]})",
            "p.json", {});
        ASSERT_EQ(s.emitters.size(), 1u);
        // Φ = π · A · ∫L dλ · sides with A = 1 + 1 = 2 m², ∫ over 380–780 nm by 1 nm trapezoids
        double integral = 0.0;
        for (double l = 380.0; l < 780.0; l += 1.0)
            integral += 0.5 * (s.emitters[0].radiance(l) + s.emitters[0].radiance(l + 1.0));
        EXPECT_NEAR(std::numbers::pi * 2.0 * integral * (two_sided ? 2.0 : 1.0), 12.0, 1e-9);
    }
}

TEST(SceneFiles, LoadSceneTriesBuiltinNamesThenFiles) {
    EXPECT_EQ(iris::scene::load_scene("furnace").name, "furnace");
    const fs::path dir = temp_dir("load");
    std::ofstream(dir / "furnace-copy.json") << *iris::scene::builtin_scene_text("furnace");
    EXPECT_EQ(iris::scene::load_scene((dir / "furnace-copy.json").string()).triangle_count(), 12u);
    try {
        iris::scene::load_scene("no-such-scene");
        FAIL();
    } catch (const iris::scene::error& e) {
        EXPECT_NE(std::string(e.what()).find("not a built-in scene (falling-cubes, "), std::string::npos) << e.what();
    }
    EXPECT_THROW(iris::scene::load_scene_file(dir / "missing.json"), iris::scene::error);
    EXPECT_THROW(iris::scene::load_scene_file(dir), iris::scene::error);  // a directory
    fs::remove_all(dir);
}

TEST(SceneFiles, ExportRoundTripsThroughTheMeshLoader) {
    const fs::path dir = temp_dir("export");
    const auto s = iris::scene::builtin_scene("cornell");
    std::size_t vertices = 0;
    for (const auto& sh : s.shapes) vertices += sh.mesh.positions.size();
    for (const char* ext : {".obj", ".ply", ".off"}) {
        SCOPED_TRACE(ext);
        const fs::path p = dir / (std::string("cornell") + ext);
        iris::scene::export_scene_mesh(s, p);
        const auto m = iris::geometry::load_mesh(p);
        EXPECT_EQ(m.triangle_count(), s.triangle_count());
        ASSERT_EQ(m.positions.size(), vertices);
        EXPECT_EQ(m.positions.front(), s.shapes.front().mesh.positions.front());  // exact: max_digits10
        EXPECT_EQ(m.positions.back(), s.shapes.back().mesh.positions.back());
    }
    EXPECT_THROW(iris::scene::export_scene_mesh(s, dir / "cornell.stl"), iris::scene::error);
    EXPECT_THROW(iris::scene::export_scene_mesh(s, dir / "no-such-dir" / "cornell.obj"), iris::scene::error);
    fs::remove_all(dir);
}

TEST(SceneFiles, LoadingTwiceGivesIdenticalScenes) {
    for (const auto& b : iris::scene::builtin_scenes()) {
        const auto x = iris::scene::builtin_scene(b.name), y = iris::scene::builtin_scene(b.name);
        ASSERT_EQ(x.shapes.size(), y.shapes.size());
        for (std::size_t i = 0; i < x.shapes.size(); ++i) {
            EXPECT_EQ(x.shapes[i].mesh.positions, y.shapes[i].mesh.positions);
            EXPECT_EQ(x.shapes[i].mesh.triangles, y.shapes[i].mesh.triangles);
        }
    }
}

}  // namespace
