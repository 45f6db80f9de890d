#pragma once
// The CPU instance's own steps of the shared kernel's BVH walk
// (shaders/objects.h: intersectObjects): at a leaf of triangles, four of
// them tested on the lanes of one register (nearestTriangleInLeaf, below);
// at a node, the ray against the node's four child boxes on one vector
// register, the children sorted as 64-bit keys (entry distance, then
// child) by the shader's network of compare-exchanges in conditional
// moves, the nearest met taken next and the others pushed far to near.
// The shader's step, compiled as C++, is scalar (GCC does not vectorise
// its vec4 lanes); this step traces the ray ceiling's incoherent rays
// about twice as fast (docs/benchmarks.md).
//
// Exact, not an approximation: the box test does the shader's float
// operations in the shader's order on the planes the shader's min and max
// would pick, so entry and exit distances are the same numbers (the sign
// of a zero aside, which no comparison sees); and the walk's closest hit
// does not depend on the order in which children are visited (of equal
// distances the lowest primitive wins), so only equal keys may be pushed
// in another order. wide_walk_test checks both against the shader's step.
#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#ifdef __SSE__
#include <xmmintrin.h>
#endif
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "device_shared.h"

namespace spectrace::device {

// Four float lanes in one register (SSE on x86-64; any target's vectors).
typedef float FloatLanes __attribute__((vector_size(16)));
typedef int32_t MaskLanes __attribute__((vector_size(16)));

inline FloatLanes broadcast(float x) { return FloatLanes{x, x, x, x}; }
// A lane of `ifTrue` where `mask` is set, else of `ifFalse` (a blend; GCC
// and Clang both take it, where a vector ?: is GCC's alone).
inline FloatLanes select(MaskLanes mask, FloatLanes ifTrue, FloatLanes ifFalse) {
  return FloatLanes((mask & MaskLanes(ifTrue)) | (~mask & MaskLanes(ifFalse)));
}
// glm::min(x, y) (y < x ? y : x) and glm::max(x, y) (x < y ? y : x), lane
// by lane, with their choice on ties and NaN. SSE's minps(a, b) is a < b ?
// a : b and maxps(a, b) is a > b ? a : b, the second operand on ties and
// NaN, so each is one instruction, where GCC leaves the select as a
// compare and three logic operations.
#ifdef __SSE__
inline FloatLanes lanesMin(FloatLanes x, FloatLanes y) { return FloatLanes(_mm_min_ps(__m128(y), __m128(x))); }
inline FloatLanes lanesMax(FloatLanes x, FloatLanes y) { return FloatLanes(_mm_max_ps(__m128(y), __m128(x))); }
#else
inline FloatLanes lanesMin(FloatLanes x, FloatLanes y) { return select(y < x, y, x); }
inline FloatLanes lanesMax(FloatLanes x, FloatLanes y) { return select(x < y, y, x); }
#endif

// Bit k set where lane k of `mask` is.
inline unsigned laneBits(MaskLanes mask) {
#ifdef __SSE__
  return unsigned(_mm_movemask_ps(__m128(mask)));
#else
  unsigned bits = 0;
  for (int k = 0; k < 4; ++k) bits |= unsigned(mask[k] & 1) << k;
  return bits;
#endif
}

// A ray as the vector step reads it, made once per walk: its origin and
// inverse direction broadcast to lanes, and for each axis which of a node's
// planes it meets first (the min plane where the inverse is positive, else
// the max plane), as byte offsets into BvhNode.
struct WalkRay {
  FloatLanes ox, oy, oz, ix, iy, iz;
  uint32_t nearX, nearY, nearZ, farX, farY, farZ;
};

inline WalkRay walkRayOf(const glm::vec3& origin, const glm::vec3& inverse) {
  WalkRay ray;
  ray.ox = broadcast(origin.x);
  ray.oy = broadcast(origin.y);
  ray.oz = broadcast(origin.z);
  ray.ix = broadcast(inverse.x);
  ray.iy = broadcast(inverse.y);
  ray.iz = broadcast(inverse.z);
  // inverseDirection gives no zero or NaN (a zero component's inverse is
  // +3e38), so each axis's inverse is plainly positive or negative.
  const auto planes = [](float inverseAxis, size_t minPlane, size_t maxPlane, uint32_t& nearPlane,
                         uint32_t& farPlane) {
    const bool positive = !(inverseAxis < 0.0f);
    nearPlane = uint32_t(positive ? minPlane : maxPlane);
    farPlane = uint32_t(positive ? maxPlane : minPlane);
  };
  planes(inverse.x, offsetof(BvhNode, minX), offsetof(BvhNode, maxX), ray.nearX, ray.farX);
  planes(inverse.y, offsetof(BvhNode, minY), offsetof(BvhNode, maxY), ray.nearY, ray.farY);
  planes(inverse.z, offsetof(BvhNode, minZ), offsetof(BvhNode, maxZ), ray.nearZ, ray.farZ);
  return ray;
}

inline FloatLanes nodePlane(const BvhNode& node, uint32_t offset) {
  FloatLanes lanes;
  __builtin_memcpy(&lanes, reinterpret_cast<const char*>(&node) + offset, sizeof lanes);
  return lanes;
}

// objects.h's rayMeetsChildren on lanes: child k is met before tMax when
// enter[k] <= leave[k].
//
// The shader takes min and max of each axis's two plane distances; here
// the near and far planes are chosen once per ray by the inverse's sign.
// That gives the same numbers: a box's min plane is never above its max
// plane, and rounding is monotonic, so (min - o) * i <= (max - o) * i for a
// positive inverse i, and >= for a negative one. Only the sign of a zero
// can differ (min and max of -0 and +0 pick by position), and no use of
// enter and leave can tell: they are only compared. An empty slot's box is
// a point, tested like any other and dropped by its zero child and count.
inline void rayMeetsChildrenLanes(const WalkRay& ray, const BvhNode& node, float tMax, FloatLanes& enter,
                                  FloatLanes& leave) {
  const FloatLanes xNear = (nodePlane(node, ray.nearX) - ray.ox) * ray.ix;
  const FloatLanes xFar = (nodePlane(node, ray.farX) - ray.ox) * ray.ix;
  const FloatLanes yNear = (nodePlane(node, ray.nearY) - ray.oy) * ray.iy;
  const FloatLanes yFar = (nodePlane(node, ray.farY) - ray.oy) * ray.iy;
  const FloatLanes zNear = (nodePlane(node, ray.nearZ) - ray.oz) * ray.iz;
  const FloatLanes zFar = (nodePlane(node, ray.farZ) - ray.oz) * ray.iz;
  enter = lanesMax(lanesMax(xNear, yNear), lanesMax(zNear, broadcast(0.0f)));
  leave = lanesMin(lanesMin(xFar, yFar), lanesMin(zFar, broadcast(tMax))) * 1.0000004f;
}

// An entry of the CPU walk's stack: a child's entry distance and its word
// (objects.h's child << kBvhCountBits | count) in one 64-bit key,
// (bits of the distance + 1) << 32 | word. A distance is never negative,
// and a non-negative float orders as its bits, so keys order as their
// distances (ties by word); 0 is no child. One key sorts and moves as one
// integer, where a distance and a word would move as two.
using WalkEntry = uint64_t;
// A step writes four entries above the stack's top and keeps the ones it
// pushes, so the stack has room for three past the deepest walk's.
constexpr uint32_t kWalkStackSize = kBvhStackSize + 3u;

inline uint32_t entryChild(WalkEntry e) { return uint32_t(e) >> kBvhCountBits; }
inline uint32_t entryCount(WalkEntry e) { return uint32_t(e) & ((1u << kBvhCountBits) - 1u); }
// Whether the entry's box begins within `reach` (objects.h's enter <=
// reach, for a reach that is not negative).
inline bool entryWithin(WalkEntry e, float reach) {
  uint32_t reachBits;
  __builtin_memcpy(&reachBits, &reach, sizeof reachBits);
  return uint32_t(e >> 32) <= reachBits + 1u;
}

// The larger key to `a`, the smaller to `b` (conditional moves, no branch).
inline void orderPair(WalkEntry& a, WalkEntry& b) {
  const WalkEntry larger = a < b ? b : a, smaller = a < b ? a : b;
  a = larger;
  b = smaller;
}

// The walk's step at `node`, for its children that the ray meets before
// tMax (empty slots never): the nearest goes to `child` and `count`, to be
// visited next, and the others onto the stack, far to near, so that the
// next nearest is on top. `prefetch(entry)` is called for the four keys
// sorted, met or not (a key of 0 names the root, whose lines are read
// anyway). Returns false, pushing nothing, when no child is met.
//
// The shader pushes the nearest too and pops it at once: its entry
// distance is never beyond the walk's reach (enter <= leave, and leave is
// at most tMax times the same widening as the reach), so visiting it
// directly is the same walk.
//
// No branch on the ray's data but "was anything met": how many children a
// ray meets, and in which order, is a coin toss at every node, and a CPU
// guessing it wrong lost more than the sort below costs. So the four keys
// (0 for a child not met) go through the shader's network of five
// compare-exchanges as integers, all four are written above the stack's
// top, and the top moves up by the number met less one.
template <typename Prefetch>
inline bool nearestChildMet(const WalkRay& ray, const BvhNode& node, float tMax, WalkEntry* stack, uint32_t& depth,
                            uint32_t& child, uint32_t& count, Prefetch prefetch) {
  FloatLanes enter, leave;
  rayMeetsChildrenLanes(ray, node, tMax, enter, leave);
  MaskLanes childLanes, countLanes;
  __builtin_memcpy(&childLanes, &node.child, sizeof childLanes);
  __builtin_memcpy(&countLanes, &node.count, sizeof countLanes);
  const MaskLanes met = (enter <= leave) & ((childLanes | countLanes) != 0);
  const unsigned bits = laneBits(met);
  if (bits == 0) return false;
  // + 0.0f turns an entry distance of -0 into +0, whose bits are 0.
  const FloatLanes distance = enter + 0.0f;
  MaskLanes high;
  __builtin_memcpy(&high, &distance, sizeof high);
  high = (high + 1) & met;
  const MaskLanes word = ((childLanes << int(kBvhCountBits)) | countLanes) & met;
  WalkEntry key[4];
#ifdef __SSE2__
  // Lane k's word and high half side by side: key k, little-endian.
  const __m128i low = _mm_unpacklo_epi32(__m128i(word), __m128i(high));
  const __m128i upper = _mm_unpackhi_epi32(__m128i(word), __m128i(high));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(key), low);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(key + 2), upper);
