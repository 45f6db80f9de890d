// The BVH builder: structure, containment, the depth limit, and traversal
// against brute force.
#include "compile/bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

namespace spectrace {
namespace {

using glm::dvec3;

dvec3 lo(const BinaryBvhNode& n) { return dvec3(n.boundsMin); }
dvec3 hi(const BinaryBvhNode& n) { return dvec3(n.boundsMax); }
bool contains(const dvec3& outerLo, const dvec3& outerHi, const dvec3& innerLo, const dvec3& innerHi) {
  return glm::all(glm::lessThanEqual(outerLo, innerLo)) && glm::all(glm::greaterThanEqual(outerHi, innerHi));
}

// Whether f is the largest float at or below d (the smallest at or above,
// when `up`): the nodes' bounds round outwards by one step at most.
bool tightBelow(float f, double d) {
  return double(f) <= d && double(std::nextafter(f, std::numeric_limits<float>::infinity())) > d;
}
bool tightAbove(float f, double d) {
  return double(f) >= d && double(std::nextafter(f, -std::numeric_limits<float>::infinity())) < d;
}

// The double union of the primitives under `node`, checking on the way that
// every node's float bounds are that union rounded outwards, no looser:
// the builder carries each child's bounds from its parent's partition, and
// loose bounds would still contain everything.
PrimitiveBounds checkTightBounds(const BuiltBvh& bvh, const std::vector<PrimitiveBounds>& bounds, uint32_t node) {
  const BinaryBvhNode& n = bvh.nodes[node];
  PrimitiveBounds all{dvec3(std::numeric_limits<double>::infinity()), dvec3(-std::numeric_limits<double>::infinity())};
  const auto add = [&](const PrimitiveBounds& b) {
    all.lo = glm::min(all.lo, b.lo);
    all.hi = glm::max(all.hi, b.hi);
  };
  if (n.primitiveCount() == 0) {
    add(checkTightBounds(bvh, bounds, node + 1));
    add(checkTightBounds(bvh, bounds, n.next));
  } else {
    for (uint32_t k = n.next; k < n.next + n.primitiveCount(); ++k) add(bounds[bvh.order[k]]);
  }
  for (int a = 0; a < 3; ++a) {
    EXPECT_TRUE(tightBelow(n.boundsMin[a], all.lo[a])) << "node " << node << " axis " << a << ": " << n.boundsMin[a]
                                                       << " for " << all.lo[a];
    EXPECT_TRUE(tightAbove(n.boundsMax[a], all.hi[a])) << "node " << node << " axis " << a << ": " << n.boundsMax[a]
                                                       << " for " << all.hi[a];
  }
  return all;
}

// Walks the whole tree and checks the layout and the guarantees the kernel
// relies on: each node reached once, first child next, leaves of 1..max
// primitives that together cover `order` once, bounds that contain (and
// no more than rounding outwards needs), the
// reported depth, and `order` a permutation of the inputs.
void checkTree(const BuiltBvh& bvh, const std::vector<PrimitiveBounds>& bounds) {
  const size_t n = bounds.size();
  ASSERT_EQ(bvh.order.size(), n);
  std::vector<int> seen(n, 0);
  for (uint32_t p : bvh.order) {
    ASSERT_LT(p, n);
    ++seen[p];
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; })) << "order is not a permutation";
  if (n == 0) {
    EXPECT_TRUE(bvh.nodes.empty());
    EXPECT_EQ(bvh.depth, 0u);
    return;
  }
  ASSERT_FALSE(bvh.nodes.empty());

