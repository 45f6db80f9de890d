// The Vulkan trace's packed BVH nodes: every unpacked box holds the float
// box it packs, on the finest grid the packing allows, with the children
// unchanged; and the kernel's walk over the unpacked nodes (the shader's
// text, compiled here) finds the same hits, bit for bit, as over the full
// nodes and as brute force, near the origin, far from it and at tiny
// scales.
#include "compile/packed_bvh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "compile/bvh_walk_testing.h"

namespace spectrace {
namespace {

using namespace bvh_testing;

const glm::vec4& component(const device::BvhNode& n, int axis, bool max) {
  const glm::vec4* mins[3] = {&n.minX, &n.minY, &n.minZ};
  const glm::vec4* maxs[3] = {&n.maxX, &n.maxY, &n.maxZ};
  return max ? *maxs[axis] : *mins[axis];
}

// Whether [lo, hi] fits a grid of step 2^e: at most 255 steps from an
// integer base of magnitude at most 2^24 - 256 (packed_bvh.h).
bool fitsGrid(float lo, float hi, int e) {
  const double scale = std::ldexp(1.0, e);
  const double base = std::floor(double(lo) / scale);
  return std::ceil(double(hi) / scale) - base <= 255.0 && std::abs(base) <= double(1 << 24) - 256.0;
}

// Every node's unpacked boxes against its own: containing, within a grid
// step, on the finest grid that fits, children and counts unchanged.
void checkPacking(const std::vector<device::BvhNode>& nodes) {
  const std::vector<device::PackedBvhNode> packed = packBvhNodes(nodes);
  ASSERT_EQ(packed.size(), nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    const device::BvhNode& node = nodes[i];
    const device::BvhNode unpacked = unpackedBvhNode(packed[i]);
    ASSERT_EQ(unpacked.child, node.child) << "node " << i;
    ASSERT_EQ(unpacked.count, node.count) << "node " << i;
    for (int axis = 0; axis < 3; ++axis) {
      const int e = int((packed[i].grid.w >> (8 * axis)) & 255u) - 127;
      const double step = std::ldexp(1.0, e);
      float lo = std::numeric_limits<float>::max(), hi = -lo;
      for (int k = 0; k < 4; ++k) {
        if (isEmptySlot(node, k)) continue;
        const float min = component(node, axis, false)[k], max = component(node, axis, true)[k];
        const float uMin = component(unpacked, axis, false)[k], uMax = component(unpacked, axis, true)[k];
        lo = std::min(lo, min);
        hi = std::max(hi, max);
        ASSERT_TRUE(std::isfinite(uMin) && std::isfinite(uMax)) << "node " << i << " axis " << axis;
        // Holding: a box test meets every ray the float box's test meets.
        ASSERT_LE(uMin, min) << "node " << i << " slot " << k << " axis " << axis;
        ASSERT_GE(uMax, max) << "node " << i << " slot " << k << " axis " << axis;
        // Within one step: rounded outwards to the next grid line, no further.
        ASSERT_LT(double(min) - double(uMin), step) << "node " << i << " slot " << k << " axis " << axis;
        ASSERT_LT(double(uMax) - double(max), step) << "node " << i << " slot " << k << " axis " << axis;
        // No coordinate a device may flush to zero.
        ASSERT_TRUE(uMin == 0.0f || std::abs(uMin) >= std::numeric_limits<float>::min());
        ASSERT_TRUE(uMax == 0.0f || std::abs(uMax) >= std::numeric_limits<float>::min());
      }
      if (lo > hi) continue;  // no children
      ASSERT_TRUE(fitsGrid(lo, hi, e)) << "node " << i << " axis " << axis;
      // The finest such grid (or the least normal step).
      ASSERT_TRUE(e == -126 || !fitsGrid(lo, hi, e - 1)) << "node " << i << " axis " << axis << " e " << e;
    }
  }
}

// Rays through a soup's tree: the closest hit over the unpacked nodes by
// the shader's steps (what lavapipe runs) and by the CPU's vector step
// equals the full nodes' and brute force's, bit for bit; any-hit agrees.
void checkWalks(const Soup& soup, const vec3& centre, float size, uint64_t seed, int minimumHits = 300) {
  const Tree t = treeOf(soup);
  std::vector<device::BvhNode> unpacked;
  for (const device::PackedBvhNode& p : packBvhNodes(t.wide.nodes)) unpacked.push_back(unpackedBvhNode(p));
  Walker full(t.primitives, t.wide.nodes, true);
  Walker shaderSteps(t.primitives, unpacked, true);
  Walker vectorStep(t.primitives, unpacked, false);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  int hits = 0;
  for (int r = 0; r < 3000; ++r) {
    const vec3 origin = centre + size * vec3(unit(rng), unit(rng), unit(rng));
    // Half the rays aim at a vertex, on the faces of the boxes that hold it,
    // where a box too small would lose the hit.
    const device::Primitive& aim = t.primitives[rng() % t.primitives.size()];
    const vec3 direction = r % 2 == 0 ? unitVector(rng) : glm::normalize(aim.a + aim.b - origin);
    const float tMax = r % 4 == 0 ? 0.5f * size : 1e30f;
    const KernelHit expected = full.bruteForce(t.primitives, origin, direction, tMax);
    ASSERT_EQ(full.closest(origin, direction, tMax), expected) << "ray " << r;
    ASSERT_EQ(shaderSteps.closest(origin, direction, tMax), expected) << "ray " << r;
    ASSERT_EQ(vectorStep.closest(origin, direction, tMax), expected) << "ray " << r;
    ASSERT_EQ(shaderSteps.closest(origin, direction, tMax, true).found, expected.found) << "ray " << r;
    hits += expected.found ? 1 : 0;
  }
  EXPECT_GT(hits, minimumHits) << "the test must hit often";
}

// `soup` moved by `offset` and scaled by `scale` (in float, as a mesh's
// placed vertices are).
Soup placed(const Soup& soup, const vec3& offset, float scale) {
  Soup out;
  for (const device::Primitive& p : soup.primitives)
    out.add(offset + scale * p.a, offset + scale * (p.a + p.b), offset + scale * (p.a + p.c));
  return out;
}

TEST(PackedBvh, RandomTrianglesPackIntoBoxesThatHoldThem) {
  checkPacking(treeOf(randomSoup(3000, 21)).wide.nodes);
  checkPacking(treeOf(heightField(40)).wide.nodes);
}

TEST(PackedBvh, FarFromTheOriginAndAtTinyScalesToo) {
  const Soup soup = randomSoup(2000, 22);
  // Far away, the grid is as coarse as the floats there: the base limit,
  // not the span, sets the step.
  checkPacking(treeOf(placed(soup, vec3(4096.3f, -70000.0f, 1.5e6f), 1.0f)).wide.nodes);
  checkPacking(treeOf(placed(soup, vec3(-3.0f, 2.0f, 1.0f), 1e-6f)).wide.nodes);
  // Below the least normal step: boxes of 1e-36 m get steps of 2^-126.
  checkPacking(treeOf(placed(soup, vec3(0.0f), 1e-36f)).wide.nodes);
  checkPacking(treeOf(placed(soup, vec3(-1e9f, 1e9f, 3e10f), 1e7f)).wide.nodes);
}

TEST(PackedBvh, AFlatMeshHasZeroSpanOnOneAxis) {
  Soup flat;
  for (int i = 0; i < 50; ++i)
    for (int j = 0; j < 50; ++j) {
      const vec3 a(0.01f * i, 0.01f * j, 0.25f);
      flat.add(a, a + vec3(0.01f, 0.0f, 0.0f), a + vec3(0.0f, 0.01f, 0.0f));
    }
  const Tree t = treeOf(flat);
  checkPacking(t.wide.nodes);
  checkWalks(flat, vec3(0.25f, 0.25f, 0.25f), 0.3f, 23, 150);
}

TEST(PackedBvh, TheWalkOverUnpackedNodesFindsTheSameHits) {
  const Soup soup = randomSoup(3000, 24);
  checkWalks(soup, vec3(0.5f), 1.0f, 25);
  checkWalks(placed(soup, vec3(4096.3f, -70000.0f, 1.5e6f), 1.0f), vec3(4096.8f, -69999.5f, 1.5e6f), 1.0f, 26);
  checkWalks(placed(soup, vec3(-3.0f, 2.0f, 1.0f), 1e-3f), vec3(-3.0f, 2.0f, 1.0f) + vec3(5e-4f), 1e-3f, 27);
  // Shared edges and vertices: ties resolve as over the full nodes.
  checkWalks(heightField(40), vec3(0.5f, 0.5f, 0.0f), 0.6f, 28);
}

TEST(PackedBvh, EmptySlotsAndAnEmptyTreePack) {
  // One primitive: the root's one leaf, three empty slots.
  Soup one;
  one.add(vec3(0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f));
  checkPacking(treeOf(one).wide.nodes);
  // A scene without objects keeps one zero node.
  checkPacking(std::vector<device::BvhNode>(1));
}

TEST(PackedBvh, ABoxThatIsNotFiniteIsRefused) {
  std::vector<device::BvhNode> nodes = treeOf(randomSoup(10, 29)).wide.nodes;
  nodes[0].maxY[0] = std::numeric_limits<float>::infinity();
  EXPECT_THROW(packBvhNodes(nodes), std::invalid_argument);
  nodes[0].maxY[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(packBvhNodes(nodes), std::invalid_argument);
  // Finite but beyond the grid: a span of 2^127.
  nodes[0].minY[0] = -1.7e38f;
  nodes[0].maxY[0] = 1.7e38f;
  EXPECT_THROW(packBvhNodes(nodes), std::invalid_argument);
}

}  // namespace
}  // namespace spectrace
