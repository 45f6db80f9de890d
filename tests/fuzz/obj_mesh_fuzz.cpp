// libFuzzer target: OBJ mesh files (parseObjMesh: readObjText, then the
// mesh checks), as read for a scene's mesh object. Bad input must end in
// SceneError (exit code 2); an accepted mesh must be what readObjText read
// (its vertices, and each face's fan) and what the tracer relies on:
// indices in range, finite vertices within the world bounds, no triangle of
// zero area. Read in two parts, split at a line's end, the text gives what
// one reader finds (readObjTextInParts).
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

void checkMesh(const Shape& shape, const ObjText& obj) {
  fuzz::require(!obj.fault, "a mesh was accepted although readObjText refused it");
  fuzz::require(shape.vertices == obj.vertices, "the vertices differ from those readObjText read");
  uint64_t triangles = 0;
  for (uint32_t corners : obj.cornerCounts) triangles += corners - 2;
  fuzz::require(shape.triangles.size() == triangles, "the triangles are not the faces' fans");
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

void checkSameReading(const ObjText& got, const ObjText& whole) {
  fuzz::require(got.fault.has_value() == whole.fault.has_value(), "a split text is refused differently");
  if (whole.fault) {
    fuzz::require(got.fault->line == whole.fault->line && got.fault->token == whole.fault->token &&
                      got.fault->what == whole.fault->what,
                  "a split text's fault differs from the whole text's");
    return;
  }
  fuzz::require(got.vertices == whole.vertices && got.corners == whole.corners &&
                    got.cornerCounts == whole.cornerCounts,
                "a split text reads differently from the whole text");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const ObjText obj = readObjText(text);
  if (const size_t end = text.find('\n', text.size() / 2); end != std::string::npos && end + 1 < text.size())
    checkSameReading(readObjTextInParts(text, {end + 1}), readObjTextInParts(text, {}));
  json_fields::Source source;
  source.file = "fuzz.json";
  source.raise = [](const std::string& message) { throw SceneError(message); };
  Shape shape;
  try {
    parseObjMesh(source, "/objects/0/file", text, "fuzz.obj", MeshTransform{}, kMaxSceneTriangles, shape);
  } catch (const SceneError&) {
    return 0;
  }
  checkMesh(shape, obj);
  return 0;
}
