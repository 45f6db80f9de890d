// loadObjMesh's reading of OBJ text (obj_text.h): what a lenient reader
// such as tinyobjloader quietly turns into a different mesh (an index that
// wraps, nan read as 0, a number read as its prefix) is refused, naming the
// file, the line and the token; what it accepts is read exactly.
#include "shapes/obj_mesh.h"

#include <algorithm>
#include <atomic>
#include <map>
#include <optional>
#include <random>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include "json/scene_error.h"

namespace spectrace {
namespace {

namespace fs = std::filesystem;

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

class ObjMeshTest : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = fs::temp_directory_path() /
           ("spectrace_obj_mesh_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::create_directories(dir_);
    source_.file = "scene.json";
    source_.dir = dir_;
    source_.raise = [](const std::string& message) { throw SceneError(message); };
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // Loads `obj` as mesh.obj of /objects/3/file.
  Shape load(const std::string& obj) {
    std::ofstream(dir_ / "mesh.obj", std::ios::binary) << obj;
    Shape shape;
    loadObjMesh(source_, "/objects/3/file", dir_ / "mesh.obj", "mesh.obj", MeshTransform{}, 1000, shape);
    return shape;
  }
  // The message of the SceneError that loading `obj` must end in.
  std::string errorOf(const std::string& obj) {
    try {
      load(obj);
    } catch (const SceneError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("scene.json: /objects/3/file: \"mesh.obj\" ", 0), 0u) << message;
      return message;
    }
    ADD_FAILURE() << "accepted:\n" << obj;
    return "";
  }
  void expectError(const std::string& obj, const std::string& phrase) {
    SCOPED_TRACE(obj);
    const std::string message = errorOf(obj);
    EXPECT_NE(message.find(phrase), std::string::npos) << "missing '" << phrase << "' in: " << message;
  }

