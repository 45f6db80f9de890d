#pragma once
// The scene's objects for the kernel (shaders/objects.h, transport.h):
// shapes become primitives in the camera frame, each object's material a
// Material with its reflectance table, and a BVH over the primitives, all
// worked out in double and rounded once.
#include <vector>

#include "compile/compile_scene.h"
#include "scene/scene.h"

namespace spectrace {

// Fills device.primitives (in the BVH's order), bvhNodes, materials and
// reflectance, and the object constants (objectPrimitives, maxBounces,
// connect). options.connect: camera connections at diffuse
// vertices (kept only when some object is diffuse); options.bruteForceObjects:
// one leaf instead of the BVH.
void compileObjects(const Scene& scene, const CompileOptions& options, DeviceScene& device);

// The reflectance table the kernel interpolates (Material's fields): nodes
// on a uniform grid over the given nodes, fine enough that the grid holds
// every node when the nodes are evenly spaced (tabulated data usually is).
struct ReflectanceTable {
  float lambda0 = 0.0f;
  float nodesPerNm = 0.0f;
  std::vector<float> values;
};
ReflectanceTable reflectanceTable(const SurfaceMaterial& material);

}  // namespace spectrace
