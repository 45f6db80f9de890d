#pragma once
// The CPU instance's own steps of the shared kernel's BVH walk
// (shaders/objects.h: intersectObjects): at a leaf of triangles, four of
// them tested on the lanes of one register (nearestTriangleInLeaf, below);
// at a node, the ray against the node's four child boxes on one vector
// register, then the children met pushed far to near by a short insertion
// among those met. The shader's
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
#ifdef __SSE__
#include <xmmintrin.h>
#endif

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

// Four triangles' a, b and c as lanes: x, y and z of each (the Primitive
// records' floats, word offsets 0, 4 and 8), for `leaf[index[k]]` in lane k.
struct TriangleLanes {
  FloatLanes ax, ay, az, bx, by, bz, cx, cy, cz;
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
#else
    for (int k = 0; k < 4; ++k) {
      const Primitive& p = leaf[index[k]];
      const glm::vec3& corner = v == 0 ? p.a : v == 1 ? p.b : p.c;
      (*rows[v][0])[k] = corner.x;
      (*rows[v][1])[k] = corner.y;
      (*rows[v][2])[k] = corner.z;
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
// primitive order, so the result is the scalar loop's. Returns false,
// handing over nothing, where the leaf holds another type of primitive.
template <typename KeepHit>
inline bool nearestTriangleInLeaf(const glm::vec3& origin, const glm::vec3& direction, const Primitive* leaf,
                                  uint32_t first, uint32_t count, KeepHit keepHit) {
  for (uint32_t i = 0; i < count; ++i)
    if (leaf[i].type != kPrimitiveTriangle) return false;
  const float dx = direction.x, dy = direction.y, dz = direction.z;
  for (uint32_t group = 0; group < count; group += 4) {
    // Lanes past the leaf's end repeat its last triangle, and are not read.
    uint32_t index[4];
    for (uint32_t k = 0; k < 4; ++k) index[k] = group + k < count ? group + k : count - 1u;
    const TriangleLanes p = triangleLanes(leaf, index);
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
    for (uint32_t k = 0; k < 4 && group + k < count; ++k)
      if (met[k]) keepHit(t[k], first + group + k);
  }
  return true;
}

}  // namespace spectrace::device
