// The "objects" array: shapes, materials, reflectance forms, OBJ meshes and
// their transform, closedness, and every refusal with the file and field it
// names. Fixtures (OBJ, CSV) are written into a fresh temporary folder.
#include "scene/scene_object.h"

#include <atomic>
#include <cmath>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "json/json_fields.h"
#include "shapes/obj_mesh.h"
#include "scene/scene.h"
#include "spectrum/glass.h"

namespace spectrace {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace nlohmann::literals;

// A unit cube, every face counter-clockwise seen from outside.
const char* kCubeVertices =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
const char* kCubeFaces[6] = {"f 1 4 3 2\n", "f 5 6 7 8\n", "f 1 2 6 5\n",
                             "f 3 4 8 7\n", "f 1 5 8 4\n", "f 2 3 7 6\n"};

std::string cubeObj(int skipFace = -1, int flipFace = -1) {
  std::string text = "# unit cube\no cube\n";
  text += kCubeVertices;
  for (int f = 0; f < 6; ++f) {
    if (f == skipFace) continue;
    if (f == flipFace) {
      text += "f 1 2 3 4\n";  // the bottom face, turned inwards
      continue;
    }
    text += kCubeFaces[f];
  }
  return text;
}

// 6 x the enclosed volume, positive when the triangles face outwards.
double signedVolume6(const Shape& s) {
  double v = 0.0;
  for (const auto& t : s.triangles)
    v += glm::dot(s.vertices[t[0]], glm::cross(s.vertices[t[1]], s.vertices[t[2]]));
  return v;
}

json baseScene() {
  return R"({
    "camera": { "position": [0, 0, 0], "look_at": [0, 0, 1] },
    "lights": [ { "type": "point", "position": [0, 0, 2], "power_w": 1, "spd": "D65" } ]
  })"_json;
}

json withObjects(json objects) {
  json s = baseScene();
  s["objects"] = std::move(objects);
  return s;
}

json cubeMesh(const json& material = R"({"type": "absorber"})"_json) {
  return json{{"type", "mesh"}, {"file", "cube.obj"}, {"material", material}};
}

class ObjectTest : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = fs::temp_directory_path() /
           ("spectrace_scene_object_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    write("cube.obj", cubeObj());
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  fs::path write(const fs::path& name, const std::string& text) {
    const fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

  Scene load(const json& scene) { return loadScene(write("scene.json", scene.dump(2))); }
  SceneObject loadOne(const json& object) {
    Scene s = load(withObjects(json::array({object})));
    EXPECT_EQ(s.objects.size(), 1u);
    return s.objects.at(0);
  }

  // The message must be "<file>: <pointer>: ..." and contain every phrase.
  void expectError(const json& scene, const std::string& pointer, const std::vector<std::string>& phrases) {
    const fs::path file = write("scene.json", scene.dump(2));
    std::string msg;
    try {
      loadScene(file);
    } catch (const SceneError& e) {
      msg = e.what();
    }
    ASSERT_FALSE(msg.empty()) << "expected an error at " << pointer << " for:\n" << scene.dump(2);
    EXPECT_EQ(msg.rfind(file.string() + ": " + pointer + ": ", 0), 0u) << "message: " << msg;
    for (const auto& phrase : phrases)
      EXPECT_NE(msg.find(phrase), std::string::npos) << "missing '" << phrase << "' in: " << msg;
  }
  void expectObjectError(const json& object, const std::string& pointer, const std::vector<std::string>& phrases) {
    SCOPED_TRACE(object.dump());
    expectError(withObjects(json::array({object})), pointer, phrases);
  }
  void expectMeshError(const std::string& obj, const std::vector<std::string>& phrases) {
    SCOPED_TRACE(obj);
    write("bad.obj", obj);
    expectObjectError(R"({"type": "mesh", "file": "bad.obj", "material": {"type": "absorber"}})"_json,
                      "/objects/0/file", phrases);
  }

  fs::path dir_;
};

void expectExactly(const glm::dvec3& v, double x, double y, double z) {
  EXPECT_EQ(v.x, x);
  EXPECT_EQ(v.y, y);
  EXPECT_EQ(v.z, z);
}

void expectNear(const glm::dvec3& v, double x, double y, double z) {
  EXPECT_NEAR(v.x, x, 1e-12);
  EXPECT_NEAR(v.y, y, 1e-12);
  EXPECT_NEAR(v.z, z, 1e-12);
}

// --- shapes -----------------------------------------------------------------

TEST_F(ObjectTest, NoObjectsKeyMeansNoObjects) {
  EXPECT_TRUE(load(baseScene()).objects.empty());
  EXPECT_TRUE(load(withObjects(json::array())).objects.empty());
}

TEST_F(ObjectTest, RectReadsItsPlacementAsRectLightsDo) {
  const SceneObject o = loadOne(R"({"name": "plate", "type": "rect", "center": [1, 2, 3], "normal": [0, 0, -2],
                                    "size_m": [0.5, 0.25], "material": {"type": "absorber"}})"_json);
  EXPECT_EQ(o.label, "/objects/0");
  EXPECT_EQ(o.name, "plate");
  EXPECT_EQ(o.shape.type, ShapeType::Rect);
  expectExactly(o.shape.center, 1, 2, 3);
  expectExactly(o.shape.normal, 0, 0, -1);
  expectNear(o.shape.uAxis, -1, 0, 0);  // the rect lights' default for a rect facing -z
  EXPECT_EQ(o.shape.sizeM.x, 0.5);
  EXPECT_EQ(o.shape.sizeM.y, 0.25);
  EXPECT_FALSE(o.shape.closed);
  EXPECT_EQ(o.material.type, MaterialType::Absorber);

  // A u_axis off the plane is projected onto it.
  const SceneObject tilted = loadOne(R"({"type": "rect", "center": [0, 0, 3], "normal": [0, 0, 1],
                                         "u_axis": [0, 1, 1], "size_m": [1, 1], "material": {"type": "absorber"}})"_json);
  expectNear(tilted.shape.uAxis, 0, 1, 0);
}

