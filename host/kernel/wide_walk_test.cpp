// The CPU's vector step of the BVH walk (wide_walk.h) against the shader's
// own step (shaders/objects.h), which the CPU instance also compiles: the
// same entry and exit distances, bit for bit, for random boxes and rays and
// for the awkward ones (direction components of zero, origins on a box's
// faces, signed zeros, empty and flat boxes), and the same children pushed,
// nearest on top. Whole walks of both are checked against brute force in
// compile/wide_bvh_test.cpp.
#include "kernel/wide_walk.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "kernel/beam_kernel.h"

namespace spectrace::device {
namespace {

using glm::vec3;
using glm::vec4;

struct Step {
  std::vector<uint32_t> entries;
  std::vector<float> keys;
};

class WalkSteps : public ::testing::Test {
 protected:
  WalkSteps() : kernel_(TraceConstants{}, {}, {}, {}) {}

  // The shader's box test and the vector one must agree in every lane: the
  // same bits, or both zero (the sign of a zero distance is the one thing
  // the vector test's choice of planes may change, and the walk only
  // compares these numbers).
  void expectSameDistances(const vec3& origin, const vec3& direction, const BvhNode& node, float tMax) {
    const vec3 inverse = kernel_.inverseDirection(direction);
    vec4 enter, leave;
    kernel_.rayMeetsChildren(origin, inverse, node, tMax, enter, leave);
    FloatLanes enterLanes, leaveLanes;
    rayMeetsChildrenLanes(walkRayOf(origin, inverse), node, tMax, enterLanes, leaveLanes);
    const auto same = [](float a, float b) {
      return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b) || (a == 0.0f && b == 0.0f);
    };
    for (int k = 0; k < 4; ++k) {
      ASSERT_TRUE(same(enter[k], enterLanes[k])) << "enter, slot " << k << ": " << enter[k] << " against "
                                                 << enterLanes[k];
      ASSERT_TRUE(same(leave[k], leaveLanes[k])) << "leave, slot " << k << ": " << leave[k] << " against "
                                                 << leaveLanes[k];
    }
  }

  // The shader's push, as objects.h does it (the text between its box test
  // and the stack), and the vector one.
  Step shaderStep(const vec3& origin, const vec3& direction, const BvhNode& node, float tMax) {
    const vec3 inverse = kernel_.inverseDirection(direction);
    vec4 enter, leave;
    kernel_.rayMeetsChildren(origin, inverse, node, tMax, enter, leave);
    vec4 key;
    uvec4 slot(0u, 1u, 2u, 3u);
    for (int k = 0; k < 4; ++k) {
      const bool met = enter[k] <= leave[k] && (node.count[k] > 0u || node.child[k] > 0u);
      key[k] = met ? enter[k] : 3.4e38f;
    }
    kernel_.sortChildPair(key, slot, 0, 1);
    kernel_.sortChildPair(key, slot, 2, 3);
    kernel_.sortChildPair(key, slot, 0, 2);
    kernel_.sortChildPair(key, slot, 1, 3);
    kernel_.sortChildPair(key, slot, 1, 2);
    Step step;
    for (int k = 3; k >= 0; --k) {
      if (key[k] == 3.4e38f) continue;
      step.entries.push_back((node.child[slot[k]] << kBvhCountBits) | node.count[slot[k]]);
      step.keys.push_back(key[k]);
    }
    return step;
  }
  Step vectorStep(const vec3& origin, const vec3& direction, const BvhNode& node, float tMax,
                  std::vector<WalkEntry>* prefetched = nullptr) {
    // Entries below the step's own, which it must leave alone.
    constexpr WalkEntry kBelow = 0x5a5a5a5a5a5a5a5aull;
    WalkEntry stack[2 + kWalkStackSize];
    std::fill(std::begin(stack), std::end(stack), kBelow);
    uint32_t depth = 2;
    const vec3 inverse = kernel_.inverseDirection(direction);
    uint32_t child = 0, count = 0;
    const bool met = nearestChildMet(walkRayOf(origin, inverse), node, tMax, stack, depth, child, count,
                                     [&](WalkEntry e) {
                                       if (prefetched) prefetched->push_back(e);
                                     });
    EXPECT_EQ(stack[0], kBelow);
    EXPECT_EQ(stack[1], kBelow);
    Step step;
    for (uint32_t i = 2; i < depth; ++i) {
      step.entries.push_back(entryChild(stack[i]) << kBvhCountBits | entryCount(stack[i]));
      step.keys.push_back(keyDistance(stack[i]));
    }
    if (!met) {
      EXPECT_EQ(depth, 2u) << "nothing pushed when nothing is met";
      return step;
    }
    // The nearest, visited next, is where the shader's step leaves it: on
    // top of the stack, at its entry distance.
    step.entries.push_back((child << kBvhCountBits) | count);
    FloatLanes enter, leave;
    rayMeetsChildrenLanes(walkRayOf(origin, inverse), node, tMax, enter, leave);
    for (int k = 0; k < 4; ++k)
      if (node.child[k] == child && node.count[k] == count && enter[k] <= leave[k]) {
        step.keys.push_back(enter[k]);
        break;
      }
    return step;
  }
  // The entry distance a stack key holds.
  static float keyDistance(WalkEntry e) {
    const uint32_t bits = uint32_t(e >> 32) - 1u;
    float distance;
    std::memcpy(&distance, &bits, sizeof distance);
    return distance;
  }

