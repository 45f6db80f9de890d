// libFuzzer target: OBJ mesh files (checkObjText, then parseObjMesh:
// tinyobjloader and the mesh checks), as read for a scene's mesh object.
// Bad input must end in SceneError (exit code 2); an accepted mesh must be
// what the text check counted (the two readers agree) and what the tracer
// relies on: indices in range, finite vertices within the world bounds, no
// triangle of zero area.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_support.h"
#include "json/scene_error.h"
#include "shapes/obj_mesh.h"
#include "shapes/obj_text.h"
#include "scene/scene_limits.h"

using namespace spectrace;

namespace {

constexpr std::string_view kDisagree = "fuzz.json: /objects/0/file: \"fuzz.obj\": the readers disagree";

void checkMesh(const Shape& shape, const ObjTextCheck& check) {
  fuzz::require(!check.fault, "a mesh was accepted although its text check refused it");
  fuzz::require(shape.vertices.size() == check.vertices, "the vertex count differs from the text check's");
  for (const auto& p : shape.vertices)
    for (int a = 0; a < 3; ++a) {
      fuzz::requireFinite(p[a], "a vertex coordinate");
      fuzz::require(std::abs(p[a]) <= kMaxCoordinateM, "a vertex outside the world bounds was accepted");
    }
  fuzz::require(!shape.triangles.empty(), "a mesh without triangles was accepted");
  for (const auto& t : shape.triangles)
    for (uint32_t v : t) fuzz::require(v < shape.vertices.size(), "a triangle index is out of range");
  fuzz::require(!findDegenerateTriangle(shape.vertices, shape.triangles), "a zero-area triangle was accepted");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const ObjTextCheck check = checkObjText(text);
  json_fields::Source source;
  source.file = "fuzz.json";
  source.raise = [](const std::string& message) { throw SceneError(message); };
  Shape shape;
  try {
    parseObjMesh(source, "/objects/0/file", text, "fuzz.obj", MeshTransform{}, kMaxSceneTriangles, shape);
  } catch (const SceneError& e) {
    // A prefix, not a search: a token quoted in a message may hold any text.
    fuzz::require(!std::string_view(e.what()).starts_with(kDisagree), e.what());
    return 0;
  }
  checkMesh(shape, check);
  return 0;
}