#else
  for (int k = 0; k < 4; ++k) key[k] = (WalkEntry(uint32_t(high[k])) << 32) | uint32_t(word[k]);
#endif
  orderPair(key[0], key[1]);
  orderPair(key[2], key[3]);
  orderPair(key[0], key[2]);
  orderPair(key[1], key[3]);
  orderPair(key[1], key[2]);
  // Each key stored on its own, and the nearest (the last not 0) picked
  // by conditional moves: a wider load or an indexed one of keys just
  // stored would wait for the stores to retire.
  for (int k = 0; k < 4; ++k) stack[depth + uint32_t(k)] = key[k];
  depth += uint32_t(__builtin_popcount(bits)) - 1u;
  WalkEntry nearest = key[0];
  nearest = key[1] != 0 ? key[1] : nearest;
  nearest = key[2] != 0 ? key[2] : nearest;
  nearest = key[3] != 0 ? key[3] : nearest;
  child = entryChild(nearest);
  count = entryCount(nearest);
  for (int k = 0; k < 4; ++k) prefetch(key[k]);
  return true;
}

// Four triangles' a, b and c as lanes: x, y and z of each (the Primitive
// records' floats, word offsets 0, 4 and 8), for `leaf[index[k]]` in lane k.
struct TriangleLanes {
  FloatLanes ax, ay, az, bx, by, bz, cx, cy, cz;
  MaskLanes type;  // the records' type words (word offset 3)
};

