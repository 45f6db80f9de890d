#pragma once
// An object's shape as a scene describes it (world coordinates in double,
// metres). What each kind reads, checks and becomes on the device is in its
// unit (shapes/shape_type.h).
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "device_shared.h"

namespace spectrace {

// ShapeType is defined in device_shared.h, beside the primitives.

// "rect", "disk", ... (the unit's name).
const char* shapeTypeName(ShapeType type);

// Mesh triangles a scene may hold: far above hand-made scenes and scanned
// models, and the compiled primitives and BVH (about 100 bytes a triangle)
// stay a few GB.
inline constexpr uint64_t kMaxSceneTriangles = 20'000'000;

struct Shape {
  ShapeType type = ShapeType::Rect;
  // rect, disk, sphere: `center`; rect, disk: `normal` (unit), rect: `u_axis`
  // (unit, perpendicular to the normal) and `size_m` [along u_axis, across].
  glm::dvec3 center{0.0};
  glm::dvec3 normal{0.0, 0.0, 1.0};
  glm::dvec3 uAxis{1.0, 0.0, 0.0};
  glm::dvec2 sizeM{0.0};
  double radiusM = 0.0;  // disk, sphere
  // mesh: the OBJ file, and its triangles in world coordinates after the
  // object's transform (scale, then rotate x, y, z in degrees, then
  // translate). Counter-clockwise seen from outside faces outwards.
  std::filesystem::path meshFile;
  // The SHA-256 (sceneSha256Hex) of the OBJ bytes the mesh was read from;
  // empty for a mesh given as vertices and triangles.
  std::string meshSha256;
  std::vector<glm::dvec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
  // What the reader found: mesh: every edge is shared by exactly two
  // triangles that traverse it in opposite directions, so the mesh bounds a
  // solid (sphere: always). The checks ask the unit (notClosedBecause).
  bool closed = false;
};

}  // namespace spectrace