  fs::path dir_;
  json_fields::Source source_;
};

TEST_F(ObjMeshTest, IndexBeyondIntIsOutOfRangeInsteadOfWrapping) {
  // 2^32 + 3 would wrap to 3 in an int; 2^32 - 1 to -1, the last vertex.
  expectError(kTriangle + "f 1 2 4294967299\n",
              "line 4, \"4294967299\": face 1 refers to vertex 4294967299, but the file has 3 vertices (1 to 3)");
  expectError(kTriangle + "f 1 2 3\nf 1 2 4294967295\n",
              "line 5, \"4294967295\": face 2 refers to vertex 4294967295, but the file has 3 vertices (1 to 3)");
  expectError(kTriangle + "f 1 2 123456789012345678901234567890\n",
              "line 4, \"123456789012345678901234567890\": face 1 refers to a vertex beyond 2^64");
}

TEST_F(ObjMeshTest, RelativeIndexBeyondIntIsOutOfRangeInsteadOfWrapping) {
  // -(2^32 + 1) would wrap to -1, the last vertex.
  expectError(kTriangle + "f 1 2 -4294967297\n",
              "line 4, \"-4294967297\": face 1 refers to vertex before the first (4294967297 back from the 3 "
              "vertices defined so far)");
  expectError(kTriangle + "f -1 -2 -4\n",
              "line 4, \"-4\": face 1 refers to vertex before the first (4 back from the 3 vertices defined so far)");
}

TEST_F(ObjMeshTest, ZeroAndMalformedIndicesNameTheirToken) {
  expectError(kTriangle + "f 1 2 0\n", "line 4, \"0\": face 1 refers to vertex 0; OBJ numbers them from 1");
  expectError(kTriangle + "f 1 2 3x\n", "line 4, \"3x\": face 1 has a corner that is not v, v/vt, v//vn or v/vt/vn");
  expectError(kTriangle + "f 1 2 3/\n", "line 4, \"3/\": face 1 has a corner that is not v, v/vt, v//vn or v/vt/vn");
  expectError(kTriangle + "f 1 2 3/1/0\n", "line 4, \"3/1/0\": face 1 refers to normal 0; OBJ numbers them from 1");
  expectError(kTriangle + "f 1 2\n", "line 4, \"f 1 2\": face 1 has 2 corners; a face needs at least 3");
}

TEST_F(ObjMeshTest, NanIsRefusedNotReadAsTheOrigin) {
  expectError("v 0 0 0\nv nan 1 0\nv 1 0 0\nf 1 2 3\n",
              "line 2, \"nan\": vertex 2 has a coordinate that is not finite (nan and inf are refused)");
  expectError("v 0 0 0\nv 1 -NaN 0\nv 1 0 0\nf 1 2 3\n",
              "line 2, \"-NaN\": vertex 2 has a coordinate that is not finite");
}

TEST_F(ObjMeshTest, InfIsNotFiniteRatherThanAZeroAreaFace) {
  expectError("v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n",
              "line 2, \"inf\": vertex 2 has a coordinate that is not finite (nan and inf are refused)");
  expectError("v 0 0 0\nv 1 0 0\nv 0 -Infinity 0\nf 1 2 3\n",
              "line 3, \"-Infinity\": vertex 3 has a coordinate that is not finite");
  expectError("v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n",
              "line 2, \"1e999\": vertex 2 has a coordinate that is not finite (beyond the range of a double)");
}

TEST_F(ObjMeshTest, NumberOutsideObjSyntaxIsRefusedNotReadAsItsPrefix) {
  for (const char* token : {"1,5", "1.5.2", "0x10", "1e", "1e+", "--1", "+", ".", "1d0", "1_000", "e3"}) {
    expectError("v 0 0 0\nv " + std::string(token) + " 1 0\nv 1 0 0\nf 1 2 3\n",
                "line 2, \"" + std::string(token) +
                    "\": vertex 2 has a coordinate that is not a number in OBJ syntax (a decimal such as -1.5 or "
                    "2.5e-3)");
  }
}

TEST_F(ObjMeshTest, VertexNeedsThreeToSixNumbers) {
  expectError("v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n",
              "line 2, \"v 1 0\": vertex 2 has 2 numbers; a vertex is x y z, optionally followed by w or by r g b");
  expectError("v 0 0 0\nv 1 0 0 1 1\nv 0 1 0\nf 1 2 3\n", "line 2, \"v 1 0 0 1 1\": vertex 2 has 5 numbers");
}

TEST_F(ObjMeshTest, LinesAreCountedAcrossLineEndingsAndComments) {
  expectError("# a comment\r\nv 0 0 0\r\n\r\nv 1 0 0\rv 0 1 0\ng group\nf 1 2 x\n", "line 7, \"x\": face 1");
  // A token that is not printable text is shown escaped, and a long one cut.
  expectError(kTriangle + "f 1 2 \x01\xff\n", "line 4, \"\\x01\\xff\": face 1");
  const std::string message = errorOf(kTriangle + "f 1 2 3" + std::string(1000, '9') + "\n");
  EXPECT_NE(message.find("line 4, \"3" + std::string(39, '9') + "...\": face 1 refers to a vertex beyond 2^64"),
            std::string::npos)
      << message;
  EXPECT_LT(message.size(), 400u) << message;
}

TEST_F(ObjMeshTest, AcceptedFormsKeepWorking) {
  const Shape s = load(
      "v -1.5e+2 .5 5.\t# trailing comment\n"
      "v +2 1E1 0.25 1\n"
      "v 0 -0 1 0.5 0.5 0.5\r\n"
      "vt 0 0\nvn 0 0 1\n"
      "f 1/1/1 2//1 3/1\n"
      "f -3 -1 -2\n");
  ASSERT_EQ(s.vertices.size(), 3u);
  EXPECT_EQ(s.vertices[0], glm::dvec3(-150.0, 0.5, 5.0));
  EXPECT_EQ(s.vertices[1], glm::dvec3(2.0, 10.0, 0.25));
  EXPECT_EQ(s.vertices[2], glm::dvec3(0.0, 0.0, 1.0));
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(s.triangles[1], (std::array<uint32_t, 3>{0, 2, 1}));
}

TEST_F(ObjMeshTest, CoordinatesAreCorrectlyRounded) {
  // The compiler's literals are correctly rounded. tinyobjloader read the
  // first three as 0.30000000000000004, 0.12345670000000002 and
  // 1.2345678901234565.
  const Shape s = load(
      "v 0.3 0.1234567 1.2345678901234567\n"
      "v 1e-400 -2.4e-324 4.9e-324\n"
      "v 0.000000000000000000000000000000000000000000000000001e50 7.0e-1 -.5e-0\n"
      "f 1 2 3\n");
  ASSERT_EQ(s.vertices.size(), 3u);
  EXPECT_EQ(s.vertices[0], glm::dvec3(0.3, 0.1234567, 1.2345678901234567));
  // Below half the least denormal: a zero (+0 once placed); the least
  // denormal itself is kept.
  EXPECT_EQ(s.vertices[1], glm::dvec3(0.0, 0.0, 4.9e-324));
  EXPECT_EQ(s.vertices[2], glm::dvec3(0.1, 0.7, -0.5));
}

TEST_F(ObjMeshTest, PolygonsAreFansFromTheFirstCorner) {
  const Shape s = load(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0.5 0\n"
      "f 1 2 3 4\n"
      "f 1 4 5\n"
      "f -5 -4 -3 -2 -1\n");
  ASSERT_EQ(s.triangles.size(), 6u);
  const std::vector<std::array<uint32_t, 3>> expected = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4},
                                                         {0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
  for (size_t k = 0; k < expected.size(); ++k) EXPECT_EQ(s.triangles[k], expected[k]) << "triangle " << k;
}

TEST_F(ObjMeshTest, ByteOrderMarkIsNotPartOfTheFirstLine) {
  const Shape s = load("\xEF\xBB\xBF" + kTriangle + "f 1 2 3\n");
  ASSERT_EQ(s.vertices.size(), 3u);
  EXPECT_EQ(s.vertices[0], glm::dvec3(0.0, 0.0, 0.0));
  // Only at the start: elsewhere it is a keyword of its own, not used.
  EXPECT_EQ(load(kTriangle + "\xEF\xBB\xBFv 5 5 5\nf 1 2 3\n").vertices.size(), 3u);
}

TEST_F(ObjMeshTest, PolylinesAndPointsAreCheckedButNotUsed) {
  EXPECT_EQ(load(kTriangle + "l 1 2 3 1\np 1 -1\nl 2/1 3/1\nf 1 2 3\n").triangles.size(), 1u);
  expectError(kTriangle + "l 1 0\nf 1 2 3\n",
              "line 4, \"0\": polyline (l) 1 refers to vertex 0; OBJ numbers them from 1");
  expectError(kTriangle + "f 1 2 3\np 1\np x\n",
              "line 6, \"x\": point set (p) 2 has a corner that is not v, v/vt, v//vn or v/vt/vn");
  expectError(kTriangle + "f 1 2 3\nl 1 7\n",
              "line 5, \"7\": polyline (l) 1 refers to vertex 7, but the file has 3 vertices (1 to 3)");
  expectError(kTriangle + "f 1 2 3\nl\n",
              "line 5, \"l\": polyline (l) 1 has 0 corners; a polyline (l) needs at least 1");
}

TEST_F(ObjMeshTest, ForwardReferencesAreCheckedAgainstTheWholeFile) {
  EXPECT_EQ(load("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").triangles.size(), 1u);
  expectError("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
              "line 5, \"4\": face 2 refers to vertex 4, but the file has 3 vertices (1 to 3)");
}

// The first edge fault in the order of (low vertex, high vertex), found
// plainly: every edge's directions counted in a map.
std::optional<std::pair<uint64_t, MeshEdgeFault::Kind>> plainFirstEdgeFault(const MeshTriangles& triangles) {
  std::map<uint64_t, std::pair<int, int>> uses;  // (low << 32 | high): (low to high, high to low)
  for (const auto& t : triangles)
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = t[e], b = t[(e + 1) % 3];
      auto& u = uses[(uint64_t(std::min(a, b)) << 32) | std::max(a, b)];
      ++(a < b ? u.first : u.second);
    }
  for (const auto& [edge, u] : uses) {
    if (u.first == 1 && u.second == 1) continue;
    const int count = u.first + u.second;
    return std::pair{edge, count == 1   ? MeshEdgeFault::Kind::Open
                           : count == 2 ? MeshEdgeFault::Kind::SameDirection
                                        : MeshEdgeFault::Kind::Shared};
  }
  return std::nullopt;
}

