// check_mesh on broken meshes: each defect is found, named, and does not hide behind a
// property that needs it.
#include <gtest/gtest.h>

#include <string>

#include <iris/geometry/mesh.hpp>

namespace {

namespace g = iris::geometry;

g::triangle_mesh cat(g::triangle_mesh a, const g::triangle_mesh& b) {
    const auto base = static_cast<std::uint32_t>(a.positions.size());
    a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
    for (auto t : b.triangles) a.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    return a;
}

g::triangle_mesh flipped(g::triangle_mesh m) {
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
    return m;
}

bool mentions(const g::mesh_check& c, const std::string& what) { return c.detail.find(what) != std::string::npos; }

TEST(CheckMesh, AnInsideOutCubeIsClosedButNotOutward) {
    const auto c = g::check_mesh(flipped(g::make_cube({0, 0, 0}, 1.0f)));
    EXPECT_TRUE(c.closed);
    EXPECT_TRUE(c.manifold);
    EXPECT_TRUE(c.self_intersection_free);
    EXPECT_FALSE(c.outward);
    EXPECT_TRUE(mentions(c, "inside-out")) << c.detail;
}

TEST(CheckMesh, OneFlippedTriangleIsAnOrientationError) {
    auto m = g::make_cube({0, 0, 0}, 1.0f);
    std::swap(m.triangles[5][1], m.triangles[5][2]);
    const auto c = g::check_mesh(m);
    EXPECT_TRUE(c.closed);
    EXPECT_TRUE(c.manifold);
    EXPECT_FALSE(c.outward);
    EXPECT_TRUE(mentions(c, "oriented oppositely")) << c.detail;
}

TEST(CheckMesh, AMissingTriangleOpensTheMesh) {
    auto m = g::make_cube({0, 0, 0}, 1.0f);
    m.triangles.pop_back();
    const auto c = g::check_mesh(m);
    EXPECT_FALSE(c.closed);
    EXPECT_TRUE(c.manifold);
    EXPECT_FALSE(c.outward);
    EXPECT_TRUE(mentions(c, "3 boundary edge")) << c.detail;
}

TEST(CheckMesh, TwoCubesSharingAnEdgeAreNotManifold) {
    const auto c = g::check_mesh(cat(g::make_box({0, 0, 0}, {1, 1, 1}), g::make_box({1, 1, 0}, {2, 2, 1})));
    EXPECT_FALSE(c.manifold);
    EXPECT_FALSE(c.ok());
    EXPECT_TRUE(mentions(c, "more than two triangles")) << c.detail;
}

TEST(CheckMesh, TwoCubesSharingOnlyACornerAreNotManifold) {
    const auto c = g::check_mesh(cat(g::make_box({0, 0, 0}, {1, 1, 1}), g::make_box({1, 1, 1}, {2, 2, 2})));
    EXPECT_TRUE(c.closed);
    EXPECT_FALSE(c.manifold);
    EXPECT_TRUE(mentions(c, "pinched vertex")) << c.detail;
}

TEST(CheckMesh, OverlappingCubesSelfIntersect) {
    const auto c = g::check_mesh(cat(g::make_cube({0, 0, 0}, 1.0f), g::make_cube({0.5f, 0.5f, 0.5f}, 1.0f)));
    EXPECT_TRUE(c.closed);
    EXPECT_TRUE(c.manifold);
    EXPECT_FALSE(c.self_intersection_free);
    EXPECT_FALSE(c.outward);  // undecided for intersecting shells
    EXPECT_TRUE(mentions(c, "intersect")) << c.detail;
}

TEST(CheckMesh, NestedShellsMustAlternate) {
    // Disjoint solids are fine; a cavity must face inwards.
    EXPECT_TRUE(g::check_mesh(cat(g::make_cube({0, 0, 0}, 1.0f), g::make_cube({3, 0, 0}, 1.0f))).ok());
    EXPECT_TRUE(g::check_mesh(cat(g::make_cube({0, 0, 0}, 2.0f), flipped(g::make_cube({0, 0, 0}, 1.0f)))).ok());
    const auto c = g::check_mesh(cat(g::make_cube({0, 0, 0}, 2.0f), g::make_cube({0, 0, 0}, 1.0f)));
    EXPECT_TRUE(c.closed && c.manifold && c.self_intersection_free);
    EXPECT_FALSE(c.outward) << c.detail;
    // An inside-out hollow cube, and a solid beside an inside-out one.
    EXPECT_FALSE(g::check_mesh(flipped(g::make_hollow_cube({0, 0, 0}, 2.0f, 1.0f))).outward);
    EXPECT_FALSE(g::check_mesh(cat(g::make_cube({0, 0, 0}, 1.0f), flipped(g::make_cube({3, 0, 0}, 1.0f)))).outward);
}

TEST(CheckMesh, RepeatedCornersAreWelded) {
    // A cube whose faces each carry their own four corners (as many files store them).
    const auto cube = g::make_cube({0, 0, 0}, 1.0f);
    g::triangle_mesh split;
    for (const auto& t : cube.triangles) {
        const auto base = static_cast<std::uint32_t>(split.positions.size());
        for (const auto i : t) split.positions.push_back(cube.positions[i]);
        split.triangles.push_back({base, base + 1, base + 2});
    }
    const auto c = g::check_mesh(split);
    EXPECT_TRUE(c.ok()) << c.detail;
    EXPECT_NEAR(g::enclosed_volume(split), 1.0, 1e-6);
}

TEST(CheckMesh, InvalidMeshesAreRejectedWithoutCrashing) {
    auto bad_index = g::make_cube({0, 0, 0}, 1.0f);
    bad_index.triangles[3][1] = 99;
    auto c = g::check_mesh(bad_index);
    EXPECT_FALSE(c.closed || c.manifold || c.outward || c.self_intersection_free);
    EXPECT_TRUE(mentions(c, "triangle 3 refers to vertex 99 of 8")) << c.detail;

    auto nan = g::make_cube({0, 0, 0}, 1.0f);
    nan.positions[2].y = std::nanf("");
    c = g::check_mesh(nan);
    EXPECT_FALSE(c.ok());
    EXPECT_TRUE(mentions(c, "vertex 2 is not finite")) << c.detail;

    c = g::check_mesh(g::triangle_mesh{});
    EXPECT_FALSE(c.ok());
    EXPECT_TRUE(mentions(c, "no triangles")) << c.detail;

    auto degenerate = g::make_cube({0, 0, 0}, 1.0f);
    degenerate.triangles[0] = {1, 1, 2};
    c = g::check_mesh(degenerate);
    EXPECT_FALSE(c.manifold);
    EXPECT_TRUE(mentions(c, "triangle 0 uses one vertex twice")) << c.detail;
}

}  // namespace
