// load_mesh: exact round trips through every format, polygons fanned into triangles, and
// one clear iris::geometry::error (naming the file and the fault) for each broken file.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <zlib.h>

#include <iris/geometry/mesh.hpp>

#include "mesh_io.hpp"

namespace {

namespace fs = std::filesystem;
namespace g = iris::geometry;
using iris::test::write_file;

struct LoadMesh : ::testing::Test {
    fs::path dir = fs::temp_directory_path() /
                   ("iris-geometry-test-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    void SetUp() override {
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    fs::path write(const std::string& name, const std::string& bytes) const {
        write_file(dir / name, bytes);
        return dir / name;
    }

    // load_mesh must throw iris::geometry::error whose message names the file and holds `what`.
    void expect_error(const std::string& name, const std::string& bytes, const std::string& what) const {
        const fs::path p = write(name, bytes);
        try {
            (void)g::load_mesh(p);
            ADD_FAILURE() << name << ": no error, expected '" << what << "'";
        } catch (const g::error& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(name), std::string::npos) << msg;
            EXPECT_NE(msg.find(what), std::string::npos) << name << ": " << msg;
        }
    }
};

// An awkward mesh: rotated, off-centre, with coordinates that need all nine digits.
g::triangle_mesh sample() {
    return g::transformed(g::make_hollow_cube({0.1f, -0.2f, 0.3f}, 1.7f, 0.9f), g::make_transform({1e-3f, 7, -2}, {31, 17, 5}, {1, 1, 1}));
}

// Bitwise-equal positions (== on floats) and identical triangles.
::testing::AssertionResult same(const g::triangle_mesh& a, const g::triangle_mesh& b) {
    if (a.positions != b.positions) return ::testing::AssertionFailure() << "positions differ";
    if (a.triangles != b.triangles) return ::testing::AssertionFailure() << "triangles differ";
    return ::testing::AssertionSuccess();
}

TEST_F(LoadMesh, EveryFormatRoundTripsExactly) {
    const auto m = sample();
    EXPECT_TRUE(same(g::load_mesh(write("a.off", iris::test::to_off(m))), m));
    EXPECT_TRUE(same(g::load_mesh(write("a.obj", iris::test::to_obj(m))), m));
    EXPECT_TRUE(same(g::load_mesh(write("a.ply", iris::test::to_ascii_ply(m))), m));
    EXPECT_TRUE(same(g::load_mesh(write("le.ply", iris::test::to_binary_ply(m, false))), m));
    EXPECT_TRUE(same(g::load_mesh(write("be.ply", iris::test::to_binary_ply(m, true))), m));
    EXPECT_TRUE(same(g::load_mesh(write("d.PLY", iris::test::to_binary_ply(m, false, true))), m));  // doubles; extension case
    EXPECT_TRUE(g::check_mesh(g::load_mesh(dir / "a.obj")).ok());
}

/// `bytes` gzip-compressed (zlib's gzip framing, as `gzip` writes).
std::string gzip(const std::string& bytes) {
    z_stream z{};
    if (deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) return {};
    std::string out(deflateBound(&z, static_cast<uLong>(bytes.size())) + 32, '\0');
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
    z.avail_in = static_cast<uInt>(bytes.size());
    z.next_out = reinterpret_cast<Bytef*>(out.data());
    z.avail_out = static_cast<uInt>(out.size());
    const int rc = deflate(&z, Z_FINISH);
    out.resize(z.total_out);
    deflateEnd(&z);
    return rc == Z_STREAM_END ? out : std::string();
}

TEST_F(LoadMesh, GzipCompressedFilesRoundTrip) {
    const auto m = sample();
    EXPECT_TRUE(same(g::load_mesh(write("a.ply.gz", gzip(iris::test::to_binary_ply(m, false)))), m));
    EXPECT_TRUE(same(g::load_mesh(write("a.obj.gz", gzip(iris::test::to_obj(m)))), m));
    EXPECT_TRUE(same(g::load_mesh(write("a.OFF.GZ", gzip(iris::test::to_off(m)))), m));
}

TEST_F(LoadMesh, BrokenGzipFilesAreNamedErrors) {
    const std::string ply = gzip(iris::test::to_ascii_ply(sample()));
    expect_error("truncated.ply.gz", ply.substr(0, ply.size() / 2), "not a valid gzip file (truncated)");
    expect_error("plain.ply.gz", iris::test::to_ascii_ply(sample()), "not a valid gzip file");
    expect_error("empty.ply.gz", "", "not a valid gzip file");
    expect_error("mesh.txt.gz", ply, "unsupported extension '.txt.gz'");
    // what a file decompresses to is bounded: 1 MiB of zeros against a 64 KiB limit
    const std::string bomb = gzip(std::string(1 << 20, '\0'));
    EXPECT_LT(bomb.size(), 2000u);
    try {
        (void)g::gunzip(bomb, "bomb.gz", 1 << 16);
        ADD_FAILURE() << "no error for a stream beyond the limit";
    } catch (const g::error& e) {
        EXPECT_NE(std::string(e.what()).find("decompresses to more than"), std::string::npos) << e.what();
    }
    EXPECT_EQ(g::gunzip(bomb, "bomb.gz").size(), std::size_t{1} << 20);
}

// The sample with a normal and a uv per vertex (not unit, awkward digits).
g::triangle_mesh sample_with_attributes() {
    auto m = sample();
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        const auto f = static_cast<float>(i);
        m.normals.emplace_back(0.3f + 0.1f * f, -1.7f, 0.123456789f * f + 0.5f);
        m.uvs.emplace_back(0.987654321f * f, -0.25f + 0.3333333f * f);
    }
    return m;
}