inline TriangleLanes triangleLanes(const Primitive* leaf, const uint32_t index[4]) {
  TriangleLanes lanes;
  FloatLanes* rows[3][3] = {{&lanes.ax, &lanes.ay, &lanes.az},
                            {&lanes.bx, &lanes.by, &lanes.bz},
                            {&lanes.cx, &lanes.cy, &lanes.cz}};
  for (int v = 0; v < 3; ++v) {
#ifdef __SSE__
    // Four records' rows, transposed in registers: a scalar fill of the
    // lanes stalls on store forwarding.
    const __m128 r0 = _mm_loadu_ps(reinterpret_cast<const float*>(leaf + index[0]) + 4 * v);
    const __m128 r1 = _mm_loadu_ps(reinterpret_cast<const float*>(leaf + index[1]) + 4 * v);
    const __m128 r2 = _mm_loadu_ps(reinterpret_cast<const float*>(leaf + index[2]) + 4 * v);
    const __m128 r3 = _mm_loadu_ps(reinterpret_cast<const float*>(leaf + index[3]) + 4 * v);
    const __m128 xy01 = _mm_unpacklo_ps(r0, r1), xy23 = _mm_unpacklo_ps(r2, r3);
    const __m128 zw01 = _mm_unpackhi_ps(r0, r1), zw23 = _mm_unpackhi_ps(r2, r3);
    *rows[v][0] = FloatLanes(_mm_movelh_ps(xy01, xy23));
    *rows[v][1] = FloatLanes(_mm_movehl_ps(xy23, xy01));
    *rows[v][2] = FloatLanes(_mm_movelh_ps(zw01, zw23));
    if (v == 0) lanes.type = MaskLanes(_mm_movehl_ps(zw23, zw01));
#else
    for (int k = 0; k < 4; ++k) {
      const Primitive& p = leaf[index[k]];
      const glm::vec3& corner = v == 0 ? p.a : v == 1 ? p.b : p.c;
      (*rows[v][0])[k] = corner.x;
      (*rows[v][1])[k] = corner.y;
      (*rows[v][2])[k] = corner.z;
      lanes.type[k] = int32_t(p.type);
    }
#endif
  }
  return lanes;
}