  BeamKernel kernel_;
};

BvhNode randomNode(std::mt19937_64& rng) {
  std::uniform_real_distribution<float> coordinate(-2.0f, 2.0f);
  std::uniform_int_distribution<int> kind(0, 5);
  BvhNode node{};
  for (int k = 0; k < 4; ++k) {
    float lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      const float u = coordinate(rng), v = coordinate(rng);
      lo[a] = std::min(u, v);
      hi[a] = kind(rng) == 0 ? lo[a] : std::max(u, v);  // some flat boxes
    }
    node.minX[k] = lo[0];
    node.minY[k] = lo[1];
    node.minZ[k] = lo[2];
    node.maxX[k] = hi[0];
    node.maxY[k] = hi[1];
    node.maxZ[k] = hi[2];
    const int what = kind(rng);
    node.child[k] = what == 0 ? 0u : uint32_t(10 + 4 * k + what);  // slot 0 of some nodes empty below
    node.count[k] = what == 0 || what > 3 ? 0u : uint32_t(what);
  }
  return node;
}

vec3 randomDirection(std::mt19937_64& rng) {
  std::normal_distribution<float> normal;
  std::uniform_int_distribution<int> zeroed(0, 7);
  vec3 d(normal(rng), normal(rng), normal(rng));
  // Some axes exactly zero, and some negative zero, as inverseDirection
  // meets them.
  for (int a = 0; a < 3; ++a) {
    const int z = zeroed(rng);
    if (z == 0) d[a] = 0.0f;
    if (z == 1) d[a] = -0.0f;
  }
  if (d == vec3(0.0f)) d.z = 1.0f;
  return d;
}

TEST_F(WalkSteps, VectorBoxTestGivesTheShadersDistancesBitForBit) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
  std::uniform_int_distribution<int> pick(0, 3);
  for (int r = 0; r < 20000; ++r) {
    const BvhNode node = randomNode(rng);
    vec3 origin(coordinate(rng), coordinate(rng), coordinate(rng));
    // Some origins on a child's faces: entry distances of +0 and -0.
    if (r % 3 == 0) {
      const int k = pick(rng);
      origin.x = node.minX[k];
      origin.y = node.maxY[k];
    }
    const float tMax = r % 5 == 0 ? 0.5f : 3.0e38f;
    ASSERT_NO_FATAL_FAILURE(expectSameDistances(origin, randomDirection(rng), node, tMax)) << "case " << r;
  }
}