// Every corner of every triangle has the same position, normal and uv in both meshes
// (bitwise); vertex order and sharing may differ (an OBJ with vn/vt is split per distinct
// triple, in the order the faces first use them).
::testing::AssertionResult same_corners(const g::triangle_mesh& a, const g::triangle_mesh& b) {
    if (a.triangles.size() != b.triangles.size()) return ::testing::AssertionFailure() << "triangle counts differ";
    if (a.normals.empty() != b.normals.empty()) return ::testing::AssertionFailure() << "normals present in one only";
    if (a.uvs.empty() != b.uvs.empty()) return ::testing::AssertionFailure() << "uvs present in one only";
    for (std::size_t t = 0; t < a.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            const auto i = a.triangles[t][static_cast<std::size_t>(k)], j = b.triangles[t][static_cast<std::size_t>(k)];
            if (a.positions[i] != b.positions[j]) return ::testing::AssertionFailure() << "triangle " << t << ": positions differ";
            if (!a.normals.empty() && a.normals[i] != b.normals[j]) return ::testing::AssertionFailure() << "triangle " << t << ": normals differ";
            if (!a.uvs.empty() && a.uvs[i] != b.uvs[j]) return ::testing::AssertionFailure() << "triangle " << t << ": uvs differ";
        }
    return ::testing::AssertionSuccess();
}

// Normals and texture coordinates survive PLY (ASCII, binary either way, floats or
// doubles) exactly and vertex for vertex, OBJ corner for corner; normals alone or uvs alone
// as well; OBJ vertices with the same position but different normals are split.
TEST_F(LoadMesh, NormalsAndUvsRoundTripExactly) {
    const auto m = sample_with_attributes();
    for (const auto& [name, bytes] :
         {std::pair{"a.ply", iris::test::to_ascii_ply(m)}, std::pair{"le.ply", iris::test::to_binary_ply(m, false)},
          std::pair{"be.ply", iris::test::to_binary_ply(m, true)}, std::pair{"d.ply", iris::test::to_binary_ply(m, true, true)}}) {
        const auto l = g::load_mesh(write(name, bytes));
        EXPECT_TRUE(same(l, m)) << name;
        EXPECT_EQ(l.normals, m.normals) << name;
        EXPECT_EQ(l.uvs, m.uvs) << name;
    }
    EXPECT_TRUE(same_corners(g::load_mesh(write("a.obj", iris::test::to_obj(m))), m));
    auto normals_only = m, uvs_only = m;
    normals_only.uvs.clear();
    uvs_only.normals.clear();
    for (const auto* x : {&normals_only, &uvs_only}) {
        EXPECT_TRUE(same_corners(g::load_mesh(write("b.obj", iris::test::to_obj(*x))), *x));
        const auto l = g::load_mesh(write("b.ply", iris::test::to_binary_ply(*x, false)));
        EXPECT_EQ(l.normals, x->normals);
        EXPECT_EQ(l.uvs, x->uvs);
    }
    // a flat-shaded edge: positions 1 and 3 with two normals each → six vertices
    const auto split = g::load_mesh(write("split.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvn 1 0 0\n"
                                                        "f 1//1 2//1 3//1\nf 1//2 3//2 4//2\n"));
    EXPECT_EQ(split.positions.size(), 6u);
    ASSERT_EQ(split.normals.size(), 6u);
    EXPECT_EQ(split.normals[split.triangles[0][0]], glm::vec3(0, 0, 1));
    EXPECT_EQ(split.normals[split.triangles[1][0]], glm::vec3(1, 0, 0));
    EXPECT_EQ(split.positions[split.triangles[1][0]], glm::vec3(0, 0, 0));
    // PLY's other names for texture coordinates
    const auto st = g::load_mesh(write("st.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                                 "property float z\nproperty float s\nproperty float t\nelement face 1\n"
                                                 "property list uchar int vertex_indices\nend_header\n0 0 0 0 0\n1 0 0 1 0\n"
                                                 "0 1 0 0.5 1\n3 0 1 2\n"));
    ASSERT_EQ(st.uvs.size(), 3u);
    EXPECT_EQ(st.uvs[2], glm::vec2(0.5f, 1.0f));
}

