#include "compile/compile_objects.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "camera/camera_frame.h"
#include "compile/bvh.h"
#include "lights/light_shared.h"
#include "materials/material_type.h"

namespace spectrace {
namespace {

// A float primitive and the double box that holds every point the kernel
// can find on it.
struct PlacedPrimitive {
  device::Primitive primitive{};
  PrimitiveBounds bounds{};
};

glm::dvec3 toDouble(const glm::vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }

// Widens a box by a little more than the float rounding of the primitive's
// own points (a few ulps of its coordinates and of its size). The ray-box
// test widens its far distance too (objects.h); a ray that only grazes a
// primitive's edge may still be pruned where a brute-force walk finds it.
PrimitiveBounds padded(glm::dvec3 lo, glm::dvec3 hi) {
  const double size = glm::length(hi - lo);
  for (int i = 0; i < 3; ++i) {
    const double magnitude = std::max(std::abs(lo[i]), std::abs(hi[i]));
    const double pad = 1e-6 * (magnitude + size) + 1e-30;
    lo[i] -= pad;
    hi[i] += pad;
  }
  return {lo, hi};
}

PrimitiveBounds boundsOfPoints(std::initializer_list<glm::dvec3> points) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const glm::dvec3& p : points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return padded(lo, hi);
}

// Returns false, placing nothing, for a triangle whose float edges are
// parallel: validation refuses zero area in double, but a sliver can still
// lose it in float, and its normal would be NaN. Beams could not meet it.
bool placeTriangle(const glm::dvec3& v0, const glm::dvec3& v1, const glm::dvec3& v2, uint32_t material,
                   PlacedPrimitive& placed) {
  device::Primitive& p = placed.primitive;
  p.type = device::kPrimitiveTriangle;
  p.material = material;
  p.a = toFloat(v0);
  p.b = toFloat(v1 - v0);
  p.c = toFloat(v2 - v0);
  const glm::vec3 n = glm::cross(p.b, p.c);
  // (1e-30 m^4: an area below 1e-15 m^2, whose normal's length would
  // underflow when the kernel squares it.)
  if (!(glm::dot(n, n) > 1e-30f) || !std::isfinite(glm::dot(n, n))) return false;
  const glm::dvec3 a = toDouble(p.a);
  placed.bounds = boundsOfPoints({a, a + toDouble(p.b), a + toDouble(p.c)});
  return true;
}

void placeShape(const Shape& shape, const CameraFrame& frame, uint32_t material, std::vector<PlacedPrimitive>& out) {
  const glm::dvec3 centre = frame.pointToLocal(shape.center);
  PlacedPrimitive placed;
  device::Primitive& p = placed.primitive;
  p.material = material;
  switch (shape.type) {
    case ShapeType::Rect: {
      const glm::dvec3 n = glm::normalize(frame.directionToLocal(shape.normal));
      glm::dvec3 u = frame.directionToLocal(shape.uAxis);
      u = glm::normalize(u - n * glm::dot(u, n));
      const glm::dvec3 v = glm::cross(n, u);  // u x v = n
      p.type = device::kPrimitiveRect;
      p.a = toFloat(centre);
      p.b = toFloat(u * (0.5 * shape.sizeM.x));
      p.c = toFloat(v * (0.5 * shape.sizeM.y));
      const glm::dvec3 a = toDouble(p.a), b = toDouble(p.b), c = toDouble(p.c);
      placed.bounds = boundsOfPoints({a + b + c, a + b - c, a - b + c, a - b - c});
      out.push_back(placed);
      return;
    }
    case ShapeType::Disk: {
      const glm::dvec3 n = glm::normalize(frame.directionToLocal(shape.normal));
      p.type = device::kPrimitiveDisk;
      p.a = toFloat(centre);
      p.b = toFloat(n);
      p.c = glm::vec3(float(shape.radiusM * shape.radiusM), 0.0f, 0.0f);
      // A disk of radius r with unit normal n reaches r * sqrt(1 - n_i^2)
      // along axis i.
      const glm::dvec3 reach = shape.radiusM * glm::sqrt(glm::max(glm::dvec3(1.0) - n * n, glm::dvec3(0.0)));
      placed.bounds = padded(toDouble(p.a) - reach, toDouble(p.a) + reach);
      out.push_back(placed);
      return;
    }
    case ShapeType::Sphere: {
      p.type = device::kPrimitiveSphere;
      p.a = toFloat(centre);
      p.b = glm::vec3(float(shape.radiusM), float(shape.radiusM * shape.radiusM), 0.0f);
      placed.bounds = padded(toDouble(p.a) - shape.radiusM, toDouble(p.a) + shape.radiusM);
      out.push_back(placed);
      return;
    }
    case ShapeType::Mesh:
      // The camera frame (right = forward x up, up, forward) is a mirror
      // image of the world, so a triangle's corners are taken in the other
      // order there: counter-clockwise from outside stays outwards.
      for (const auto& t : shape.triangles) {
        PlacedPrimitive triangle;
        if (placeTriangle(frame.pointToLocal(shape.vertices[t[0]]), frame.pointToLocal(shape.vertices[t[2]]),
                          frame.pointToLocal(shape.vertices[t[1]]), material, triangle))
          out.push_back(triangle);
      }
      return;
  }
}

// The record's kind; the rest is the kind's unit's (its pack).
device::Material deviceMaterial(const SurfaceMaterial& material, DeviceScene& device) {
  device::Material record{};
  record.type = uint32_t(material.type);
  materialTypeUnit(material.type).pack(material, record, device.data);
  return record;
}

// Every primitive in one leaf under a root that bounds them all: the
// kernel then tests each one (the bench's brute force).
BuiltBvh oneLeaf(const std::vector<PrimitiveBounds>& bounds) {
  if (bounds.size() > 0xFFFFu) throw std::invalid_argument("brute force: at most 65535 primitives fit one leaf");
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  BuiltBvh bvh;
  for (uint32_t i = 0; i < bounds.size(); ++i) {
    lo = glm::min(lo, bounds[i].lo);
    hi = glm::max(hi, bounds[i].hi);
    bvh.order.push_back(i);
  }
  const PrimitiveBounds all = padded(lo, hi);
  device::BvhNode root{};
  root.boundsMin = glm::vec3(all.lo) - glm::vec3(1e-6f);
  root.boundsMax = glm::vec3(all.hi) + glm::vec3(1e-6f);
  root.next = 0;
  root.countAxis = uint32_t(bounds.size());
  bvh.nodes.push_back(root);
  bvh.depth = 1;
  return bvh;
}

}  // namespace

void compileObjects(const Scene& scene, const CompileOptions& options, DeviceScene& device) {
  device::TraceConstants& c = device.constants;
  c.maxBounces = scene.render.maxBounces;
  if (scene.objects.empty()) return;
  const CameraFrame frame = CameraFrame::fromCamera(scene.camera);
  std::vector<PlacedPrimitive> placed;
  bool connects = false;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    device.materials.push_back(deviceMaterial(object.material, device));
    connects = connects || materialTypeUnit(object.material.type).connectsToCamera;
    placeShape(object.shape, frame, uint32_t(i), placed);
  }
  std::vector<PrimitiveBounds> bounds;
  bounds.reserve(placed.size());
  for (const PlacedPrimitive& p : placed) bounds.push_back(p.bounds);
  BuiltBvh bvh = options.bruteForceObjects ? oneLeaf(bounds) : buildBvh(bounds);
  device.bvhNodes = std::move(bvh.nodes);
  device.primitives.reserve(placed.size());
  for (uint32_t index : bvh.order) device.primitives.push_back(placed[index].primitive);
  c.objectPrimitives = uint32_t(device.primitives.size());
  c.connect = options.connect && connects ? 1u : 0u;
}

}  // namespace spectrace
