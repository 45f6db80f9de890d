#pragma once
// Scene objects built in code for tests: shapes and materials as the scene
// loader would make them, placed in the camera's frame.
//
// The camera frame (camera/camera_frame.h: right, up, forward, where
// right = forward x up) is left-handed, so world and camera coordinates
// differ by a reflection. Tests reason in the camera frame, where the
// kernel works (sensor at z = 0 looking along +z, image columns along +x,
// rows down from +y), and place objects in the world through toWorld.
#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "camera/camera_frame.h"
#include "scene/scene.h"
#include "spectrum/cie_data.h"
#include "spectrum/glass.h"

namespace spectrace::testing {

// A camera-frame point or direction in world coordinates.
inline glm::dvec3 toWorld(const Camera& camera, const glm::dvec3& local) {
  const CameraFrame f = CameraFrame::fromCamera(camera);
  return f.origin + f.right * local.x + f.up * local.y + f.forward * local.z;
}
inline glm::dvec3 directionToWorld(const Camera& camera, const glm::dvec3& local) {
  const CameraFrame f = CameraFrame::fromCamera(camera);
  return f.right * local.x + f.up * local.y + f.forward * local.z;
}

// --- materials ---------------------------------------------------------------

inline SurfaceMaterial absorberMaterial() { return SurfaceMaterial{}; }

// Diffuse or mirror of one reflectance at every wavelength (the loader's
// form of a number: one node).
inline SurfaceMaterial constantMaterial(MaterialType type, double reflectance) {
  SurfaceMaterial m;
  m.type = type;
  m.reflectanceNm = {550.0};
  m.reflectance = {reflectance};
  m.reflectanceLabel = std::to_string(reflectance);
  return m;
}
inline SurfaceMaterial diffuseMaterial(double reflectance) { return constantMaterial(MaterialType::Diffuse, reflectance); }
inline SurfaceMaterial mirrorMaterial(double reflectance) { return constantMaterial(MaterialType::Mirror, reflectance); }

// Diffuse with a ColorChecker patch's reflectance (Ohta 1997, 380-780 nm
// at 5 nm), as the loader resolves "reflectance": "<patch>".
inline SurfaceMaterial colorCheckerMaterial(const std::string& patch) {
  const CsvTable& table = colorCheckerTable();
  const auto it = std::find(table.columns.begin(), table.columns.end(), patch);
  SurfaceMaterial m;
  m.type = MaterialType::Diffuse;
  if (it == table.columns.end()) return m;  // no reflectance: validateScene refuses it
  m.reflectanceNm = table.lambdaNm;
  m.reflectance = table.data[size_t(it - table.columns.begin())];
  m.reflectanceLabel = patch;
  return m;
}

// A catalogue glass (glass.h), as "glass": "<name>".
inline SurfaceMaterial glassMaterial(const std::string& name) {
  SurfaceMaterial m;
  m.type = MaterialType::Dielectric;
  if (const SellmeierGlass* g = glassNamed(name)) {
    m.sellmeierB = g->b;
    m.sellmeierC = g->cUm2;
  }
  m.glassLabel = name;
  return m;
}

// A dispersion-free dielectric, as "ior": n.
inline SurfaceMaterial iorMaterial(double n) {
  SurfaceMaterial m;
  m.type = MaterialType::Dielectric;
  m.sellmeierB = {n * n - 1.0, 0.0, 0.0};
  m.glassLabel = "ior " + std::to_string(n);
  return m;
}

// --- shapes, given in the camera frame ---------------------------------------

inline SceneObject namedObject(const std::string& name, size_t index, const Shape& shape, const SurfaceMaterial& m) {
  SceneObject o;
  o.label = "/objects/" + std::to_string(index);
  o.name = name;
  o.shape = shape;
  o.material = m;
  return o;
}

// A rect of size [along uAxis, across] with the given unit normal and
// uAxis (perpendicular to it).
inline Shape rectShape(const Camera& camera, glm::dvec3 centre, glm::dvec3 normal, glm::dvec3 uAxis, glm::dvec2 size) {
  Shape s;
  s.type = ShapeType::Rect;
  s.center = toWorld(camera, centre);
  s.normal = directionToWorld(camera, glm::normalize(normal));
  s.uAxis = directionToWorld(camera, glm::normalize(uAxis));
  s.sizeM = size;
  return s;
}

inline Shape diskShape(const Camera& camera, glm::dvec3 centre, glm::dvec3 normal, double radius) {
  Shape s;
  s.type = ShapeType::Disk;
  s.center = toWorld(camera, centre);
  s.normal = directionToWorld(camera, glm::normalize(normal));
  s.radiusM = radius;
  return s;
}

inline Shape sphereShape(const Camera& camera, glm::dvec3 centre, double radius) {
  Shape s;
  s.type = ShapeType::Sphere;
  s.center = toWorld(camera, centre);
  s.radiusM = radius;
  s.closed = true;
  return s;
}

// A closed triangle mesh from vertices given in the world (the loader's
// Shape after an OBJ file's transform): triangles counter-clockwise seen
// from outside in world coordinates.
inline Shape meshShape(std::vector<glm::dvec3> worldVertices, std::vector<std::array<uint32_t, 3>> triangles) {
  Shape s;
  s.type = ShapeType::Mesh;
  s.meshFile = "built-in-test";
  s.vertices = std::move(worldVertices);
  s.triangles = std::move(triangles);
  s.closed = true;
  return s;
}

// The regular octahedron with vertices at centre +- radius along the world
// axes, faces counter-clockwise seen from outside (world coordinates).
inline Shape worldOctahedron(glm::dvec3 worldCentre, double radius) {
  std::vector<glm::dvec3> v;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {1.0, -1.0}) {
      glm::dvec3 p = worldCentre;
      p[axis] += sign * radius;
      v.push_back(p);  // index 2 axis + (sign < 0)
    }
  std::vector<std::array<uint32_t, 3>> t;
  for (uint32_t sx = 0; sx < 2; ++sx)
    for (uint32_t sy = 0; sy < 2; ++sy)
      for (uint32_t sz = 0; sz < 2; ++sz) {
        const uint32_t x = sx, y = 2 + sy, z = 4 + sz;
        // (+x, +y, +z) runs counter-clockwise seen from outside; each
        // negative axis mirrors the face, so an odd count reverses it.
        if ((sx + sy + sz) % 2 == 0) t.push_back({x, y, z});
        else t.push_back({x, z, y});
      }
  return meshShape(std::move(v), std::move(t));
}