TEST_F(ObjectTest, DiskAndSphere) {
  const SceneObject disk = loadOne(R"({"type": "disk", "center": [0, 0, 3], "normal": [0, 3, 0], "radius_m": 0.2,
                                       "material": {"type": "absorber"}})"_json);
  EXPECT_EQ(disk.shape.type, ShapeType::Disk);
  expectExactly(disk.shape.normal, 0, 1, 0);
  EXPECT_EQ(disk.shape.radiusM, 0.2);
  EXPECT_FALSE(disk.shape.closed);

  const SceneObject sphere = loadOne(R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 0.5,
                                         "material": {"type": "dielectric", "ior": 1.5}})"_json);
  EXPECT_EQ(sphere.shape.type, ShapeType::Sphere);
  expectExactly(sphere.shape.center, 0, 0, 3);
  EXPECT_EQ(sphere.shape.radiusM, 0.5);
  EXPECT_TRUE(sphere.shape.closed);
}

TEST_F(ObjectTest, ObjectsKeepTheirOrderAndLabels) {
  const Scene s = load(withObjects(json::array(
      {R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 0.5, "material": {"type": "absorber"}})"_json,
       cubeMesh()})));
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[0].shape.type, ShapeType::Sphere);
  EXPECT_EQ(s.objects[1].shape.type, ShapeType::Mesh);
  EXPECT_EQ(s.objects[1].label, "/objects/1");
}

TEST_F(ObjectTest, TypeNames) {
  EXPECT_STREQ(shapeTypeName(ShapeType::Rect), "rect");
  EXPECT_STREQ(shapeTypeName(ShapeType::Disk), "disk");
  EXPECT_STREQ(shapeTypeName(ShapeType::Sphere), "sphere");
  EXPECT_STREQ(shapeTypeName(ShapeType::Mesh), "mesh");
  EXPECT_STREQ(materialTypeName(MaterialType::Absorber), "absorber");
  EXPECT_STREQ(materialTypeName(MaterialType::Diffuse), "diffuse");
  EXPECT_STREQ(materialTypeName(MaterialType::Mirror), "mirror");
  EXPECT_STREQ(materialTypeName(MaterialType::Dielectric), "dielectric");
}

// --- meshes -----------------------------------------------------------------

TEST_F(ObjectTest, CubeMeshIsClosedAndFacesOutwards) {
  const SceneObject o = loadOne(cubeMesh());
  EXPECT_EQ(o.shape.type, ShapeType::Mesh);
  EXPECT_EQ(o.shape.meshFile, dir_ / "cube.obj");
  ASSERT_EQ(o.shape.vertices.size(), 8u);
  EXPECT_EQ(o.shape.triangles.size(), 12u);  // 6 quads, each split in two
  expectExactly(o.shape.vertices[6], 1, 1, 1);  // the file's vertex 7
  EXPECT_TRUE(o.shape.closed);
  EXPECT_DOUBLE_EQ(signedVolume6(o.shape), 6.0);
}