  std::vector<int> nodeSeen(bvh.nodes.size(), 0);
  std::vector<int> slotSeen(n, 0);
  uint32_t depth = 0;
  struct Entry {
    uint32_t node, level;
  };
  std::vector<Entry> stack{{0, 1}};
  while (!stack.empty()) {
    const Entry e = stack.back();
    stack.pop_back();
    ASSERT_LT(e.node, bvh.nodes.size());
    ASSERT_EQ(nodeSeen[e.node]++, 0) << "node " << e.node << " reached twice";
    depth = std::max(depth, e.level);
    const BinaryBvhNode& node = bvh.nodes[e.node];
    const uint32_t count = node.primitiveCount();
    if (count == 0) {
      const uint32_t first = e.node + 1, second = node.next;
      ASSERT_GT(second, first);
      ASSERT_LT(second, bvh.nodes.size());
      EXPECT_LE((node.countAxis >> 16) & 3u, 2u);
      for (uint32_t child : {first, second})
        EXPECT_TRUE(contains(lo(node), hi(node), lo(bvh.nodes[child]), hi(bvh.nodes[child])))
            << "node " << e.node << " does not contain child " << child;
      stack.push_back({second, e.level + 1});
      stack.push_back({first, e.level + 1});
    } else {
      EXPECT_LE(count, device::kBvhMaxLeafPrimitives);
      EXPECT_EQ(node.countAxis >> 16, 0u);
      ASSERT_LE(size_t(node.next) + count, n);
      for (uint32_t k = node.next; k < node.next + count; ++k) {
        ++slotSeen[k];
        const PrimitiveBounds& b = bounds[bvh.order[k]];
        EXPECT_TRUE(contains(lo(node), hi(node), b.lo, b.hi))
            << "leaf " << e.node << " does not contain primitive " << bvh.order[k];
      }
    }
  }
  EXPECT_TRUE(std::all_of(nodeSeen.begin(), nodeSeen.end(), [](int s) { return s == 1; })) << "unreachable nodes";
  EXPECT_TRUE(std::all_of(slotSeen.begin(), slotSeen.end(), [](int s) { return s == 1; }))
      << "leaves do not cover order once";
  EXPECT_EQ(bvh.depth, depth);
  EXPECT_LE(bvh.depth, device::kBvhMaxDepth);
  checkTightBounds(bvh, bounds, 0);
}

struct Ray {
  dvec3 origin, invDir;
};

// Slab test in double. Monotonic in the box's bounds, so a ray that hits a
// box also hits every box containing it.
bool hits(const Ray& ray, const dvec3& boxLo, const dvec3& boxHi) {
  const dvec3 t0 = (boxLo - ray.origin) * ray.invDir;
  const dvec3 t1 = (boxHi - ray.origin) * ray.invDir;
  const dvec3 tNear = glm::min(t0, t1), tFar = glm::max(t0, t1);
  const double enter = std::max({tNear.x, tNear.y, tNear.z, 0.0});
  const double exit = std::min({tFar.x, tFar.y, tFar.z});
  return enter <= exit;
}

// The kernel's traversal, with its fixed stack: one entry pushed per level.
std::vector<uint32_t> traverse(const BuiltBvh& bvh, const Ray& ray) {
  std::vector<uint32_t> found;
  if (bvh.nodes.empty()) return found;
  std::array<uint32_t, device::kBvhMaxDepth> stack;
  uint32_t size = 0;
  uint32_t node = 0;
  while (true) {
    const BinaryBvhNode& n = bvh.nodes[node];
    if (hits(ray, lo(n), hi(n))) {
      if (n.primitiveCount() == 0) {
        if (size == stack.size()) {
          ADD_FAILURE() << "traversal stack overflow";
          return found;
        }
        stack[size++] = n.next;
        node = node + 1;
        continue;
      }
      for (uint32_t k = n.next; k < n.next + n.primitiveCount(); ++k) found.push_back(bvh.order[k]);
    }
    if (size == 0) break;
    node = stack[--size];
  }
  return found;
}