// objects.h's leaf loop on a leaf of triangles: the shader's
// intersectTriangle (shapes/triangle.h) on four lanes at once, then its
// choice of hit. A scalar walk mispredicts the test's two range checks for
// about every other triangle; here they are masks.
//
// Exact: each lane does the shader's float operations in its order (dot3
// and cross3 as beam_math.h writes them; no contraction), so u, v and t are
// the same bits, and a lane that the shader would leave early is masked
// out by the same comparisons. Each triangle met is then handed to
// `keepHit(t, primitive)` (the walk's rule, objects.h: keepNearerHit) in
// primitive order, so the result is the scalar loop's.
//
// Returns false where the leaf holds another type of primitive, found a
// group of four at a time: the triangles of groups before it have been
// handed over, and the caller's scalar loop hands them over again, which
// changes nothing (keepNearerHit keeps the least (t, primitive) of those
// it is given, and the least of a set is the same with repeats).
template <typename KeepHit>
inline bool nearestTriangleInLeaf(const glm::vec3& origin, const glm::vec3& direction, const Primitive* leaf,
                                  uint32_t first, uint32_t count, KeepHit keepHit) {
  const float dx = direction.x, dy = direction.y, dz = direction.z;
  for (uint32_t group = 0; group < count; group += 4) {
    // Lanes past the leaf's end repeat its last triangle, and are not read.
    uint32_t index[4];
    for (uint32_t k = 0; k < 4; ++k) index[k] = group + k < count ? group + k : count - 1u;
    const TriangleLanes p = triangleLanes(leaf, index);
    const MaskLanes triangle = p.type == int32_t(kPrimitiveTriangle);
    if (!(triangle[0] & triangle[1] & triangle[2] & triangle[3])) return false;
    // pvec = cross3(direction, c); det = dot3(b, pvec).
    const FloatLanes px = dy * p.cz - dz * p.cy, py = dz * p.cx - dx * p.cz, pz = dx * p.cy - dy * p.cx;
    const FloatLanes det = p.bx * px + p.by * py + p.bz * pz;
    const FloatLanes inverse = 1.0f / det;
    // tvec = origin - a; u = dot3(tvec, pvec) * inverse.
    const FloatLanes tx = origin.x - p.ax, ty = origin.y - p.ay, tz = origin.z - p.az;
    const FloatLanes u = (tx * px + ty * py + tz * pz) * inverse;
    // qvec = cross3(tvec, b); v = dot3(direction, qvec) * inverse.
    const FloatLanes qx = ty * p.bz - tz * p.by, qy = tz * p.bx - tx * p.bz, qz = tx * p.by - ty * p.bx;
    const FloatLanes v = (dx * qx + dy * qy + dz * qz) * inverse;
    const FloatLanes t = (p.cx * qx + p.cy * qy + p.cz * qz) * inverse;
    const MaskLanes met = (det != 0.0f) & (u >= 0.0f) & (u <= 1.0f) & (v >= 0.0f) & (u + v <= 1.0f) & (t > 0.0f);
    // Lanes past the leaf's end are masked off; the hits go in lane order.
    const unsigned inLeaf = count - group >= 4 ? 15u : (1u << (count - group)) - 1u;
    for (unsigned bits = laneBits(met) & inLeaf; bits != 0; bits &= bits - 1) {
      const int k = __builtin_ctz(bits);
      keepHit(t[k], first + group + uint32_t(k));
    }
  }
  return true;
}

}  // namespace spectrace::device
