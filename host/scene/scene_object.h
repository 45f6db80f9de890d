#pragma once
// Objects a scene places between its lights and its camera: a shape with a
// material (world coordinates in double, metres; the material's kinds are
// units, materials/material_type.h). The kernel's side is
// shaders/transport.h; the compiler turns shapes into primitives
// (device_shared.h) and builds the BVH over them.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "device_shared.h"
#include "materials/material.h"

namespace spectrace {

enum class ShapeType { Rect, Disk, Sphere, Mesh };
const char* shapeTypeName(ShapeType type);

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
  std::vector<glm::dvec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
  // mesh: every edge is shared by exactly two triangles that traverse it in
  // opposite directions, so the mesh bounds a solid (sphere: always).
  bool closed = false;
};

struct SceneObject {
  std::string label;  // JSON pointer, e.g. "/objects/2", for messages
  std::string name;   // optional "name"
  Shape shape;
  SurfaceMaterial material;
};

}  // namespace spectrace