TEST_F(ObjectTest, PolygonsAreSplitIntoFans) {
  write("pentagon.obj", "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nf 1 2 3 4 5\n");
  json mesh = cubeMesh();
  mesh["file"] = "pentagon.obj";
  const SceneObject o = loadOne(mesh);
  ASSERT_EQ(o.shape.triangles.size(), 3u);
  EXPECT_EQ(o.shape.triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(o.shape.triangles[1], (std::array<uint32_t, 3>{0, 2, 3}));
  EXPECT_EQ(o.shape.triangles[2], (std::array<uint32_t, 3>{0, 3, 4}));
  EXPECT_FALSE(o.shape.closed);
}

TEST_F(ObjectTest, MeshPathsResolveAgainstTheSceneFolder) {
  write("models/cube.obj", cubeObj());
  json mesh = cubeMesh();
  mesh["file"] = "models/cube.obj";
  EXPECT_EQ(loadOne(mesh).shape.meshFile, dir_ / "models" / "cube.obj");
  mesh["file"] = (dir_ / "models" / "cube.obj").string();  // absolute
  EXPECT_EQ(loadOne(mesh).shape.vertices.size(), 8u);
}

TEST_F(ObjectTest, TransformScalesThenRotatesXYZThenTranslates) {
  json mesh = cubeMesh();
  mesh["transform"] = R"({"scale": [1, 2, 3], "rotate_deg": [0, 0, 90], "translate": [10, 20, 30]})"_json;
  const SceneObject o = loadOne(mesh);
  // (1, 1, 1) -> scale (1, 2, 3) -> about z by 90: (-2, 1, 3) -> (8, 21, 33),
  // exactly: quarter turns use exact sines.
  expectExactly(o.shape.vertices[6], 8, 21, 33);
  expectExactly(o.shape.vertices[1], 10, 21, 30);  // (1, 0, 0)
  EXPECT_TRUE(o.shape.closed);
  EXPECT_DOUBLE_EQ(signedVolume6(o.shape), 36.0);

  // The order of the rotations: x first, then y. (0, 1, 0) about x by 90 is
  // (0, 0, 1), then about y by 90 is (1, 0, 0); the other order would give
  // (0, 0, 1).
  mesh["transform"] = R"({"rotate_deg": [90, 90, 0]})"_json;
  expectExactly(loadOne(mesh).shape.vertices[3], 1, 0, 0);

  // Any angle, and a uniform scale given as one number.
  mesh["transform"] = R"({"scale": 2, "rotate_deg": [30, 0, 0]})"_json;
  const SceneObject turned = loadOne(mesh);
  const double c = std::cos(std::numbers::pi / 6), s = std::sin(std::numbers::pi / 6);
  expectNear(turned.shape.vertices[6], 2, 2 * c - 2 * s, 2 * s + 2 * c);
  expectNear(turned.shape.vertices[3], 0, 2 * c, 2 * s);
  // Angles beyond a turn reduce exactly.
  mesh["transform"] = R"({"rotate_deg": [0, 0, -270]})"_json;
  expectExactly(loadOne(mesh).shape.vertices[1], 0, 1, 0);
}

TEST_F(ObjectTest, MirroringScaleKeepsFacesOutwards) {
  json mesh = cubeMesh(R"({"type": "dielectric", "glass": "N-BK7"})"_json);
  mesh["transform"] = R"({"scale": [-1, 1, 1]})"_json;
  const SceneObject o = loadOne(mesh);
  expectExactly(o.shape.vertices[6], -1, 1, 1);
  EXPECT_TRUE(o.shape.closed);
  EXPECT_DOUBLE_EQ(signedVolume6(o.shape), 6.0);
}

TEST_F(ObjectTest, CubeMissingAFaceIsOpen) {
  write("open.obj", cubeObj(/*skipFace=*/1));
  json mesh = cubeMesh(R"({"type": "diffuse", "reflectance": 0.5})"_json);
  mesh["file"] = "open.obj";
  const SceneObject o = loadOne(mesh);  // fine for an opaque surface
  EXPECT_EQ(o.shape.triangles.size(), 10u);
  EXPECT_FALSE(o.shape.closed);

  mesh["material"] = R"({"type": "dielectric", "glass": "N-BK7"})"_json;
  expectObjectError(mesh, "/objects/0/material",
                    {"a dielectric needs a closed shape: a sphere or a closed mesh", "\"open.obj\" is not closed",
                     "the edge between vertices 5 and 6 belongs to face 2 only", "hole"});
}

TEST_F(ObjectTest, CubeWithAFlippedFaceIsNotClosed) {
  write("flipped.obj", cubeObj(-1, /*flipFace=*/0));
  json mesh = cubeMesh();
  mesh["file"] = "flipped.obj";
  EXPECT_FALSE(loadOne(mesh).shape.closed);

  mesh["material"] = R"({"type": "dielectric", "ior": 1.33})"_json;
  expectObjectError(mesh, "/objects/0/material",
                    {"\"flipped.obj\" is not closed", "face 1 and face 3 both run from vertex 1 to vertex 2",
                     "flipped"});
}

TEST_F(ObjectTest, EdgeFaultsAreFoundAndDescribed) {
  // Two triangles sharing an edge the same way, then three sharing one.
  const MeshTriangles same = {{0, 1, 2}, {0, 1, 3}};
  auto fault = findEdgeFault(same);
  ASSERT_TRUE(fault);
  EXPECT_EQ(fault->kind, MeshEdgeFault::Kind::SameDirection);
  EXPECT_EQ(fault->from, 0u);
  EXPECT_EQ(fault->to, 1u);
  const auto name = [](size_t k) { return "triangle " + std::to_string(k); };
  EXPECT_EQ(describeEdgeFault(*fault, 0, name),
            "triangle 0 and triangle 1 both run from vertex 0 to vertex 1 (one of them is flipped: seen from outside, "
            "every face must run counter-clockwise)");
  const MeshTriangles fin = {{0, 1, 2}, {1, 0, 3}, {1, 0, 4}};
  fault = findEdgeFault(fin);
  ASSERT_TRUE(fault);
  EXPECT_EQ(fault->kind, MeshEdgeFault::Kind::Shared);
  EXPECT_EQ(fault->triangles.size(), 3u);
  // A tetrahedron is closed.
  EXPECT_FALSE(findEdgeFault({{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}}));
}

// --- mesh errors ------------------------------------------------------------

TEST_F(ObjectTest, MissingObjIsNamedWithTheField) {
  json mesh = cubeMesh();
  mesh["file"] = "bunny.obj";
  expectObjectError(mesh, "/objects/0/file",
                    {"cannot read \"bunny.obj\": No such file or directory", "relative to the scene file's folder"});
  fs::create_directories(dir_ / "folder.obj");
  mesh["file"] = "folder.obj";
  expectObjectError(mesh, "/objects/0/file", {"cannot read \"folder.obj\": is a directory"});
}

TEST_F(ObjectTest, PolylineCornersAreCheckedLikeFaces) {
  // `l` lines are not used, but one with a vertex 0 is not an OBJ file.
  expectMeshError("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 0 1\nf 1 2 3\n",
                  {"\"bad.obj\" line 4, \"0\": polyline (l) 1 refers to vertex 0; OBJ numbers them from 1"});
}

TEST_F(ObjectTest, MeshWithoutTrianglesIsRefused) {
  expectMeshError("v 0 0 0\nv 1 0 0\nv 0 1 0\n", {"\"bad.obj\" has no triangles"});
  expectMeshError("", {"\"bad.obj\" has no triangles"});
  expectMeshError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n",
                  {"\"bad.obj\" line 4, \"f 1 2\": face 1 has 2 corners; a face needs at least 3"});
}