TEST_F(WalkSteps, VectorStepPushesTheShadersChildrenNearestOnTop) {
  std::mt19937_64 rng(32);
  std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
  std::uniform_int_distribution<int> pick(0, 3);
  int pushedSomething = 0, pushedSeveral = 0;
  for (int r = 0; r < 20000; ++r) {
    const BvhNode node = randomNode(rng);
    const vec3 origin(coordinate(rng), coordinate(rng), coordinate(rng));
    // Most rays aimed at a child's box, so that several are met.
    const int k = pick(rng);
    const vec3 aim(node.minX[k] + node.maxX[k], node.minY[k] + node.maxY[k], node.minZ[k] + node.maxZ[k]);
    const vec3 direction = r % 4 == 0 ? randomDirection(rng) : glm::normalize(0.5f * aim - origin);
    const float tMax = r % 5 == 0 ? 0.5f : 3.0e38f;
    const Step expected = shaderStep(origin, direction, node, tMax);
    std::vector<WalkEntry> prefetched;
    const Step got = vectorStep(origin, direction, node, tMax, &prefetched);
    ASSERT_EQ(got.keys, expected.keys) << "case " << r;
    // Equal keys may come in either order (the walk's hit does not depend
    // on it); distinct ones must come in the shader's.
    std::vector<uint32_t> gotEntries = got.entries, expectedEntries = expected.entries;
    for (size_t i = 0; i < got.keys.size(); ++i) {
      const bool tied = (i > 0 && got.keys[i - 1] == got.keys[i]) ||
                        (i + 1 < got.keys.size() && got.keys[i + 1] == got.keys[i]);
      if (!tied) {
        ASSERT_EQ(got.entries[i], expected.entries[i]) << "case " << r << ", entry " << i;
      }
    }
    std::sort(gotEntries.begin(), gotEntries.end());
    std::sort(expectedEntries.begin(), expectedEntries.end());
    ASSERT_EQ(gotEntries, expectedEntries) << "case " << r;
    // Every child met is prefetched, the nearest included; the other keys
    // prefetched are 0, no child (the root).
    std::vector<uint32_t> prefetchedChildren;
    for (WalkEntry e : prefetched)
      if (e != 0) prefetchedChildren.push_back(entryChild(e) << kBvhCountBits | entryCount(e));
    std::sort(prefetchedChildren.begin(), prefetchedChildren.end());
    ASSERT_EQ(prefetchedChildren, gotEntries) << "case " << r;
    ASSERT_EQ(prefetched.size(), got.entries.empty() ? 0u : 4u) << "case " << r;
    pushedSomething += got.entries.empty() ? 0 : 1;
    pushedSeveral += got.entries.size() > 1 ? 1 : 0;
  }
  EXPECT_GT(pushedSomething, 10000) << "the test must meet boxes";
  EXPECT_GT(pushedSeveral, 2000) << "the test must order several children";
}

// The pop's test on a key, against the shader's enter <= reach on the
// distance: at the distance, one float either side, 0 and the largest.
TEST_F(WalkSteps, KeysAreWithinReachAsTheirDistancesAre) {
  std::mt19937_64 rng(33);
  std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
  std::uniform_int_distribution<int> pick(0, 3);
  int keys = 0, zeros = 0;
  for (int r = 0; r < 10000; ++r) {
    const BvhNode node = randomNode(rng);
    vec3 origin(coordinate(rng), coordinate(rng), coordinate(rng));
    const int k = pick(rng);
    // Some origins on a child's face (an entry distance of +0 or -0), the
    // rest aimed at a child's box.
    if (r % 3 == 0) origin.x = node.minX[k];
    const vec3 aim(node.minX[k] + node.maxX[k], node.minY[k] + node.maxY[k], node.minZ[k] + node.maxZ[k]);
    const vec3 direction = r % 3 == 0 ? randomDirection(rng) : glm::normalize(0.5f * aim - origin);
    std::vector<WalkEntry> prefetched;
    vectorStep(origin, direction, node, 3.0e38f, &prefetched);
    for (WalkEntry e : prefetched) {
      if (e == 0) continue;
      ++keys;
      const float d = keyDistance(e);
      zeros += d == 0.0f ? 1 : 0;
      ASSERT_GE(d, 0.0f);
      ASSERT_FALSE(std::signbit(d)) << "an entry distance of -0 is keyed as +0";
      for (float reach : {d, std::nextafter(d, 0.0f), std::nextafter(d, INFINITY), 0.0f, 1.0f, 3.0e38f,
                          3.0e38f * 1.0000004f, INFINITY})
        ASSERT_EQ(entryWithin(e, reach), d <= reach) << "distance " << d << ", reach " << reach;
    }
  }
  EXPECT_GT(keys, 5000);
  EXPECT_GT(zeros, 100) << "the test must meet entry distances of zero";
}

