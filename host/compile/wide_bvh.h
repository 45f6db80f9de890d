#pragma once
// The four-wide BVH the kernel walks (device::BvhNode, shaders/objects.h),
// made from the binary SAH tree (compile/bvh.h) by collapsing it: each wide
// node takes a binary node's two children and opens the interior child of
// largest area until it has four. A wide node then holds the boxes the
// binary tree would have tested one at a time, and its children are only
// read when the ray meets their boxes. The leaves and their float bounds
// are the binary tree's own, so the wide tree contains what it holds.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "compile/bvh.h"
#include "device_shared.h"

namespace spectrace {

struct WideBvh {
  std::vector<device::BvhNode> nodes;  // depth first, the root at 0; empty for no primitives
  // Wide nodes on the longest path from the root (0 for no nodes); never
  // more than the binary tree's depth, so within device::kBvhMaxDepth and
  // the kernel's stack (device::kBvhStackSize = 3 kBvhMaxDepth + 1).
  uint32_t depth = 0;
};

// The wide tree over `binary`, whose leaves index its primitives in
// binary.order's order.
WideBvh widenBvh(const BuiltBvh& binary);

// Primitives [0, count) in leaves of device::kBvhMaxLeafPrimitives under
// nodes whose every box is [lo, hi]: a walk tests every primitive, in
// order (the bench's brute force). Throws as checkBvhPrimitiveCount does.
WideBvh flatBvh(const glm::vec3& lo, const glm::vec3& hi, uint32_t count);

// Whether slot k of a node holds nothing (device::BvhNode: count and child
// both 0, the root being nobody's child).
inline bool isEmptySlot(const device::BvhNode& node, int k) { return node.count[k] == 0 && node.child[k] == 0; }

// The primitives of the root's only child when that child is a leaf (a
// scene of a few primitives), else 0. A walk may start at that leaf, as if
// the root's box test had passed: the hit is the same, since a box is met
// by every ray that meets what it holds (its test is widened for rounding)
// and the leaf's tests reject what the box would have. It saves each ray a
// pass of the walk's loop, which on lavapipe runs both the node's and the
// leaf's code.
uint32_t rootLeafCount(const std::vector<device::BvhNode>& nodes);

// The union of a node's child boxes (the root's: the tree's bounds); lo
// above hi for a node without children. NaN planes are passed over.
void nodeBounds(const device::BvhNode& node, glm::vec3& lo, glm::vec3& hi);

}  // namespace spectrace