TEST_F(ObjectTest, VertexIndexOutOfRange) {
  expectMeshError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n",
                  {"\"bad.obj\" line 5, \"9\": face 2 refers to vertex 9, but the file has 3 vertices (1 to 3)"});
  expectMeshError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
                  {"\"bad.obj\" line 4, \"-4\": face 1 refers to vertex before the first (4 back from the 3 vertices "
                   "defined so far)"});
}

TEST_F(ObjectTest, NonFiniteAndOutOfWorldCoordinates) {
  expectMeshError("v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n",
                  {"\"bad.obj\" line 2, \"1e999\": vertex 2 has a coordinate that is not finite"});
  // 0 in OBJ syntax (which tinyobjloader read as 0 * inf, nan) is 0: the
  // face's first two corners are the same point.
  expectMeshError("v 0 0 0\nv 0e999999999 0 0\nv 0 1 0\nf 1 2 3\n",
                  {"\"bad.obj\": face 1 has zero area: its corners, vertices 1, 2 and 3, lie at [0, 0, 0], [0, 0, 0] "
                   "and [0, 1, 0]"});
  expectMeshError("v 0 0 0\nv 2e12 0 0\nv 0 1 0\nf 1 2 3\n",
                  {"\"bad.obj\": vertex 2 lies at [2000000000000, 0, 0]; world coordinates must be finite with "
                   "magnitude <= 1e+12 m"});
  // In the file's bounds, out of the world's after the transform.
  json mesh = cubeMesh();
  mesh["transform"] = R"({"scale": 1e12, "translate": [0, 0, 1]})"_json;
  expectObjectError(mesh, "/objects/0/file",
                    {"\"cube.obj\": vertex 5 lies at [0, 0, 1000000000001] after the transform ([0, 0, 1] in the "
                     "file)"});
}

TEST_F(ObjectTest, DegenerateTriangleNamesItsFaceAndVertices) {
  expectMeshError("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n",
                  {"\"bad.obj\": face 2 has zero area: its corners, vertices 1, 2 and 4, lie at [0, 0, 0], [1, 0, 0] "
                   "and [2, 0, 0]"});
  expectMeshError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 3 3 1\n", {"face 2 has zero area", "vertices 3, 3 and 1"});
}

TEST_F(ObjectTest, TriangleBudgetIsEnforced) {
  json_fields::Source source;
  source.file = "scene.json";
  source.dir = dir_;
  source.raise = [](const std::string& message) { throw SceneError(message); };
  Shape shape;
  try {
    loadObjMesh(source, "/objects/4/file", dir_ / "cube.obj", "cube.obj", MeshTransform{}, 11, shape);
    FAIL() << "expected the budget to be refused";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("scene.json: /objects/4/file: \"cube.obj\" has 12 triangles, more than the 11 "
                                          "left of the 20000000 a scene may hold",
                                          0),
              0u)
        << e.what();
  }
  EXPECT_EQ(loadObjMesh(source, "/objects/4/file", dir_ / "cube.obj", "cube.obj", MeshTransform{}, 12, shape), "");
  EXPECT_EQ(shape.triangles.size(), 12u);
}

TEST_F(ObjectTest, TransformFieldsAreChecked) {
  json mesh = cubeMesh();
  mesh["transform"] = R"({"scale": 0})"_json;
  expectObjectError(mesh, "/objects/0/transform/scale", {"must be a finite number other than 0"});
  mesh["transform"] = R"({"scale": [1, 0, 1]})"_json;
  expectObjectError(mesh, "/objects/0/transform/scale/1", {"other than 0"});
  mesh["transform"] = R"({"scale": [1, 1]})"_json;
  expectObjectError(mesh, "/objects/0/transform/scale", {"a number or an array of 3 numbers"});
  mesh["transform"] = R"({"rotate": [0, 0, 90]})"_json;
  expectObjectError(mesh, "/objects/0/transform/rotate", {"unknown key \"rotate\"", "translate, rotate_deg, scale"});
  mesh["transform"] = R"({"translate": [0, 0, 2e12]})"_json;
  expectObjectError(mesh, "/objects/0/transform/translate/2", {"magnitude <= 1e+12"});
}

// --- materials and reflectances ----------------------------------------------

TEST_F(ObjectTest, ReflectanceNumberIsOneNode) {
  const SceneObject o = loadOne(R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 1,
                                    "material": {"type": "diffuse", "reflectance": 0.8}})"_json);
  EXPECT_EQ(o.material.type, MaterialType::Diffuse);
  ASSERT_EQ(o.material.reflectance.size(), 1u);
  EXPECT_EQ(o.material.reflectanceNm.size(), 1u);
  EXPECT_EQ(o.material.reflectanceLabel, "0.8");
  for (double nm : {200.0, 550.0, 900.0}) EXPECT_EQ(o.material.reflectanceAt(nm), 0.8);
}

