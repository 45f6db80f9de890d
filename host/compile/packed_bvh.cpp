#include "compile/packed_bvh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <fmt/format.h>
#include <glm/glm.hpp>

#include "compile/wide_bvh.h"
#include "kernel_lang.h"

namespace spectrace {
namespace device {
using glm::ivec4;
using glm::uintBitsToFloat;
#include "packed_bvh_node.h"
}  // namespace device

namespace {

constexpr int kMinExponent = -126;  // 2^-126: the least normal float
// A step count's magnitude bound: base + 255 converts to float exactly.
constexpr double kMaxBase = double(1 << 24) - 256.0;
// (kMaxBase + 255) * 2^103 < 2^127: no product overflows.
constexpr int kMaxExponent = 103;

struct AxisGrid {
  int exponent;
  double base;  // an integer
};

// The finest grid on which [lo, hi] spans at most 255 steps from an integer
// base of magnitude at most kMaxBase.
AxisGrid axisGrid(float lo, float hi, size_t node) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi)
    throw std::invalid_argument(
        fmt::format("packBvhNodes: node {} has children spanning [{}, {}], not a finite interval", node, lo, hi));
  const double span = double(hi) - double(lo);
  int e = kMinExponent;
  if (span > 0) e = std::max(e, int(std::floor(std::log2(span / 255.0))));
  for (; e <= kMaxExponent; ++e) {
    const double scale = std::ldexp(1.0, e);
    const double base = std::floor(double(lo) / scale);
    const double top = std::ceil(double(hi) / scale);
    if (top - base <= 255.0 && std::abs(base) <= kMaxBase) return {e, base};
  }
  throw std::invalid_argument(fmt::format("packBvhNodes: node {} spans [{}, {}], beyond the packed grid", node, lo, hi));
}

// Child coordinates on the grid: steps above the base, rounded outwards.
uint32_t gridBytes(const glm::vec4& values, const AxisGrid& grid, bool up, const device::BvhNode& node, size_t index) {
  uint32_t bytes = 0;
  for (int k = 0; k < 4; ++k) {
    if (isEmptySlot(node, k)) continue;
    const double scaled = std::ldexp(double(values[k]), -grid.exponent);
    const double steps = (up ? std::ceil(scaled) : std::floor(scaled)) - grid.base;
    // Off the grid: a plane that is NaN (nodeBounds passes over it) or
    // outside the node's bounds.
    if (!(steps >= 0.0 && steps <= 255.0))
      throw std::invalid_argument(fmt::format("packBvhNodes: node {} slot {} has a plane at {}, off its grid", index, k,
                                              values[k]));
    bytes |= uint32_t(steps) << (8 * k);
  }
  return bytes;
}

}  // namespace

std::vector<device::PackedBvhNode> packBvhNodes(std::span<const device::BvhNode> nodes) {
  std::vector<device::PackedBvhNode> packed(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    const device::BvhNode& node = nodes[i];
    device::PackedBvhNode& out = packed[i];
    const glm::vec4* mins[3] = {&node.minX, &node.minY, &node.minZ};
    const glm::vec4* maxs[3] = {&node.maxX, &node.maxY, &node.maxZ};
    glm::vec3 lo, hi;
    nodeBounds(node, lo, hi);
    if (lo.x > hi.x) lo = hi = glm::vec3(0.0f);  // no children (a scene without objects)
    uint32_t exponents = 0;
    uint32_t boxes[6] = {};
    for (int axis = 0; axis < 3; ++axis) {
      const AxisGrid grid = axisGrid(lo[axis], hi[axis], i);
      out.grid[axis] = uint32_t(int32_t(grid.base));
      exponents |= uint32_t(grid.exponent + 127) << (8 * axis);
      boxes[2 * axis] = gridBytes(*mins[axis], grid, false, node, i);
      boxes[2 * axis + 1] = gridBytes(*maxs[axis], grid, true, node, i);
    }
    out.grid.w = exponents;
    out.boxesXY = glm::uvec4(boxes[0], boxes[1], boxes[2], boxes[3]);
    out.boxesZ = glm::uvec4(boxes[4], boxes[5], 0u, 0u);
    out.entries = (node.child << device::kBvhCountBits) | node.count;
  }
  return packed;
}

device::BvhNode unpackedBvhNode(const device::PackedBvhNode& packed) { return device::unpackBvhNode(packed); }

}  // namespace spectrace