// The axis-aligned box [lo, hi] in world coordinates as 12 triangles,
// counter-clockwise seen from outside.
inline Shape worldBox(glm::dvec3 lo, glm::dvec3 hi) {
  std::vector<glm::dvec3> v;
  for (int i = 0; i < 8; ++i) v.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  // Each face as a quad counter-clockwise from outside, split into two.
  const std::array<std::array<uint32_t, 4>, 6> quads{{
      {0, 4, 6, 2},  // -x
      {1, 3, 7, 5},  // +x
      {0, 1, 5, 4},  // -y
      {2, 6, 7, 3},  // +y
      {0, 2, 3, 1},  // -z
      {4, 5, 7, 6},  // +z
  }};
  std::vector<std::array<uint32_t, 3>> t;
  for (const auto& q : quads) {
    t.push_back({q[0], q[1], q[2]});
    t.push_back({q[0], q[2], q[3]});
  }
  return meshShape(std::move(v), std::move(t));
}

// Six times the signed volume a closed mesh encloses: positive when its
// faces run counter-clockwise seen from outside (in the coordinates given).
inline double signedVolume6(const std::vector<glm::dvec3>& v, const std::vector<std::array<uint32_t, 3>>& t) {
  double sum = 0.0;
  for (const auto& f : t) sum += glm::dot(v[f[0]], glm::cross(v[f[1]], v[f[2]]));
  return sum;
}

}  // namespace spectrace::testing