// Every ray must find, among the leaves' primitives, exactly the boxes brute
// force hits.
void checkTraversal(const BuiltBvh& bvh, const std::vector<PrimitiveBounds>& bounds, const dvec3& sceneLo,
                    const dvec3& sceneHi, uint64_t seed, int rays) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const dvec3 size = sceneHi - sceneLo;
  size_t totalHits = 0;
  for (int r = 0; r < rays; ++r) {
    // Every other ray aims at a primitive, so that small clusters get hit.
    Ray ray;
    dvec3 dir;
    do {
      ray.origin = sceneLo - 0.2 * size + 1.4 * size * dvec3(unit(rng), unit(rng), unit(rng));
      if (r % 2 == 0) {
        const PrimitiveBounds& target = bounds[size_t(unit(rng) * double(bounds.size())) % bounds.size()];
        dir = 0.5 * (target.lo + target.hi) - ray.origin;
      } else {
        dir = dvec3(unit(rng), unit(rng), unit(rng)) * 2.0 - 1.0;
      }
    } while (std::min({std::abs(dir.x), std::abs(dir.y), std::abs(dir.z)}) < 1e-3 * glm::length(dir));
    ray.invDir = 1.0 / dir;

    std::vector<uint32_t> expected;
    for (uint32_t i = 0; i < bounds.size(); ++i)
      if (hits(ray, bounds[i].lo, bounds[i].hi)) expected.push_back(i);
    std::vector<uint32_t> found;
    for (uint32_t p : traverse(bvh, ray))
      if (hits(ray, bounds[p].lo, bounds[p].hi)) found.push_back(p);
    std::sort(found.begin(), found.end());
    ASSERT_EQ(found, expected) << "ray " << r;
    totalHits += expected.size();
  }
  EXPECT_GE(totalHits, size_t(rays / 2)) << "the aimed rays should hit";
}

std::vector<PrimitiveBounds> randomBoxes(size_t n, uint64_t seed, double minSize, double maxSize) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<PrimitiveBounds> boxes(n);
  for (auto& b : boxes) {
    const dvec3 centre(unit(rng), unit(rng), unit(rng));
    const dvec3 half = 0.5 * (minSize + (maxSize - minSize) * dvec3(unit(rng), unit(rng), unit(rng)));
    b = {centre - half, centre + half};
  }
  return boxes;
}

TEST(Bvh, EmptyInputGivesAnEmptyTree) {
  const BuiltBvh bvh = buildBvh({});
  EXPECT_TRUE(bvh.nodes.empty());
  EXPECT_TRUE(bvh.order.empty());
  EXPECT_EQ(bvh.depth, 0u);
}

TEST(Bvh, OnePrimitiveIsOneLeaf) {
  const std::vector<PrimitiveBounds> bounds{{dvec3(0.1, 0.2, 0.3), dvec3(0.4, 0.5, 0.6)}};
  const BuiltBvh bvh = buildBvh(bounds);
  ASSERT_EQ(bvh.nodes.size(), 1u);
  EXPECT_EQ(bvh.nodes[0].primitiveCount(), 1u);
  EXPECT_EQ(bvh.nodes[0].next, 0u);
  EXPECT_EQ(bvh.order, std::vector<uint32_t>{0});
  EXPECT_EQ(bvh.depth, 1u);
  checkTree(bvh, bounds);
}

TEST(Bvh, FloatBoundsContainTheDoubleBounds) {
  // Values that float rounds both ways, tiny ones that underflow, and ones
  // beyond float's range.
  const std::vector<PrimitiveBounds> bounds{
      {dvec3(0.1, -0.1, 1.0 / 3.0), dvec3(0.1 + 1e-12, -0.1 + 1e-12, 2.0 / 3.0)},
      {dvec3(1e-300, -1e-300, 0.0), dvec3(2e-300, 1e-300, 1e-300)},
      {dvec3(-1e300, 3e38, 1.0), dvec3(-1e39, 1e300, 1.0)},
  };
  for (const auto& b : bounds) checkTree(buildBvh(std::span(&b, 1)), {b});
  checkTree(buildBvh(bounds), bounds);
}

