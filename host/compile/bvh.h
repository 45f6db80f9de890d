#pragma once
// The binary BVH over the scene's primitives, built on the host in double
// (binned SAH, pbrt-v4 style) and flattened depth first, the root at 0,
// float bounds rounded outwards so that each node contains what it holds.
// The kernel walks the four-wide tree made from it (compile/wide_bvh.h).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "device_shared.h"
#include "shapes/shape_type.h"

namespace spectrace {

// A binary node (pbrt-v4's LinearBVHNode): an interior node's first child
// follows it; `next` is its second child. A leaf's primitives are
// order[next .. next + count).
struct BinaryBvhNode {
  glm::vec3 boundsMin;
  uint32_t next;
  glm::vec3 boundsMax;
  uint32_t countAxis;  // bits 0-15: primitive count (0: interior), bits 16-17: split axis
  uint32_t primitiveCount() const { return countAxis & 0xFFFFu; }
};

struct BuiltBvh {
  std::vector<BinaryBvhNode> nodes;  // empty for no primitives
  // order[k]: the input index of the k-th primitive; a leaf holds
  // order[next .. next + count).
  std::vector<uint32_t> order;
  // Nodes on the longest root-to-leaf path (a lone leaf: 1, no nodes: 0);
  // never more than device::kBvhMaxDepth, so the kernel's traversal stack
  // cannot overflow.
  uint32_t depth = 0;
};

// Throws std::invalid_argument for device::kBvhMaxIndex (2^28) primitives
// or more: the kernel's stack packs primitive and wide node indices below
// it (shaders/objects.h).
void checkBvhPrimitiveCount(size_t count);

// Builds the BVH. Leaves hold at most device::kBvhMaxLeafPrimitives; where
// SAH splits would make the tree too deep, median splits take over. Throws
// std::invalid_argument for bounds that are not finite or have lo > hi, or
// as checkBvhPrimitiveCount does. Large trees are built on up to `threads`
// threads (0: one per hardware thread); the tree does not depend on them.
BuiltBvh buildBvh(std::span<const PrimitiveBounds> bounds, unsigned threads = 0);

}  // namespace spectrace