// A node whose four boxes are the same: four equal keys, all pushed.
TEST_F(WalkSteps, EqualBoxesAreAllPushed) {
  BvhNode node{};
  for (int k = 0; k < 4; ++k) {
    node.minX[k] = node.minY[k] = node.minZ[k] = 1.0f;
    node.maxX[k] = node.maxY[k] = node.maxZ[k] = 2.0f;
    node.child[k] = uint32_t(5 + k);
  }
  const Step got = vectorStep(vec3(0.0f), glm::normalize(vec3(1.0f)), node, 3.0e38f);
  ASSERT_EQ(got.entries.size(), 4u);
  for (float key : got.keys) EXPECT_EQ(key, got.keys[0]);
  const Step expected = shaderStep(vec3(0.0f), glm::normalize(vec3(1.0f)), node, 3.0e38f);
  EXPECT_EQ(got.keys, expected.keys);
}

// A walk's hit so far, and the walk's rule (objects.h: keepNearerHit)
// applied to it.
struct LeafHit {
  float t;
  uint32_t primitive;
  bool found;
  bool operator==(const LeafHit&) const = default;
};

void keepNearer(BeamKernel& kernel, LeafHit& hit, float t, uint32_t primitive) {
  BeamKernel::ObjectHit kept{hit.t, hit.primitive};
  kernel.keepNearerHit(t, primitive, kept, hit.found);
  hit.t = kept.t;
  hit.primitive = kept.primitive;
}

// objects.h's leaf loop, as the shader runs it: each primitive's test, then
// the rule.
LeafHit shaderLeaf(BeamKernel& kernel, const vec3& origin, const vec3& direction, const std::vector<Primitive>& leaf,
                   uint32_t first, LeafHit hit) {
  for (uint32_t i = 0; i < leaf.size(); ++i)
    keepNearer(kernel, hit, kernel.intersectPrimitive(origin, direction, leaf[i]), first + i);
  return hit;
}

Primitive triangle(const vec3& a, const vec3& b, const vec3& c) {
  Primitive p{};
  p.type = kPrimitiveTriangle;
  p.a = a;
  p.b = b - a;
  p.c = c - a;
  return p;
}

// The lanes' leaf against the shader's, bit for bit, on leaves of one to
// eight triangles: random ones, and a fan about one vertex with the ray
// through the vertex or along a shared edge (equal distances on several
// triangles, where the lowest index must win), degenerate triangles
// (det == 0), duplicates, and earlier hits nearer, farther and equal.
TEST_F(WalkSteps, TriangleLanesGiveTheShadersLeafHit) {
  std::mt19937_64 rng(33);
  std::uniform_real_distribution<float> coordinate(-2.0f, 2.0f);
  std::uniform_int_distribution<int> sizes(1, 8), kinds(0, 5);
  int hits = 0, ties = 0;
  for (int r = 0; r < 30000; ++r) {
    const int n = sizes(rng);
    const int kind = kinds(rng);
    std::vector<Primitive> leaf;
    const vec3 centre(coordinate(rng), coordinate(rng), coordinate(rng));
    for (int i = 0; i < n; ++i) {
      const vec3 a(coordinate(rng), coordinate(rng), coordinate(rng));
      const vec3 b(coordinate(rng), coordinate(rng), coordinate(rng));
      vec3 c(coordinate(rng), coordinate(rng), coordinate(rng));
      if (kind == 1) {  // a fan: every triangle has the vertex `centre`
        leaf.push_back(triangle(centre, a, b));
        continue;
      }
      if (kind == 2 && i % 3 == 2) c = a + 2.0f * (b - a);  // collinear: det == 0
      if (kind == 3 && i > 0 && i % 2 == 1) {
        leaf.push_back(leaf.back());  // a duplicate: the same distance
        continue;
      }
      leaf.push_back(triangle(a, b, c));
    }
    vec3 origin(coordinate(rng), coordinate(rng), coordinate(rng));
    origin *= 3.0f;
    vec3 target = kind == 1 && r % 2 == 0 ? centre  // through the shared vertex
                                          : leaf[r % n].a + 0.5f * leaf[r % n].b + (r % 3) * 0.25f * leaf[r % n].c;
    if (kind == 4) target = leaf[r % n].a + 0.5f * leaf[r % n].b;  // on an edge
    const vec3 direction = r % 7 == 0 ? randomDirection(rng) : glm::normalize(target - origin);
    const uint32_t first = uint32_t(r % 1000);
    // The hit so far: none, or nearer, farther or at the same distance as
    // this leaf's own.
    LeafHit before{3.0e38f, 0u, false};
    const LeafHit alone = shaderLeaf(kernel_, origin, direction, leaf, first, before);
    if (alone.found && kind != 5) {
      const int which = r % 4;
      if (which == 1) before = {alone.t * 0.5f, first + 3u, true};
      if (which == 2) before = {alone.t * 2.0f, first + 1000u, true};
      if (which == 3) before = {alone.t, r % 2 == 0 ? first + 1000u : (first > 0 ? first - 1u : 0u), true};
    }
    const LeafHit expected = shaderLeaf(kernel_, origin, direction, leaf, first, before);
    LeafHit got = before;
    ASSERT_TRUE(nearestTriangleInLeaf(origin, direction, leaf.data(), first, uint32_t(n),
                                      [&](float t, uint32_t p) { keepNearer(kernel_, got, t, p); }));
    ASSERT_EQ(std::bit_cast<uint32_t>(got.t), std::bit_cast<uint32_t>(expected.t)) << "case " << r;
    ASSERT_EQ(got.primitive, expected.primitive) << "case " << r;
    ASSERT_EQ(got.found, expected.found) << "case " << r;
    hits += expected.found && expected.primitive != before.primitive ? 1 : 0;
    int equal = 0;
    for (int i = 0; i < n; ++i)
      equal += kernel_.intersectPrimitive(origin, direction, leaf[i]) == expected.t && expected.found ? 1 : 0;
    ties += equal > 1 ? 1 : 0;
  }
  EXPECT_GT(hits, 8000) << "the test must hit triangles";
  EXPECT_GT(ties, 1000) << "the test must meet equal distances";
}