TEST(Bvh, ExtremeCoordinatesBuild) {
  // Centroids spread over double's whole range (lo + hi and hi - lo
  // overflow), and a cluster spread over a few denormals (bin widths
  // overflow): the builder must still split them validly.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<PrimitiveBounds> boxes;
  for (int i = 0; i < 500; ++i) {
    const dvec3 c = 1.7e308 * dvec3(unit(rng), unit(rng), unit(rng));
    boxes.push_back({glm::min(c, c * 0.5), glm::max(c, c * 0.5)});
  }
  for (int i = 0; i < 50; ++i) {
    const double d = std::ldexp(double(i % 7), -1074);  // multiples of the smallest denormal
    boxes.push_back({dvec3(d, -d, 0.0), dvec3(d, d, d)});
  }
  boxes.push_back({dvec3(-1.7e308), dvec3(1.7e308)});
  const BuiltBvh bvh = buildBvh(boxes);
  checkTree(bvh, boxes);
}

TEST(Bvh, InvalidBoundsThrow) {
  const double nan = std::nan("");
  EXPECT_THROW(buildBvh(std::vector<PrimitiveBounds>{{dvec3(0.0), dvec3(nan)}}), std::invalid_argument);
  EXPECT_THROW(buildBvh(std::vector<PrimitiveBounds>{{dvec3(1.0), dvec3(0.0)}}), std::invalid_argument);
  EXPECT_THROW(buildBvh(std::vector<PrimitiveBounds>{{dvec3(0.0), dvec3(INFINITY)}}), std::invalid_argument);
}

TEST(Bvh, RandomBoxesTraverseLikeBruteForce) {
  const std::vector<PrimitiveBounds> boxes = randomBoxes(20000, 1, 0.002, 0.03);
  const BuiltBvh bvh = buildBvh(boxes);
  checkTree(bvh, boxes);
  checkTraversal(bvh, boxes, dvec3(0.0), dvec3(1.0), 2, 2000);
}

TEST(Bvh, SmallInputsTraverseLikeBruteForce) {
  for (size_t n : {2, 3, 7, 8, 9, 16, 17, 100}) {
    const std::vector<PrimitiveBounds> boxes = randomBoxes(n, 10 + n, 0.05, 0.3);
    const BuiltBvh bvh = buildBvh(boxes);
    checkTree(bvh, boxes);
    checkTraversal(bvh, boxes, dvec3(0.0), dvec3(1.0), 20 + n, 500);
  }
}

TEST(Bvh, ClustersTraverseLikeBruteForce) {
  // Dense clusters far apart, of very different sizes: SAH splits unevenly.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<PrimitiveBounds> boxes;
  for (int cluster = 0; cluster < 6; ++cluster) {
    const dvec3 centre = 100.0 * dvec3(unit(rng), unit(rng), unit(rng));
    const double spread = std::pow(10.0, -cluster);
    for (int i = 0; i < 3000 / (cluster + 1); ++i) {
      const dvec3 c = centre + spread * dvec3(unit(rng), unit(rng), unit(rng));
      boxes.push_back({c - 0.05 * spread, c + 0.05 * spread});
    }
  }
  const BuiltBvh bvh = buildBvh(boxes);
  checkTree(bvh, boxes);
  checkTraversal(bvh, boxes, dvec3(0.0), dvec3(100.0), 4, 2000);
}

TEST(Bvh, CoincidentPrimitivesStayWithinTheDepthLimit) {
  const std::vector<PrimitiveBounds> boxes(100000, PrimitiveBounds{dvec3(1.0, 2.0, 3.0), dvec3(1.5, 2.5, 3.5)});
  const BuiltBvh bvh = buildBvh(boxes);
  checkTree(bvh, boxes);
  EXPECT_EQ(bvh.depth, 15u);  // median splits: 1 + ceil(log2(100000 / 8))
}