// A closed grid on a torus (every edge met once each way), with `faults`
// triangles then flipped, removed or repeated at random, and vertex indices
// spread by `spread` (beyond the edges' count, the search sorts whole).
MeshTriangles torusWithFaults(uint32_t side, int faults, uint32_t spread, std::mt19937& rng) {
  MeshTriangles triangles;
  const auto at = [&](uint32_t i, uint32_t j) { return ((i % side) * side + (j % side)) * spread; };
  for (uint32_t i = 0; i < side; ++i)
    for (uint32_t j = 0; j < side; ++j) {
      triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  for (int f = 0; f < faults; ++f) {
    const size_t k = rng() % triangles.size();
    switch (rng() % 3) {
      case 0: std::swap(triangles[k][1], triangles[k][2]); break;
      case 1: triangles.erase(triangles.begin() + std::ptrdiff_t(k)); break;
      default: triangles.push_back(triangles[k]); break;
    }
  }
  std::shuffle(triangles.begin(), triangles.end(), rng);
  return triangles;
}

TEST(EdgeFaults, FirstFaultIsTheOneAMapOfEdgesFinds) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    const uint32_t side = 3 + uint32_t(rng() % 20);
    const int faults = trial % 4 == 0 ? 0 : 1 + int(rng() % 5);
    const uint32_t spread = trial % 3 == 0 ? 1000003u : 1u;
    const MeshTriangles triangles = torusWithFaults(side, faults, spread, rng);
    const auto expected = plainFirstEdgeFault(triangles);
    const auto found = findEdgeFault(triangles);
    ASSERT_EQ(found.has_value(), expected.has_value()) << "trial " << trial;
    if (!found) continue;
    EXPECT_EQ(found->kind, expected->second) << "trial " << trial;
    const uint64_t edge = (uint64_t(std::min(found->from, found->to)) << 32) | std::max(found->from, found->to);
    EXPECT_EQ(edge, expected->first) << "trial " << trial;
    ASSERT_FALSE(found->triangles.empty());
    for (size_t k : found->triangles) {
      const auto& t = triangles[k];
      int meets = 0;
      for (int e = 0; e < 3; ++e)
        meets += std::min(t[e], t[(e + 1) % 3]) == std::min(found->from, found->to) &&
                 std::max(t[e], t[(e + 1) % 3]) == std::max(found->from, found->to);
      EXPECT_EQ(meets, 1) << "trial " << trial << ": triangle " << k << " does not hold the edge";
    }
  }
}

}  // namespace
}  // namespace spectrace