TEST_F(ObjectTest, MirrorReflectanceDefaultsToOne) {
  const SceneObject o = loadOne(R"({"type": "disk", "center": [0, 0, 3], "normal": [0, 0, 1], "radius_m": 1,
                                    "material": {"type": "mirror"}})"_json);
  EXPECT_EQ(o.material.type, MaterialType::Mirror);
  EXPECT_EQ(o.material.reflectanceAt(400.0), 1.0);
  EXPECT_EQ(o.material.reflectanceLabel, "1");
}

TEST_F(ObjectTest, ColorCheckerPatchesByName) {
  json sphere = R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 1,
                    "material": {"type": "diffuse", "reflectance": "dark_skin"}})"_json;
  SceneObject o = loadOne(sphere);
  EXPECT_EQ(o.material.reflectanceLabel, "dark_skin");
  ASSERT_EQ(o.material.reflectanceNm.size(), 81u);  // 380..780 nm at 5 nm
  EXPECT_EQ(o.material.reflectanceNm.front(), 380.0);
  EXPECT_EQ(o.material.reflectanceNm.back(), 780.0);
  EXPECT_EQ(o.material.reflectanceAt(380.0), 0.048);
  EXPECT_EQ(o.material.reflectanceAt(385.0), 0.051);
  EXPECT_NEAR(o.material.reflectanceAt(382.5), 0.0495, 1e-15);  // linear between nodes
  EXPECT_EQ(o.material.reflectanceAt(300.0), 0.048);            // held outside
  EXPECT_EQ(o.material.reflectanceAt(1000.0), o.material.reflectance.back());

  sphere["material"]["reflectance"] = "white_9.5";
  o = loadOne(sphere);
  EXPECT_EQ(o.material.reflectanceAt(380.0), 0.153);
  sphere["material"]["type"] = "mirror";
  sphere["material"]["reflectance"] = "black_2";
  EXPECT_EQ(loadOne(sphere).material.reflectanceAt(380.0), 0.032);
}

TEST_F(ObjectTest, ReflectanceTakesTheSpdObjectForms) {
  write("paint.csv", "wavelength_nm,matte,gloss\n400,0.1,0.2\n500,0.5,0.6\n700,0.9,0.7\n");
  json sphere = R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 1, "material": {"type": "diffuse"}})"_json;

  sphere["material"]["reflectance"] = R"({"csv": "paint.csv", "column": "gloss"})"_json;
  SceneObject o = loadOne(sphere);
  EXPECT_EQ(o.material.reflectanceNm, (std::vector<double>{400, 500, 700}));
  EXPECT_EQ(o.material.reflectance, (std::vector<double>{0.2, 0.6, 0.7}));
  EXPECT_EQ(o.material.reflectanceLabel, "csv paint.csv column gloss");
  EXPECT_EQ(o.material.reflectanceFile, dir_ / "paint.csv");
  EXPECT_DOUBLE_EQ(o.material.reflectanceAt(600.0), 0.65);

  sphere["material"]["reflectance"] = R"({"table": [[400, 0.25], [800, 0.75]]})"_json;
  o = loadOne(sphere);
  EXPECT_DOUBLE_EQ(o.material.reflectanceAt(600.0), 0.5);
  EXPECT_TRUE(o.material.reflectanceFile.empty());

  sphere["material"]["reflectance"] = R"({"lambda_nm": [400, 600], "value": [0, 1]})"_json;
  o = loadOne(sphere);
  EXPECT_DOUBLE_EQ(o.material.reflectanceAt(500.0), 0.5);
  EXPECT_EQ(o.material.reflectanceAt(700.0), 1.0);
}

TEST_F(ObjectTest, DielectricIndexForms) {
  json sphere = R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 1})"_json;

  sphere["material"] = R"({"type": "dielectric", "glass": "N-BK7"})"_json;
  SceneObject o = loadOne(sphere);
  EXPECT_EQ(o.material.type, MaterialType::Dielectric);
  EXPECT_EQ(o.material.glassLabel, "N-BK7");
  EXPECT_NEAR(o.material.refractiveIndexAt(587.5618), 1.5168, 1e-4);  // the d line
  const SellmeierGlass* bk7 = glassNamed("N-BK7");
  ASSERT_TRUE(bk7);
  EXPECT_EQ(o.material.sellmeierB, bk7->b);
  EXPECT_EQ(o.material.sellmeierC, bk7->cUm2);
  EXPECT_GT(o.material.refractiveIndexAt(400.0), o.material.refractiveIndexAt(700.0));  // normal dispersion

  for (const char* name : {"N-SF11", "F2", "fused_silica"}) {
    sphere["material"]["glass"] = name;
    EXPECT_EQ(loadOne(sphere).material.glassLabel, name);
  }

  sphere["material"] = R"({"type": "dielectric", "sellmeier": {"b": [1.03961212, 0.231792344, 1.01046945],
                            "c_um2": [0.00600069867, 0.0200179144, 103.560653]}})"_json;
  o = loadOne(sphere);
  EXPECT_EQ(o.material.glassLabel, "sellmeier");
  EXPECT_EQ(o.material.refractiveIndexAt(550.0), sellmeierIndex(bk7->b, bk7->cUm2, 550.0));

  sphere["material"] = R"({"type": "dielectric", "ior": 1.5})"_json;
  o = loadOne(sphere);
  EXPECT_EQ(o.material.glassLabel, "ior 1.5");
  for (double nm : {360.0, 550.0, 830.0}) EXPECT_NEAR(o.material.refractiveIndexAt(nm), 1.5, 1e-15);
  sphere["material"]["ior"] = 1;
  EXPECT_EQ(loadOne(sphere).material.refractiveIndexAt(500.0), 1.0);
}

