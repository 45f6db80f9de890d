#pragma once
// The CPU instance's own step of the shared kernel's BVH walk
// (shaders/objects.h: intersectObjects, at a node): the ray against the
// node's four child boxes on one vector register, then the children met
// pushed far to near by a short insertion among those met. The shader's
// step, compiled as C++, is scalar (GCC does not vectorise its vec4 lanes)
// and runs the fixed sorting network that keeps a GPU's lanes together, so
// a CPU thread paid for both; this step traces the ray ceiling's incoherent
// rays about 1.4x as fast (docs/benchmarks.md).
//
// Exact, not an approximation: the box test does the shader's float
// operations in the shader's order, min and max picking as glm's do
// (glm::min(x, y) is y < x ? y : x), so entry and exit distances are the
// same bits; and the walk's closest hit does not depend on the order in
// which children are visited (of equal distances the lowest primitive
// wins), so only equal keys may be pushed in another order. wide_walk_test
// checks both against the shader's step.
#include <cstdint>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "device_shared.h"

namespace spectrace::device {

// Four float lanes in one register (SSE on x86-64; any target's vectors).
typedef float FloatLanes __attribute__((vector_size(16)));
typedef int32_t MaskLanes __attribute__((vector_size(16)));

inline FloatLanes lanesOf(const glm::vec4& v) {
  FloatLanes lanes;
  __builtin_memcpy(&lanes, &v, sizeof lanes);
  return lanes;
}
inline FloatLanes broadcast(float x) { return FloatLanes{x, x, x, x}; }
// A lane of `ifTrue` where `mask` is set, else of `ifFalse` (a blend; GCC
// and Clang both take it, where a vector ?: is GCC's alone).
inline FloatLanes select(MaskLanes mask, FloatLanes ifTrue, FloatLanes ifFalse) {
  return FloatLanes((mask & MaskLanes(ifTrue)) | (~mask & MaskLanes(ifFalse)));
}
// glm::min(x, y) and glm::max(x, y), lane by lane, with their choice on
// ties and NaN.
inline FloatLanes lanesMin(FloatLanes x, FloatLanes y) { return select(y < x, y, x); }
inline FloatLanes lanesMax(FloatLanes x, FloatLanes y) { return select(x < y, y, x); }

// objects.h's rayMeetsChildren on lanes: child k is met before tMax when
// enter[k] <= leave[k].
inline void rayMeetsChildrenLanes(const glm::vec3& origin, const glm::vec3& inverse, const BvhNode& node, float tMax,
                                  FloatLanes& enter, FloatLanes& leave) {
  const FloatLanes ox = broadcast(origin.x), oy = broadcast(origin.y), oz = broadcast(origin.z);
  const FloatLanes x0 = (lanesOf(node.minX) - ox) * inverse.x;
  const FloatLanes x1 = (lanesOf(node.maxX) - ox) * inverse.x;
  const FloatLanes y0 = (lanesOf(node.minY) - oy) * inverse.y;
  const FloatLanes y1 = (lanesOf(node.maxY) - oy) * inverse.y;
  const FloatLanes z0 = (lanesOf(node.minZ) - oz) * inverse.z;
  const FloatLanes z1 = (lanesOf(node.maxZ) - oz) * inverse.z;
  enter = lanesMax(lanesMax(lanesMin(x0, x1), lanesMin(y0, y1)), lanesMax(lanesMin(z0, z1), broadcast(0.0f)));
  leave = lanesMin(lanesMin(lanesMax(x0, x1), lanesMax(y0, y1)), lanesMin(lanesMax(z0, z1), broadcast(tMax))) *
          1.0000004f;
}

// The walk's step at `node`: its children that the ray meets before tMax
// (empty slots never) onto the stack (objects.h's entries: child <<
// kBvhCountBits | count, and the entry distance), far to near, so the
// nearest is on top; `prefetch(child, count)` for each, as it is known.
template <typename Prefetch>
inline void pushChildrenMet(const glm::vec3& origin, const glm::vec3& inverse, const BvhNode& node, float tMax,
                            uint32_t* stackEntry, float* stackEnter, uint32_t& depth, Prefetch prefetch) {
  FloatLanes enter, leave;
  rayMeetsChildrenLanes(origin, inverse, node, tMax, enter, leave);
  const MaskLanes met = enter <= leave;
  float key[4];
  uint32_t entry[4];
  int n = 0;
  for (int k = 0; k < 4; ++k) {
    if (!met[k] || (node.count[k] == 0u && node.child[k] == 0u)) continue;
    prefetch(node.child[k], node.count[k]);
    // Insertion: farthest first.
    const float keyK = enter[k];
    int j = n++;
    for (; j > 0 && key[j - 1] < keyK; --j) {
      key[j] = key[j - 1];
      entry[j] = entry[j - 1];
    }
    key[j] = keyK;
    entry[j] = (node.child[k] << kBvhCountBits) | node.count[k];
  }
  for (int j = 0; j < n; ++j) {
    stackEntry[depth] = entry[j];
    stackEnter[depth] = key[j];
    ++depth;
  }
}

}  // namespace spectrace::device