// A leaf that holds another primitive is left to the shader's loop: at
// once where it is in the first four, else after the groups before it,
// whose hits the loop then gives again, to the same end.
TEST_F(WalkSteps, TriangleLanesDeclineOtherPrimitives) {
  std::vector<Primitive> leaf = {triangle(vec3(0, 0, 1), vec3(1, 0, 1), vec3(0, 1, 1)), Primitive{}};
  leaf[1].type = kPrimitiveSphere;
  int handed = 0;
  EXPECT_FALSE(nearestTriangleInLeaf(vec3(0.1f, 0.1f, 0.0f), vec3(0, 0, 1), leaf.data(), 0u, 2u,
                                     [&](float, uint32_t) { ++handed; }));
  EXPECT_EQ(handed, 0) << "no hit is handed over";

  // Six: triangles at z = 3, 1 (twice: a tie), 2 and 4, then a sphere about
  // z = -5, behind the ray's start, which the ray misses.
  std::vector<Primitive> mixed;
  for (float z : {3.0f, 1.0f, 1.0f, 2.0f, 4.0f})
    mixed.push_back(triangle(vec3(0, 0, z), vec3(1, 0, z), vec3(0, 1, z)));
  Primitive sphere{};
  sphere.type = kPrimitiveSphere;
  sphere.a = vec3(0.0f, 0.0f, -5.0f);
  sphere.b = vec3(0.5f);
  mixed.push_back(sphere);
  const vec3 origin(0.1f, 0.1f, 0.0f), direction(0, 0, 1);
  const LeafHit expected = shaderLeaf(kernel_, origin, direction, mixed, 7u, LeafHit{3.0e38f, 0u, false});
  ASSERT_TRUE(expected.found);
  ASSERT_EQ(expected.primitive, 8u) << "the nearer of the tied pair, by index";
  LeafHit got{3.0e38f, 0u, false};
  handed = 0;
  EXPECT_FALSE(nearestTriangleInLeaf(origin, direction, mixed.data(), 7u, uint32_t(mixed.size()),
                                     [&](float t, uint32_t p) {
                                       ++handed;
                                       keepNearer(kernel_, got, t, p);
                                     }));
  EXPECT_EQ(handed, 4) << "the first group's four hits";
  const LeafHit again = shaderLeaf(kernel_, origin, direction, mixed, 7u, got);
  EXPECT_EQ(again, expected);
}

}  // namespace
}  // namespace spectrace::device