TEST_F(ObjectTest, ReflectanceOutOfRangeNamesTheWorstWavelength) {
  json sphere = R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 1, "material": {"type": "diffuse"}})"_json;
  const std::string rp = "/objects/0/material/reflectance";
  sphere["material"]["reflectance"] = 1.5;
  expectObjectError(sphere, rp, {"must be a reflectance in [0, 1] (got 1.5)"});
  sphere["material"]["reflectance"] = -0.1;
  expectObjectError(sphere, rp, {"must be a reflectance in [0, 1] (got -0.1)"});
  sphere["material"]["reflectance"] = R"({"table": [[400, 0.5], [500, 1.2], [600, 1.4], [700, 0.9]]})"_json;
  expectObjectError(sphere, rp, {"must lie in [0, 1] at every wavelength", "is 1.4 at 600 nm"});
  // An illuminant is a spectrum of a light: its values are far above 1.
  sphere["material"]["reflectance"] = "D65";
  expectObjectError(sphere, rp, {"must lie in [0, 1] at every wavelength, but D65 is"});
  sphere["material"]["reflectance"] = R"({"blackbody_k": 3000})"_json;
  expectObjectError(sphere, rp, {"must lie in [0, 1]", "blackbody 3000 K"});
}

TEST_F(ObjectTest, ReflectanceFormsThatAreRefused) {
  json sphere = R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 1, "material": {"type": "diffuse"}})"_json;
  const std::string rp = "/objects/0/material/reflectance";
  sphere["material"]["reflectance"] = R"({"line_nm": 532})"_json;
  expectObjectError(sphere, rp + "/line_nm", {"a spectral line is light, not a reflectance"});
  sphere["material"]["reflectance"] = "dark_skn";
  expectObjectError(sphere, rp, {"unknown reflectance \"dark_skn\"; did you mean \"dark_skin\"?", "white_9.5"});
  sphere["material"]["reflectance"] = true;
  expectObjectError(sphere, rp, {"must be a number in [0, 1], a ColorChecker patch name", "(got true)"});
  sphere["material"]["reflectance"] = R"({"tabel": [[400, 0.5]]})"_json;
  expectObjectError(sphere, rp + "/tabel", {"did you mean \"table\"?"});
  sphere["material"]["reflectance"] = R"({"csv": "no_such.csv"})"_json;
  expectObjectError(sphere, rp + "/csv", {"SPD file not found: \"no_such.csv\""});
  sphere["material"].erase("reflectance");
  expectObjectError(sphere, "/objects/0/material/reflectance", {"missing required field \"reflectance\"", "dark_skin"});
}

TEST_F(ObjectTest, DielectricErrors) {
  json sphere = R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 1})"_json;
  const auto expectMaterial = [&](const json& material, const std::string& pointer,
                                  const std::vector<std::string>& phrases) {
    sphere["material"] = material;
    expectObjectError(sphere, pointer, phrases);
  };
  expectMaterial(R"({"type": "dielectric", "glass": "N-BK8"})"_json, "/objects/0/material/glass",
                 {"unknown glass \"N-BK8\"; did you mean \"N-BK7\"?", "N-BK7, N-SF11, F2, fused_silica"});
  // The name without the catalogue's "N-" prefix: too far by edit distance
  // for three letters, but held in the catalogue's name.
  expectMaterial(R"({"type": "dielectric", "glass": "BK7"})"_json, "/objects/0/material/glass",
                 {"unknown glass \"BK7\"; did you mean \"N-BK7\"?"});
  expectMaterial(R"({"type": "dielectric"})"_json, "/objects/0/material", {"a dielectric needs one of \"glass\""});
  expectMaterial(R"({"type": "dielectric", "ior": 1.5, "glass": "F2"})"_json, "/objects/0/material",
                 {"ambiguous"});
  expectMaterial(R"({"type": "dielectric", "ior": 0.9})"_json, "/objects/0/material/ior",
                 {"must be a refractive index, >= 1 and <= 5 (got 0.9)"});
  expectMaterial(R"({"type": "dielectric", "ior": 6})"_json, "/objects/0/material/ior", {"(got 6)"});
  expectMaterial(R"({"type": "dielectric", "sellmeier": {"b": [1, -0.1, 0], "c_um2": [0, 0, 0]}})"_json,
                 "/objects/0/material/sellmeier/b/1", {"must be a finite number >= 0 (got -0.1)"});
  expectMaterial(R"({"type": "dielectric", "sellmeier": {"b": [1, 0, 0], "c_um2": [0, -1, 0]}})"_json,
                 "/objects/0/material/sellmeier/c_um2/1", {"must be a finite number >= 0 (got -1)"});
  expectMaterial(R"({"type": "dielectric", "sellmeier": {"b": [1, 0], "c_um2": [0, 0, 0]}})"_json,
                 "/objects/0/material/sellmeier/b", {"must be an array of 3 finite numbers"});
  // C = 0.25 um^2 puts a pole at 500 nm, inside 360-830 nm.
  expectMaterial(R"({"type": "dielectric", "sellmeier": {"b": [1, 0.5, 0], "c_um2": [0.01, 0.25, 0]}})"_json,
                 "/objects/0/material/sellmeier", {"has a pole at 500 nm (C2 = 0.25 um^2)", "360-830 nm"});
  // Above the range every term is negative: n^2 < 1.
  expectMaterial(R"({"type": "dielectric", "sellmeier": {"b": [0.1, 0, 0], "c_um2": [1, 0, 0]}})"_json,
                 "/objects/0/material/sellmeier", {"must be finite and >= 1", "at 830 nm it is"});
  expectMaterial(R"({"type": "dielectric", "sellmeier": {"b": [5, 0, 0], "c_um2": [1, 0, 0]}})"_json,
                 "/objects/0/material/sellmeier", {"at 830 nm it is not a real number"});

  // A flat shape has no inside.
  for (const char* flat : {R"({"type": "rect", "center": [0, 0, 3], "normal": [0, 0, 1], "size_m": [1, 1]})",
                           R"({"type": "disk", "center": [0, 0, 3], "normal": [0, 0, 1], "radius_m": 1})"}) {
    json object = json::parse(flat);
    object["material"] = R"({"type": "dielectric", "glass": "F2"})"_json;
    expectObjectError(object, "/objects/0/material",
                      {"a dielectric needs a closed shape: a sphere or a closed mesh", "has no inside"});
  }
}