TEST(Bvh, ExponentiallySpacedPrimitivesStayWithinTheDepthLimit) {
  // Centroids at 1.0002^i: every SAH bin split peels off a few hundred
  // primitives at the far end, which unchecked would nest ~300 levels deep.
  std::vector<PrimitiveBounds> boxes;
  for (int i = 0; i < 100000; ++i) {
    const double x = std::pow(1.0002, i);
    boxes.push_back({dvec3(x, 0.0, 0.0), dvec3(x * 1.0001, 1.0, 1.0)});
  }
  const BuiltBvh bvh = buildBvh(boxes);
  checkTree(bvh, boxes);
  EXPECT_LE(bvh.depth, device::kBvhMaxDepth);

  // Powers of two over double's whole range: float bounds underflow to 0 and
  // overflow to infinity, and must still contain.
  std::vector<PrimitiveBounds> wide;
  for (int e = -1000; e <= 1000; ++e) {
    const double x = std::ldexp(1.0, e);
    wide.push_back({dvec3(x, -x, 0.0), dvec3(1.5 * x, -0.5 * x, x)});
  }
  const BuiltBvh wideBvh = buildBvh(wide);
  checkTree(wideBvh, wide);
  EXPECT_LE(wideBvh.depth, device::kBvhMaxDepth);

  // Flat boxes at 2^e: the cheapest SAH split peels off the farthest one,
  // level after level, until the depth limit makes median splits take over.
  std::vector<PrimitiveBounds> peeled;
  for (int e = 0; e < 1000; ++e) {
    const double x = std::ldexp(1.0, e);
    peeled.push_back({dvec3(x, 0.0, 0.0), dvec3(x, 1.0, 1.0)});
  }
  const BuiltBvh peeledBvh = buildBvh(peeled);
  checkTree(peeledBvh, peeled);
  EXPECT_LE(peeledBvh.depth, device::kBvhMaxDepth);
}

TEST(Bvh, ExponentiallySpacedPrimitivesTraverseLikeBruteForce) {
  std::vector<PrimitiveBounds> boxes;
  for (int i = 0; i < 20000; ++i) {
    const double x = std::pow(1.001, i);  // up to ~5e8
    boxes.push_back({dvec3(x, 0.0, 0.0), dvec3(x * 1.01, 1.0, 1.0)});
  }
  const BuiltBvh bvh = buildBvh(boxes);
  checkTree(bvh, boxes);
  EXPECT_LE(bvh.depth, device::kBvhMaxDepth);
  checkTraversal(bvh, boxes, dvec3(0.0), dvec3(100.0, 1.0, 1.0), 5, 500);
}

// Subtrees built on other threads must give the very tree one thread does:
// the same nodes in the same places and the same primitive order.
void expectSameTree(const BuiltBvh& a, const BuiltBvh& b, unsigned threads) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size()) << threads << " threads";
  for (size_t k = 0; k < a.nodes.size(); ++k) {
    const BinaryBvhNode &x = a.nodes[k], &y = b.nodes[k];
    ASSERT_TRUE(x.boundsMin == y.boundsMin && x.boundsMax == y.boundsMax && x.next == y.next &&
                x.countAxis == y.countAxis)
        << "node " << k << " differs with " << threads << " threads";
  }
  EXPECT_EQ(a.order, b.order) << threads << " threads";
  EXPECT_EQ(a.depth, b.depth) << threads << " threads";
}

TEST(Bvh, ThreadsBuildTheSameTree) {
  // Enough primitives that subtrees below the top levels are forked
  // (kMinForkedPrimitives is 2^15), and clusters so that SAH splits unevenly.
  std::vector<PrimitiveBounds> boxes = randomBoxes(150000, 8, 0.001, 0.004);
  const std::vector<PrimitiveBounds> cluster = randomBoxes(60000, 9, 0.0001, 0.0004);
  for (const PrimitiveBounds& b : cluster) boxes.push_back({0.01 * b.lo, 0.01 * b.hi});
  const BuiltBvh one = buildBvh(boxes, 1);
  checkTree(one, boxes);
  for (unsigned threads : {2u, 3u, 8u}) expectSameTree(one, buildBvh(boxes, threads), threads);
}

TEST(Bvh, AMillionPrimitives) {
  // The scale scenes reach; the build takes about a second in Release.
  const std::vector<PrimitiveBounds> boxes = randomBoxes(1000000, 6, 0.0005, 0.002);
  checkTree(buildBvh(boxes), boxes);
}

}  // namespace
}  // namespace spectrace