// Each broken attribute is a named error: partial normals or uvs, two names for one
// coordinate, non-finite or zero normals, out-of-range vn/vt indices, corners with and
// without normals in one OBJ.
TEST_F(LoadMesh, BrokenNormalsAndUvsAreNamedErrors) {
    const std::string tri_ply_head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    const std::string tri_ply_faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    expect_error("nxny.ply", tri_ply_head + "property float nx\nproperty float ny\n" + tri_ply_faces + "0 0 0 0 0\n1 0 0 0 0\n0 1 0 0 0\n3 0 1 2\n",
                 "some of the normal's nx, ny, nz but not all three");
    expect_error("u.ply", tri_ply_head + "property float u\n" + tri_ply_faces + "0 0 0 0\n1 0 0 0\n0 1 0 0\n3 0 1 2\n",
                 "one texture coordinate ('u') without the other");
    expect_error("us.ply", tri_ply_head + "property float u\nproperty float s\nproperty float v\n" + tri_ply_faces,
                 "two texture coordinates for u ('u' and 's')");
    const std::string normals = "property float nx\nproperty float ny\nproperty float nz\n";
    expect_error("zero.ply", tri_ply_head + normals + tri_ply_faces + "0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n3 0 1 2\n",
                 "vertex 1 has a zero normal");
    expect_error("nan.ply", tri_ply_head + normals + tri_ply_faces + "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 nan 0 1\n3 0 1 2\n",
                 "vertex 2 has a non-finite normal");
    expect_error("vn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n", "refers to normal 1, but there are 1 normals");
    expect_error("vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/3\n", "refers to texture coordinate 2, but there are 1");
    expect_error("mixed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1 3 4\n",
                 "some face corners have a normal");
    expect_error("mixed_vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3\n", "some face corners have texture coordinates");
    expect_error("uvinf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 1e39 0\nf 1/1 2/1 3/1\n", "non-finite texture coordinates");
    expect_error("normals.off", "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n",
                 "line 1: 'NOFF': the normals and texture coordinates of OFF files are not read");
    expect_error("st.off", "STOFF\n", "'STOFF': the normals and texture coordinates");
    expect_error("vrange.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 5//1\n", "refers to vertex 4, but there are 3 vertices");
}

TEST_F(LoadMesh, PolygonsAreFannedAndCommentsSkipped) {
    // A unit cube as six quads, with comments, CRLF line ends and per-face colours.
    const std::string off =
        "# a cube\r\nOFF\r\n8 6 12\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n1 1 0\r\n0 0 1\r\n1 0 1\r\n0 1 1\r\n1 1 1  # last vertex\r\n"
        "4 0 4 6 2 255 0 0\r\n4 1 3 7 5\r\n4 0 1 5 4\r\n4 2 6 7 3\r\n4 0 2 3 1\r\n4 4 5 7 6\r\n";
    const auto m = g::load_mesh(write("quads.off", off));
    EXPECT_EQ(m.positions.size(), 8u);
    EXPECT_EQ(m.triangle_count(), 12u);
    EXPECT_TRUE(g::check_mesh(m).ok()) << g::check_mesh(m).detail;
    // (a face with normals among faces without is an error now: BrokenNormalsAndUvsAreNamedErrors)
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
                            "f 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 3 7 8 4\nf -8 -6 -5 -7\nf 5 6 8 7\n";
    const auto o = g::load_mesh(write("quads.obj", obj));
    EXPECT_EQ(o.triangle_count(), 12u);
    EXPECT_NEAR(g::enclosed_volume(o), 1.0, 1e-6);
}

TEST_F(LoadMesh, MissingFilesAndUnknownExtensionsAreErrors) {
    EXPECT_THROW((void)g::load_mesh(dir / "nothing.obj"), g::error);
    try {
        (void)g::load_mesh(dir / "nothing.off");
    } catch (const g::error& e) {
        EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
    }
    expect_error("mesh.stl", "solid x\nendsolid x\n", "unsupported extension '.stl'");
    expect_error("noext", "OFF\n", "unsupported extension");
    fs::create_directories(dir / "folder.off");
    EXPECT_THROW((void)g::load_mesh(dir / "folder.off"), g::error);
}