TEST_F(ObjectTest, PoleOutsideTheRangeIsFine) {
  // The same pole at 500 nm, with the spectrum above it.
  json scene = withObjects(json::array({R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 1,
      "material": {"type": "dielectric", "sellmeier": {"b": [1, 0.5, 0], "c_um2": [0.01, 0.25, 0]}}})"_json}));
  scene["spectrum"] = R"({"min_nm": 600, "max_nm": 800, "bins": 20})"_json;
  scene["lights"][0]["spd"] = R"({"blackbody_k": 3000})"_json;
  const Scene s = load(scene);
  EXPECT_GT(s.objects[0].material.refractiveIndexAt(800.0), 1.0);
}

// --- object schema errors ---------------------------------------------------

TEST_F(ObjectTest, SchemaErrors) {
  expectError(withObjects(json::object()), "/objects", {"must be an array of objects"});
  expectError(withObjects(json::array({3})), "/objects/0", {"must be a JSON object"});
  expectObjectError(R"({"type": "cube", "material": {"type": "absorber"}})"_json, "/objects/0/type",
                    {"unknown object type \"cube\"", "rect, disk, sphere, mesh"});
  expectObjectError(R"({"type": "sphre", "material": {"type": "absorber"}})"_json, "/objects/0/type",
                    {"did you mean \"sphere\"?"});
  expectObjectError(R"({"typ": "sphere"})"_json, "/objects/0/typ", {"did you mean \"type\"?"});
  expectObjectError(R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 1})"_json, "/objects/0/material",
                    {"missing required field \"material\""});
  expectObjectError(R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 1, "normal": [0, 0, 1],
                        "material": {"type": "absorber"}})"_json,
                    "/objects/0/normal", {"unknown key \"normal\" in a sphere object"});
  expectObjectError(R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 1, "material": {"type": "glass"}})"_json,
                    "/objects/0/material/type", {"unknown material type \"glass\"", "absorber, diffuse, mirror, dielectric"});
  expectObjectError(R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 1,
                        "material": {"type": "absorber", "reflectance": 0.5}})"_json,
                    "/objects/0/material/reflectance", {"unknown key \"reflectance\" in an absorber material"});
  expectObjectError(R"({"type": "sphere", "center": [0, 0, 3], "radius_m": 0, "material": {"type": "absorber"}})"_json,
                    "/objects/0/radius_m", {"must be a finite number > 0 (got 0)"});
  expectObjectError(R"({"type": "disk", "center": [0, 0, 3], "normal": [0, 0, 0], "radius_m": 1,
                        "material": {"type": "absorber"}})"_json,
                    "/objects/0/normal", {"must not be zero-length"});
  expectObjectError(R"({"type": "rect", "center": [0, 0, 3], "normal": [0, 0, 1], "size_m": [1, -1],
                        "material": {"type": "absorber"}})"_json,
                    "/objects/0/size_m/1", {"must be a finite number > 0 (got -1)"});
  expectObjectError(R"({"type": "rect", "center": [0, 0, 3], "normal": [0, 0, 1], "u_axis": [0, 0, 2],
                        "size_m": [1, 1], "material": {"type": "absorber"}})"_json,
                    "/objects/0/u_axis", {"is parallel to the normal"});
  expectObjectError(R"({"type": "sphere", "center": [0, 0, 2e12], "radius_m": 1, "material": {"type": "absorber"}})"_json,
                    "/objects/0/center/2", {"magnitude <= 1e+12"});
  expectObjectError(R"({"type": "mesh", "material": {"type": "absorber"}})"_json, "/objects/0/file",
                    {"missing required field \"file\" (an OBJ file)"});
  // The object's name is in its messages.
  expectObjectError(R"({"name": "ball", "type": "sphere", "center": [0, 0, 3], "radius_m": -1,
                        "material": {"type": "absorber"}})"_json,
                    "/objects/0/radius_m", {"(object \"ball\")"});
}

