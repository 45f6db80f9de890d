#include "compile/compile_objects.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "camera/camera_frame.h"
#include "compile/bvh.h"
#include "compile/wide_bvh.h"
#include "materials/material_type.h"
#include "shapes/shape_shared.h"
#include "shapes/shape_type.h"

namespace spectrace {
namespace {

// The record's kind; the rest is the kind's unit's (its pack).
device::Material deviceMaterial(const SurfaceMaterial& material, DeviceScene& device) {
  device::Material record{};
  record.type = uint32_t(material.type);
  materialTypeUnit(material.type).pack(material, record, device.data);
  return record;
}

// Every primitive in leaves under nodes whose boxes all bound them all:
// the kernel then tests each one (the bench's brute force).
WideBvh flatTree(const std::vector<PrimitiveBounds>& bounds, std::vector<uint32_t>& order) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (uint32_t i = 0; i < bounds.size(); ++i) {
    lo = glm::min(lo, bounds[i].lo);
    hi = glm::max(hi, bounds[i].hi);
    order.push_back(i);
  }
  const PrimitiveBounds all = paddedBounds(lo, hi);
  return flatBvh(glm::vec3(all.lo) - glm::vec3(1e-6f), glm::vec3(all.hi) + glm::vec3(1e-6f), uint32_t(bounds.size()));
}

}  // namespace

void compileObjects(const Scene& scene, const CompileOptions& options, DeviceScene& device,
                    const std::vector<uint32_t>& emitterOf) {
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
    const size_t first = placed.size();
    shapeTypeUnit(object.shape.type).place(object.shape, frame, uint32_t(i), placed);
    const uint32_t emitter = i < emitterOf.size() ? emitterOf[i] : 0u;
    for (size_t p = first; p < placed.size(); ++p) placed[p].primitive.emitter = emitter;
  }
  std::vector<PrimitiveBounds> bounds;
  bounds.reserve(placed.size());
  for (const PlacedPrimitive& p : placed) bounds.push_back(p.bounds);
  std::vector<uint32_t> order;
  if (options.bruteForceObjects) {
    device.bvhNodes = flatTree(bounds, order).nodes;
  } else {
    BuiltBvh binary = buildBvh(bounds);
    device.bvhNodes = widenBvh(binary).nodes;
    order = std::move(binary.order);
    c.bvhRootLeaf = rootLeafCount(device.bvhNodes);
  }
  device.primitives.reserve(placed.size());
  for (uint32_t index : order) device.primitives.push_back(placed[index].primitive);
  c.objectPrimitives = uint32_t(device.primitives.size());
  c.connect = options.connect && connects ? 1u : 0u;
}

}  // namespace spectrace
