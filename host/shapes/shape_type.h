#pragma once
// One unit per shape kind: everything the host knows about a kind (its JSON
// keys, checks, the device primitives it becomes and their bounds, whether
// it bounds a solid) lives in its own file, shapes/<kind>_shape.cpp; the
// kernel's side is one file per primitive in shaders/shapes/.
// They are listed once, in host/shapes/CMakeLists.txt
// (spectrace_unit_table), from which shape_types.cpp builds the table.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "camera/camera_frame.h"
#include "device_shared.h"
#include "json/json_fields.h"
#include "shapes/shape.h"

namespace spectrace {

// One primitive's axis-aligned bounds, in double.
struct PrimitiveBounds {
  glm::dvec3 lo, hi;
};

// A float primitive and the double box that holds every point the kernel
// can find on it.
struct PlacedPrimitive {
  device::Primitive primitive{};
  PrimitiveBounds bounds{};
};

// How a unit's `validate` reports a problem: throws SceneError naming the
// object's field (`key` relative to the object, e.g. "radius_m").
class ShapeFieldCheck {
 public:
  virtual ~ShapeFieldCheck() = default;
  [[noreturn]] virtual void fail(const std::string& key, const std::string& what) const = 0;
  // For "(got ...)": the value as the scene file wrote it when the scene came
  // from a file that has `key`, else `fallback`.
  virtual std::string got(const std::string& key, double fallback) const = 0;
  virtual std::string got(const std::string& key, const glm::dvec3& fallback) const = 0;
};

// What reading a shape needs besides its JSON.
struct ShapeReading {
  // The most triangles it may hold (what the scene has left).
  uint64_t trianglesLeft = 0;
  // The material kind that needs the shape closed, else nullptr, and the
  // material's field: a shape read from a file that is not closed is
  // refused there, in the file's own terms (its face numbers).
  const char* closedFor = nullptr;
  std::string materialPtr;
};

struct ShapeTypeUnit {
  ShapeType type;
  const char* name;  // "rect", "disk", ... (the JSON "type")
  // The kind's own JSON keys, besides "name", "type" and "material".
  json_fields::Keys keys;

  // Reads the object `v` at `ptr` into `shape` (types only: value ranges
  // are `validate`'s; a mesh's file is checked as it is read).
  void (*parse)(const json_fields::Source& c, const json_fields::Json& v, const std::string& ptr,
                const ShapeReading& reading, Shape& shape);
  // The kind's semantic checks (world bounds, lengths, unit vectors).
  void (*validate)(const Shape& shape, const ShapeFieldCheck& check);
  // Why the shape cannot hold a material of kind `material` that refracts
  // into it (no inside, a hole, faces turned inwards), as the whole message;
  // "" when it bounds a solid with outward faces.
  std::string (*notClosedBecause)(const Shape& shape, std::string_view material);
  // Appends its primitives, in the camera frame, with `material` as their
  // material index (a mesh: one triangle per triangle the kernel can meet).
  void (*place)(const Shape& shape, const CameraFrame& frame, uint32_t material, std::vector<PlacedPrimitive>& out);
};

const ShapeTypeUnit& shapeTypeUnit(ShapeType type);
// nullptr for an unknown name.
const ShapeTypeUnit* shapeTypeUnitNamed(std::string_view name);
// Every unit, in ShapeType order.
const std::vector<const ShapeTypeUnit*>& shapeTypeUnits();

}  // namespace spectrace