TEST_F(ObjectTest, MaxBounces) {
  json scene = baseScene();
  EXPECT_EQ(load(scene).render.maxBounces, 64u);
  scene["render"] = R"({"max_bounces": 8})"_json;
  EXPECT_EQ(load(scene).render.maxBounces, 8u);
  scene["render"]["max_bounces"] = 1024;
  EXPECT_EQ(load(scene).render.maxBounces, 1024u);
  for (const json& bad : {json(0), json(1025), json(2.5), json("8")}) {
    scene["render"]["max_bounces"] = bad;
    expectError(scene, "/render/max_bounces", {});
  }
}

// --- scenes built in code ---------------------------------------------------

class BuiltObjectTest : public ::testing::Test {
 protected:
  Scene scene() {
    Scene s;
    s.camera.position = {0, 0, 0};
    s.camera.lookAt = {0, 0, 1};
    Light light;
    light.type = LightType::Point;
    light.position = {0, 0, 2};
    light.powerW = 1;
    light.spd = *cieIlluminant("D65");
    s.lights.push_back(light);
    return s;
  }
  static SceneObject sphere() {
    SceneObject o;
    o.shape.type = ShapeType::Sphere;
    o.shape.center = {0, 0, 3};
    o.shape.radiusM = 1;
    o.shape.closed = true;
    return o;
  }
  static SceneObject tetrahedron() {
    SceneObject o;
    o.shape.type = ShapeType::Mesh;
    o.shape.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    o.shape.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
    o.shape.closed = true;
    return o;
  }
  void expectError(const SceneObject& object, const std::string& pointer, const std::string& phrase) {
    Scene s = scene();
    s.objects.push_back(object);
    try {
      validateScene(s);
      ADD_FAILURE() << "expected an error at " << pointer;
    } catch (const SceneError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind("<scene>: " + pointer + ": ", 0), 0u) << msg;
      EXPECT_NE(msg.find(phrase), std::string::npos) << "missing '" << phrase << "' in: " << msg;
    }
  }
};

TEST_F(BuiltObjectTest, ValidObjectsPass) {
  Scene s = scene();
  SceneObject glass = tetrahedron();
  glass.material.type = MaterialType::Dielectric;
  glass.material.sellmeierB = {1.25, 0, 0};
  s.objects.push_back(glass);
  SceneObject ball = sphere();
  ball.material.type = MaterialType::Diffuse;
  ball.material.reflectanceNm = {400, 700};
  ball.material.reflectance = {0, 1};
  s.objects.push_back(ball);
  EXPECT_NO_THROW(validateScene(s));
  EXPECT_NEAR(glass.material.refractiveIndexAt(500.0), 1.5, 1e-15);
}

TEST_F(BuiltObjectTest, ShapeRules) {
  SceneObject o = sphere();
  o.shape.radiusM = -1;
  expectError(o, "/objects/0/radius_m", "must be a length in metres");
  o = sphere();
  o.shape.center.x = NAN;
  expectError(o, "/objects/0/center", "must be finite");
  o = sphere();
  o.shape.type = ShapeType::Disk;
  o.shape.normal = {0, 0, 2};
  expectError(o, "/objects/0/normal", "must be a unit vector");
  o.shape.type = ShapeType::Rect;
  o.shape.normal = {0, 0, 1};
  o.shape.sizeM = {1, 1};
  o.shape.uAxis = {0.6, 0, 0.8};
  expectError(o, "/objects/0/u_axis", "must be a unit vector perpendicular to the normal");
  o.shape.sizeM = {1, 0};
  expectError(o, "/objects/0/size_m/1", "must be a length in metres");

  o = tetrahedron();
  o.shape.triangles[2][1] = 4;
  expectError(o, "/objects/0/triangles/2", "refers to vertex 4, but the mesh has 4 vertices");
  o = tetrahedron();
  o.shape.vertices[3] = {0, 0, 2e12};
  expectError(o, "/objects/0/vertices/3", "magnitude <= 1e+12");
  o = tetrahedron();
  o.shape.triangles.push_back({0, 1, 1});
  expectError(o, "/objects/0/triangles/4", "has zero area");
  o = tetrahedron();
  o.shape.triangles.clear();
  expectError(o, "/objects/0/triangles", "at least one triangle");
}

TEST_F(BuiltObjectTest, MaterialRules) {
  SceneObject o = sphere();
  o.material.type = MaterialType::Diffuse;
  expectError(o, "/objects/0/material/reflectance", "at least one");
  o.material.reflectanceNm = {500};
  o.material.reflectance = {NAN};
  expectError(o, "/objects/0/material/reflectance", "must be a reflectance in [0, 1]");
  o.material.reflectanceNm = {500, 400};
  o.material.reflectance = {0.5, 0.5};
  expectError(o, "/objects/0/material/reflectance", "strictly increasing");

  o = tetrahedron();
  o.material.type = MaterialType::Dielectric;
  o.material.sellmeierB = {0.5, 0, 0};
  o.shape.triangles.pop_back();
  expectError(o, "/objects/0/material",
              "this mesh is not closed: the edge between vertices 0 and 2 belongs to triangle 0 only");
  o = sphere();
  o.material.type = MaterialType::Dielectric;
  o.material.sellmeierB = {NAN, 0, 0};
  expectError(o, "/objects/0/material/sellmeier/b/0", "must be a finite number >= 0");
}

}  // namespace
}  // namespace spectrace
