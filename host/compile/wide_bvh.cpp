#include "compile/wide_bvh.h"

#include <algorithm>
#include <array>
#include <limits>

#include <glm/common.hpp>

namespace spectrace {
namespace {

constexpr uint32_t kWidth = 4;

// Half the surface area, in double so that thin boxes still compare.
double halfArea(const BinaryBvhNode& n) {
  const glm::dvec3 e = glm::max(glm::dvec3(n.boundsMax) - glm::dvec3(n.boundsMin), glm::dvec3(0.0));
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

void setSlot(device::BvhNode& node, uint32_t k, const glm::vec3& lo, const glm::vec3& hi, uint32_t child,
             uint32_t count) {
  node.minX[k] = lo.x;
  node.minY[k] = lo.y;
  node.minZ[k] = lo.z;
  node.maxX[k] = hi.x;
  node.maxY[k] = hi.y;
  node.maxZ[k] = hi.z;
  node.child[k] = child;
  node.count[k] = count;
}

class Widener {
 public:
  Widener(const BuiltBvh& binary, WideBvh& out) : binary_(binary), out_(out) {}

  // Appends the wide node whose children are those of binary node `index`
  // (or, for a leaf root, that leaf), then its interior children depth
  // first; returns its index.
  uint32_t emit(uint32_t index, uint32_t level) {
    const uint32_t wideIndex = uint32_t(out_.nodes.size());
    out_.nodes.push_back(device::BvhNode{});
    out_.depth = std::max(out_.depth, level);
    std::array<uint32_t, kWidth> slots{};
    uint32_t n = 0;
    const BinaryBvhNode& node = binary_.nodes[index];
    if (node.primitiveCount() > 0) {
      slots[n++] = index;
    } else {
      slots[n++] = index + 1;
      slots[n++] = node.next;
    }
    // Open the largest interior child (by area, the likeliest to be met)
    // until the node is full; the first of equals, so the tree is the same
    // on every machine.
    while (n < kWidth) {
      int widest = -1;
      double widestArea = -1.0;
      for (uint32_t k = 0; k < n; ++k) {
        const BinaryBvhNode& c = binary_.nodes[slots[k]];
        if (c.primitiveCount() == 0 && halfArea(c) > widestArea) {
          widest = int(k);
          widestArea = halfArea(c);
        }
      }
      if (widest < 0) break;
      const uint32_t opened = slots[widest];
      slots[widest] = opened + 1;
      slots[n++] = binary_.nodes[opened].next;
    }
    for (uint32_t k = 0; k < n; ++k) {
      const BinaryBvhNode& c = binary_.nodes[slots[k]];
      const uint32_t count = c.primitiveCount();
      // Interior children are filled in below, once their index is known.
      setSlot(out_.nodes[wideIndex], k, c.boundsMin, c.boundsMax, count > 0 ? c.next : 0u, count);
    }
    for (uint32_t k = 0; k < n; ++k)
      if (binary_.nodes[slots[k]].primitiveCount() == 0) {
        const uint32_t child = emit(slots[k], level + 1);
        out_.nodes[wideIndex].child[k] = child;
      }
    return wideIndex;
  }

 private:
  const BuiltBvh& binary_;
  WideBvh& out_;
};

}  // namespace

WideBvh widenBvh(const BuiltBvh& binary) {
  WideBvh out;
  if (binary.nodes.empty()) return out;
  out.nodes.reserve(binary.nodes.size() / 3 + 1);
  Widener(binary, out).emit(0, 1);
  return out;
}

WideBvh flatBvh(const glm::vec3& lo, const glm::vec3& hi, uint32_t count) {
  checkBvhPrimitiveCount(count);
  WideBvh out;
  // Levels of nodes: each holds four subtrees of `capacity` primitives.
  uint64_t capacity = device::kBvhMaxLeafPrimitives;
  uint32_t levels = 1;
  for (; capacity * kWidth < count; capacity *= kWidth) ++levels;
  out.depth = levels;
  // Depth first, as widenBvh lays out its nodes.
  const auto emit = [&](auto& self, uint32_t first, uint32_t n, uint64_t slotCapacity) -> uint32_t {
    const uint32_t index = uint32_t(out.nodes.size());
    out.nodes.push_back(device::BvhNode{});
    for (uint32_t k = 0; k < kWidth && n > 0; ++k) {
      const uint32_t part = uint32_t(std::min<uint64_t>(n, slotCapacity));
      if (slotCapacity == device::kBvhMaxLeafPrimitives) {
        setSlot(out.nodes[index], k, lo, hi, first, part);
      } else {
        const uint32_t child = self(self, first, part, slotCapacity / kWidth);
        setSlot(out.nodes[index], k, lo, hi, child, 0u);
      }
      first += part;
      n -= part;
    }
    return index;
  };
  emit(emit, 0u, count, capacity);
  return out;
}

void nodeBounds(const device::BvhNode& node, glm::vec3& lo, glm::vec3& hi) {
  lo = glm::vec3(std::numeric_limits<float>::infinity());
  hi = -lo;
  for (int k = 0; k < int(kWidth); ++k) {
    if (isEmptySlot(node, k)) continue;
    lo = glm::min(lo, glm::vec3(node.minX[k], node.minY[k], node.minZ[k]));
    hi = glm::max(hi, glm::vec3(node.maxX[k], node.maxY[k], node.maxZ[k]));
  }
}

uint32_t rootLeafCount(const std::vector<device::BvhNode>& nodes) {
  if (nodes.empty()) return 0;
  const device::BvhNode& root = nodes[0];
  int used = 0;
  uint32_t leaf = 0;
  for (int k = 0; k < 4; ++k) {
    if (isEmptySlot(root, k)) continue;
    ++used;
    if (root.count[k] > 0 && root.child[k] == 0) leaf = root.count[k];
  }
  return used == 1 ? leaf : 0;
}

}  // namespace spectrace
