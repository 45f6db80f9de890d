// The four-wide BVH: its layout (every node reached once, leaves covering
// the primitives once, boxes that contain what they hold, depth within the
// kernel's stack) and the kernel's walk of it against brute force: the same
// closest primitive at the same distance, ties at shared edges and vertices
// included, and the same answer to any-hit queries.
#include "compile/wide_bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "compile/bvh.h"
#include "compile/bvh_walk_testing.h"
#include "kernel/beam_kernel.h"
#include "shapes/shape_shared.h"

namespace spectrace {
namespace {

using glm::dvec3;
using glm::vec3;
using namespace bvh_testing;

vec3 slotLo(const device::BvhNode& n, int k) { return {n.minX[k], n.minY[k], n.minZ[k]}; }
vec3 slotHi(const device::BvhNode& n, int k) { return {n.maxX[k], n.maxY[k], n.maxZ[k]}; }
bool contains(const dvec3& outerLo, const dvec3& outerHi, const dvec3& lo, const dvec3& hi) {
  return outerLo.x <= lo.x && outerLo.y <= lo.y && outerLo.z <= lo.z && outerHi.x >= hi.x && outerHi.y >= hi.y &&
         outerHi.z >= hi.z;
}

// Walks the wide tree and checks what the kernel relies on.
void checkLayout(const Tree& t) {
  const auto& nodes = t.wide.nodes;
  const size_t n = t.primitives.size();
  ASSERT_FALSE(nodes.empty());
  std::vector<int> nodeSeen(nodes.size(), 0), primitiveSeen(n, 0);
  struct Entry {
    uint32_t node, level;
    dvec3 lo, hi;  // the parent's slot box (the root: everything)
  };
  std::vector<Entry> stack{{0, 1, dvec3(-INFINITY), dvec3(INFINITY)}};
  uint32_t depth = 0;
  while (!stack.empty()) {
    const Entry e = stack.back();
    stack.pop_back();
    ASSERT_LT(e.node, nodes.size());
    ASSERT_EQ(nodeSeen[e.node]++, 0) << "node " << e.node << " reached twice";
    depth = std::max(depth, e.level);
    const device::BvhNode& node = nodes[e.node];
    int used = 0;
    for (int k = 0; k < 4; ++k) {
      if (isEmptySlot(node, k)) continue;
      ++used;
      const dvec3 lo(slotLo(node, k)), hi(slotHi(node, k));
      EXPECT_TRUE(contains(e.lo, e.hi, lo, hi)) << "node " << e.node << " slot " << k << " leaves its parent's box";
      if (node.count[k] == 0) {
        ASSERT_GT(node.child[k], e.node) << "children follow their parent";
        stack.push_back({node.child[k], e.level + 1, lo, hi});
        continue;
      }
      EXPECT_LE(node.count[k], device::kBvhMaxLeafPrimitives);
      ASSERT_LE(size_t(node.child[k]) + node.count[k], n);
      for (uint32_t p = node.child[k]; p < node.child[k] + node.count[k]; ++p) {
        ++primitiveSeen[p];
        EXPECT_TRUE(contains(lo, hi, t.bounds[p].lo, t.bounds[p].hi)) << "leaf does not contain primitive " << p;
      }
    }
    EXPECT_GE(used, e.node == 0 ? 1 : 2) << "node " << e.node;
  }
  EXPECT_TRUE(std::all_of(nodeSeen.begin(), nodeSeen.end(), [](int s) { return s == 1; })) << "unreachable nodes";
  EXPECT_TRUE(std::all_of(primitiveSeen.begin(), primitiveSeen.end(), [](int s) { return s == 1; }))
      << "leaves do not cover the primitives once";
  EXPECT_EQ(t.wide.depth, depth);
  EXPECT_LE(t.wide.depth, t.binary.depth) << "collapsing never deepens the tree";
  // Each level below the root leaves at most three siblings on the stack.
  EXPECT_LE(3 * t.wide.depth + 1, device::kBvhStackSize);
}

TEST(WideBvh, EmptyBinaryTreeGivesNoNodes) {
  const WideBvh wide = widenBvh(BuiltBvh{});
  EXPECT_TRUE(wide.nodes.empty());
  EXPECT_EQ(wide.depth, 0u);
}

TEST(WideBvh, OnePrimitiveIsOneLeafUnderTheRoot) {
  Soup soup;
  soup.add({0, 0, 1}, {1, 0, 1}, {0, 1, 1});
  const Tree t = treeOf(soup);
  ASSERT_EQ(t.wide.nodes.size(), 1u);
  EXPECT_EQ(t.wide.nodes[0].count[0], 1u);
  for (int k = 1; k < 4; ++k) EXPECT_TRUE(isEmptySlot(t.wide.nodes[0], k));
  checkLayout(t);
  Walker walker(t.primitives, t.wide.nodes);
  const KernelHit h = walker.closest({0.25f, 0.25f, 0.0f}, {0, 0, 1}, 1e30f);
  EXPECT_TRUE(h.found);
  EXPECT_EQ(h.t, 1.0f);
}

TEST(WideBvh, LayoutOfRandomTrianglesAndAHeightField) {
  for (size_t n : {2u, 5u, 17u, 100u, 5000u}) {
    SCOPED_TRACE(n);
    checkLayout(treeOf(randomSoup(n, 7 + n)));
  }
  checkLayout(treeOf(heightField(64)));
}

// Most interior nodes are full: the collapse opens children until four.
TEST(WideBvh, NodesAreMostlyFull) {
  const Tree t = treeOf(randomSoup(20000, 3));
  size_t slots = 0;
  for (const auto& node : t.wide.nodes)
    for (int k = 0; k < 4; ++k) slots += isEmptySlot(node, k) ? 0 : 1;
  const double perNode = double(slots) / double(t.wide.nodes.size());
  std::printf("  %zu binary nodes, %zu wide nodes, %.2f slots a wide node\n", t.binary.nodes.size(),
              t.wide.nodes.size(), perNode);
  EXPECT_GT(perNode, 3.0) << "a node whose children are two leaves has two slots; most have four";
}

// Rays through random triangles of many sizes, from inside and outside the
// cube: the walk finds what brute force finds, bit for bit.
TEST(WideBvh, ClosestHitsOfRandomTrianglesEqualBruteForce) {
  const Soup soup = randomSoup(3000, 11);
  const Tree t = treeOf(soup);
  for (const bool portable : {false, true}) {
    SCOPED_TRACE(portable ? "the shader's steps" : "the CPU's vector step");
    Walker walker(t.primitives, t.wide.nodes, portable);
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<float> unit(-0.5f, 1.5f);
    int hits = 0;
    for (int r = 0; r < 5000; ++r) {
      const vec3 origin(unit(rng), unit(rng), unit(rng));
      const vec3 direction = unitVector(rng);
      const float tMax = r % 4 == 0 ? 0.3f : 1e30f;
      const KernelHit expected = walker.bruteForce(t.primitives, origin, direction, tMax);
      ASSERT_EQ(walker.closest(origin, direction, tMax), expected) << "ray " << r;
      // Any-hit: found exactly when brute force finds a hit before tMax.
      ASSERT_EQ(walker.closest(origin, direction, tMax, true).found, expected.found) << "ray " << r;
      hits += expected.found ? 1 : 0;
    }
    EXPECT_GT(hits, 500) << "the test must hit often";
  }
}

// A few triangles make one leaf under the root, and a walk that starts at
// it finds what the whole walk finds: for rays that meet the root's box and
// rays that miss it, closest and any hit, on both kinds of step.
TEST(WideBvh, AWalkFromTheRootsOnlyLeafFindsTheSameHits) {
  Soup bigger = randomSoup(40, 14);
  EXPECT_EQ(rootLeafCount(treeOf(bigger).wide.nodes), 0u) << "a tree of several leaves";
  EXPECT_EQ(rootLeafCount({}), 0u);
  int oneLeaf = 0;
  for (size_t n = 1; n <= device::kBvhMaxLeafPrimitives; ++n) {
    SCOPED_TRACE(n);
    Soup soup;
    std::mt19937_64 rng(20 + n);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    // Triangles of one mesh-like patch: the SAH keeps them in one leaf.
    for (size_t i = 0; i < n; ++i) {
      const vec3 c(0.1f * float(i), 0.05f * unit(rng), 0.5f);
      soup.add(c, c + vec3(0.1f, 0.0f, 0.01f * unit(rng)), c + vec3(0.05f, 0.1f, 0.0f));
    }
    const Tree t = treeOf(soup);
    const uint32_t rootLeaf = rootLeafCount(t.wide.nodes);
    ASSERT_TRUE(rootLeaf == 0 || rootLeaf == n) << "the leaf holds them all";
    if (rootLeaf == 0) continue;  // the SAH split them
    ++oneLeaf;
    for (const bool portable : {false, true}) {
      Walker whole(t.primitives, t.wide.nodes, portable);
      Walker fromLeaf(t.primitives, t.wide.nodes, portable, rootLeaf);
      std::uniform_real_distribution<float> around(-1.0f, 2.0f);
      int hits = 0, missedBox = 0;
      vec3 lo, hi;
      nodeBounds(t.wide.nodes[0], lo, hi);
      for (int r = 0; r < 4000; ++r) {
        const vec3 origin(around(rng), around(rng), r % 2 == 0 ? -0.5f : around(rng));
        // Half aimed at a triangle's corner or edge, half anywhere.
        const device::Primitive& p = t.primitives[r % n];
        const vec3 target = p.a + (r % 3 == 0 ? vec3(0.0f) : 0.5f * p.b);
        const vec3 direction = r % 2 == 0 ? glm::normalize(target - origin) : unitVector(rng);
        const float tMax = r % 5 == 0 ? 0.4f : 1e30f;
        const KernelHit expected = whole.closest(origin, direction, tMax);
        ASSERT_EQ(fromLeaf.closest(origin, direction, tMax), expected) << "ray " << r;
        ASSERT_EQ(fromLeaf.closest(origin, direction, tMax, true).found, expected.found) << "ray " << r;
        ASSERT_EQ(expected, whole.bruteForce(t.primitives, origin, direction, tMax)) << "ray " << r;
        hits += expected.found ? 1 : 0;
        const vec3 inverse = 1.0f / direction;
        const vec3 t0 = (lo - origin) * inverse, t1 = (hi - origin) * inverse;
        const vec3 nearT = glm::min(t0, t1), farT = glm::max(t0, t1);
        missedBox += std::max({nearT.x, nearT.y, nearT.z, 0.0f}) > std::min({farT.x, farT.y, farT.z}) ? 1 : 0;
      }
      EXPECT_GT(hits, 1000) << "the test must hit";
      EXPECT_GT(missedBox, 500) << "and miss the root's box";
    }
  }
  EXPECT_GE(oneLeaf, 4) << "most of these patches must be one leaf";
}

// Rays aimed at the height field's shared vertices and edge midpoints, where
// two to six triangles meet the ray at (nearly) the same distance: the walk
// picks the one brute force picks (the nearest; among equal distances, the
// lowest index), whatever order it visits the leaves in.
TEST(WideBvh, TiesAtSharedEdgesAndVerticesResolveAsBruteForce) {
  constexpr int kCells = 32;
  const Soup soup = heightField(kCells);
  const Tree t = treeOf(soup);
  for (const bool portable : {false, true}) {
    SCOPED_TRACE(portable ? "the shader's steps" : "the CPU's vector step");
    Walker walker(t.primitives, t.wide.nodes, portable);
    std::mt19937_64 rng(13);
    std::uniform_int_distribution<int> cell(1, kCells - 1);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int ties = 0, misses = 0;
    for (int r = 0; r < 6000; ++r) {
      const int i = cell(rng), j = cell(rng);
      const float x = (float(i) + (r % 3 == 1 ? 0.5f : 0.0f)) / float(kCells);
      const float y = (float(j) + (r % 3 == 2 ? 0.5f : 0.0f)) / float(kCells);
      const vec3 target(x, y, 0.1f * std::sin(7.0f * x) * std::cos(5.0f * y));
      const vec3 origin = target + vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, 0.5f + unit(rng));
      const vec3 direction = glm::normalize(target - origin);
      int atThatDistance = 0;
      const KernelHit expected = walker.bruteForce(t.primitives, origin, direction, 1e30f, &atThatDistance);
      // Moller-Trumbore is not watertight: a ray through a vertex may slip
      // between its triangles. The walk must then miss too.
      ASSERT_EQ(walker.closest(origin, direction, 1e30f), expected) << "ray " << r;
      ties += atThatDistance > 1 ? 1 : 0;
      misses += expected.found ? 0 : 1;
    }
    std::printf("  %d of 6000 rays met several triangles at the closest distance; %d slipped through\n", ties,
                misses);
    EXPECT_GT(ties, 100) << "the test must meet ties";
    EXPECT_LT(misses, 600) << "most rays aimed at the surface hit it";
  }
}

// The brute force's flat tree holds each primitive once, in order, in
// full leaves, under as few levels as four-wide nodes allow.
TEST(WideBvh, FlatTreeHoldsEveryPrimitiveOnceInOrder) {
  for (uint32_t count : {1u, 8u, 9u, 32u, 33u, 1000u, 4097u}) {
    const WideBvh flat = flatBvh(vec3(-1.0f), vec3(2.0f), count);
    uint32_t next = 0;
    uint32_t deepest = 0;
    const auto visit = [&](auto& self, uint32_t index, uint32_t level) -> void {
      deepest = std::max(deepest, level);
      const device::BvhNode& node = flat.nodes.at(index);
      for (int k = 0; k < 4; ++k) {
        if (isEmptySlot(node, k)) continue;
        EXPECT_EQ(node.minX[k], -1.0f);
        EXPECT_EQ(node.maxZ[k], 2.0f);
        if (node.count[k] == 0) {
          self(self, node.child[k], level + 1);
          continue;
        }
        EXPECT_EQ(node.child[k], next) << count << " primitives";
        EXPECT_LE(node.count[k], device::kBvhMaxLeafPrimitives);
        next += node.count[k];
      }
    };
    visit(visit, 0, 1);
    EXPECT_EQ(next, count);
    EXPECT_EQ(deepest, flat.depth);
    // 8 primitives a leaf, 4 leaves a node, 16 a node's grandchildren...
    uint32_t levels = 1;
    for (uint64_t capacity = 32; capacity < count; capacity *= 4) ++levels;
    EXPECT_EQ(flat.depth, levels) << count << " primitives";
  }
  // The walk's stack word holds indices below kBvhMaxIndex.
  EXPECT_THROW(flatBvh(vec3(-1.0f), vec3(2.0f), device::kBvhMaxIndex), std::invalid_argument);
}

// The same triangles in the brute force's flat tree and in the BVH: the
// same hits.
TEST(WideBvh, FlatTreeWalksLikeTheBvh) {
  const Soup soup = heightField(16);
  const Tree t = treeOf(soup);
  const WideBvh leaves = flatBvh(vec3(-1.0f), vec3(2.0f), uint32_t(t.primitives.size()));
  Walker tree(t.primitives, t.wide.nodes), flat(t.primitives, leaves.nodes);
  std::mt19937_64 rng(14);
  for (int r = 0; r < 2000; ++r) {
    const vec3 origin = vec3(0.5f, 0.5f, 1.0f) + 0.3f * unitVector(rng);
    const vec3 direction = unitVector(rng);
    ASSERT_EQ(tree.closest(origin, direction, 1e30f), flat.closest(origin, direction, 1e30f)) << "ray " << r;
  }
}

}  // namespace
}  // namespace spectrace
