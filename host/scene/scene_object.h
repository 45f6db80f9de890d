#pragma once
// Objects a scene places between its lights and its camera: a shape with a
// material (world coordinates in double, metres). The kernel's side is
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
#include "spectrum/spd.h"

namespace spectrace {

enum class ShapeType { Rect, Disk, Sphere, Mesh };
const char* shapeTypeName(ShapeType type);

// Numbered as the kernel numbers them.
enum class MaterialType : uint32_t {
  Absorber = device::kMaterialAbsorber,
  Diffuse = device::kMaterialDiffuse,
  Mirror = device::kMaterialMirror,
  Dielectric = device::kMaterialDielectric,
};
const char* materialTypeName(MaterialType type);

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

struct SurfaceMaterial {
  MaterialType type = MaterialType::Absorber;
  // diffuse, mirror: reflectance in [0, 1], linear between the nodes and
  // holding its end values outside them (a constant is one node).
  std::vector<double> reflectanceNm;
  std::vector<double> reflectance;
  std::string reflectanceLabel;  // "0.8", "dark_skin", "paint.csv", ...
  std::filesystem::path reflectanceFile;  // the CSV it was read from (an input: never an output); else empty
  // dielectric: n^2 = 1 + sum B_i l^2 / (l^2 - C_i), l in micrometres; a
  // constant ior n is B = {n^2 - 1, 0, 0}, C = {0, 0, 0}.
  std::array<double, 3> sellmeierB{};
  std::array<double, 3> sellmeierC{};
  std::string glassLabel;  // "N-BK7", "sellmeier", "ior 1.5"

  // The reflectance at a wavelength (diffuse, mirror), as the kernel
  // evaluates its table: linear, held constant outside the nodes.
  double reflectanceAt(double lambdaNm) const;
  // The refractive index at a wavelength (dielectric).
  double refractiveIndexAt(double lambdaNm) const;
};

struct SceneObject {
  std::string label;  // JSON pointer, e.g. "/objects/2", for messages
  std::string name;   // optional "name"
  Shape shape;
  SurfaceMaterial material;
};

}  // namespace spectrace