TEST_F(LoadMesh, BrokenOffFilesAreNamedErrors) {
    expect_error("empty.off", "", "empty file");
    expect_error("header.off", "PLY\n3 1 0\n", "line 1: expected the OFF header keyword");
    expect_error("binary.off", "OFF BINARY\n", "binary OFF is not supported");
    expect_error("counts.off", "OFF\n3 x 0\n", "line 2: expected the counts");
    expect_error("negative.off", "OFF\n-3 1 0\n", "expected the counts");
    expect_error("short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", "unexpected end of file after 2 of 3 vertices");
    expect_error("nofaces.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "after 1 of 2 faces");
    expect_error("xyz.off", "OFF\n3 1 0\n0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "line 3: a vertex needs x y z");
    expect_error("word.off", "OFF\n3 1 0\n0 0 zero\n1 0 0\n0 1 0\n3 0 1 2\n", "line 3: 'zero' is not a number");
    expect_error("nan.off", "OFF\n3 1 0\n0 0 nan\n1 0 0\n0 1 0\n3 0 1 2\n", "vertex 0 has a non-finite coordinate");
    expect_error("inf.off", "OFF\n3 1 0\n0 0 0\n1 0 1e39\n0 1 0\n3 0 1 2\n", "vertex 1 has a non-finite coordinate");
    expect_error("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "face 0 refers to vertex 3, but there are 3 vertices");
    expect_error("minus.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "refers to vertex -1");
    expect_error("line.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "face 0 has fewer than 3 vertices");
    expect_error("announce.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", "line 6: the face announces 4 vertices");
    expect_error("zero.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", "holds no triangles");
    // A huge count must fail at the end of the data, not try to allocate it.
    expect_error("huge.off", "OFF\n4000000000 4000000000 0\n0 0 0\n", "unexpected end of file after 1 of 4000000000 vertices");
}

TEST_F(LoadMesh, BrokenObjFilesAreNamedErrors) {
    expect_error("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "face 0 refers to vertex 3, but there are 3 vertices");
    expect_error("quad_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 9\n", "refers to vertex 8");
    expect_error("poly_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 9 10 11\n", "refers to vertex 8");
    expect_error("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "OBJ parse error");
    expect_error("empty.obj", "# nothing\n", "holds no triangles");
    expect_error("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "holds no triangles");
    expect_error("line.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "fewer than 3 vertices");
    expect_error("inf.obj", "v 0 0 1e39\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "non-finite");
}

TEST_F(LoadMesh, BrokenPlyFilesAreNamedErrors) {
    const auto tri = g::make_prism({0, 0, 0}, 1.0f, 1.0f);
    expect_error("magic.ply", "PLY\n", "not a PLY file");
    expect_error("noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n", "no 'end_header'");
    expect_error("noformat.ply", "ply\nelement vertex 0\nend_header\n", "no 'format' line");
    expect_error("format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", "line 2: unknown PLY format");
    expect_error("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n", "line 4: unknown property type 'float128'");
    expect_error("keyword.ply", "ply\nformat ascii 1.0\nbogus\nend_header\n", "line 3: unknown header keyword 'bogus'");
    expect_error("noxyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n", "lacks x, y or z");
    expect_error("noface.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n", "no 'face' element");
    std::string ascii = iris::test::to_ascii_ply(tri);
    expect_error("few.ply", ascii.substr(0, ascii.find("end_header")) + "end_header\n0 0\n", "too few values in element 'vertex' #0");
    expect_error("many.ply", ascii.substr(0, ascii.find("end_header")) + "end_header\n0 0 0 255 7\n", "line 12: too many values in element 'vertex' #0");
    std::string binary = iris::test::to_binary_ply(tri, false);
    expect_error("truncated.ply", binary.substr(0, binary.size() - 5), "unexpected end of file in element 'face' #7");
    // A corrupt count: fails at the end of the data, quickly, without a huge allocation.
    std::string huge = binary;
    huge.replace(huge.find("element vertex 6"), 16, "element vertex 4000000000");
    expect_error("huge.ply", huge, "unexpected end of file in element 'vertex'");
    // An element without properties but a huge count: nothing to read, so nothing would
    // stop a loop over its instances (a minute for this count; found by fuzz_mesh_ply).
    std::string empty = binary;
    empty.replace(empty.find("element face"), 12, "element junk 444444444\nelement face");
    expect_error("empty-element.ply", empty, "element 'junk' has 444444444 instances but no properties");
    // NaN bits in a binary float.
    std::string nan = binary;
    const float q = std::nanf("");
    std::memcpy(nan.data() + nan.find("end_header\n") + 11 + 4, &q, 4);
    expect_error("nan.ply", nan, "vertex 0 has a non-finite coordinate");
    std::string range = ascii.substr(0, ascii.rfind("\n3 ") + 1) + "3 0 1 9\n";  // the last face
    expect_error("range.ply", range, "face 7 refers to vertex 9, but there are 6 vertices");
}

}  // namespace
