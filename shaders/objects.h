// Scene objects in the shared kernel: dispatch to the primitive's unit
// (shapes/<primitive>.h), the BVH walk with a fixed stack, the camera's
// body (the offset that keeps a scattered beam off the surface it leaves
// is shapes/shape_shared.h's). Float only, with PRECISE, so the CPU reference and the shader
// find the same surface at the same point.
#ifndef SPECTRACE_OBJECTS_H
#define SPECTRACE_OBJECTS_H

// The closest surface a ray meets.
struct ObjectHit {
  float t;         // distance along the (unit) direction
  uint primitive;  // index into the primitives
};

// A hit that met nothing: where a walk may be skipped (no objects), the
// variable still holds a value.
FN ObjectHit noObjectHit() {
  ObjectHit none;
  none.t = 3.0e38f;
  none.primitive = 0u;
  return none;
}

// One kernel unit per primitive (host units: host/shapes/<kind>_shape.cpp),
// chosen by the Primitive record's type.
#include "shapes/shape_shared.h"
#include "shapes/triangle.h"
#include "shapes/rect.h"
#include "shapes/disk.h"
#include "shapes/sphere.h"

// The distance along the ray to the primitive, or a negative number for a
// miss.
FN float intersectPrimitive(vec3 origin, vec3 direction, Primitive p) {
  float t = -1.0f;
  if (isPrimitive(p, kPrimitiveTriangle)) t = intersectTriangle(origin, direction, p);
  else if (isPrimitive(p, kPrimitiveRect)) t = intersectRect(origin, direction, p);
  else if (isPrimitive(p, kPrimitiveDisk)) t = intersectDisk(origin, direction, p);
  else if (isPrimitive(p, kPrimitiveSphere)) t = intersectSphere(origin, direction, p);
  return t;
}

// The unit geometric normal at `point`: outwards for spheres and closed
// meshes (counter-clockwise from outside), along the given normal for
// rects and disks.
FN vec3 primitiveNormal(Primitive p, vec3 point) {
  vec3 n = vec3(0.0f, 0.0f, 0.0f);
  if (isPrimitive(p, kPrimitiveTriangle)) n = triangleNormal(p);
  else if (isPrimitive(p, kPrimitiveRect)) n = rectNormal(p);
  else if (isPrimitive(p, kPrimitiveDisk)) n = diskNormal(p);
  else if (isPrimitive(p, kPrimitiveSphere)) n = sphereNormal(p, point);
  return n;
}

// The hit point put back onto the primitive's surface. A point found as
// origin + t * direction carries rounding that grows with |origin| and t,
// which the offset below (a few ulps of the point itself) need not cover;
// projected onto the surface, its error is a few ulps of the primitive's
// own coordinates.
FN vec3 pointOnSurface(Primitive p, vec3 point, vec3 n) {
  vec3 onSurface = point;
  if (isPrimitive(p, kPrimitiveTriangle)) onSurface = triangleSurfacePoint(p, point, n);
  else if (isPrimitive(p, kPrimitiveRect)) onSurface = rectSurfacePoint(p, point, n);
  else if (isPrimitive(p, kPrimitiveDisk)) onSurface = diskSurfacePoint(p, point, n);
  else if (isPrimitive(p, kPrimitiveSphere)) onSurface = sphereSurfacePoint(p, n);
  return onSurface;
}

// 1 / direction with zero components replaced by a huge finite value, so
// the slab test never forms 0 * inf (NaN).
FN vec3 inverseDirection(vec3 direction) {
  PRECISE vec3 inverse = vec3(direction.x != 0.0f ? 1.0f / direction.x : 3.0e38f,
                              direction.y != 0.0f ? 1.0f / direction.y : 3.0e38f,
                              direction.z != 0.0f ? 1.0f / direction.z : 3.0e38f);
  return inverse;
}

// The ray against the four child boxes of a BVH node: child k is met
// before tMax when enter[k] <= leave[k]. The far distance is widened by a
// few ulps (pbrt-v4's 1 + 2 gamma(3)), so rounding never drops a box the
// ray grazes; visiting more boxes than needed changes no result. Four lanes
// of one vector operation on the CPU, as on lavapipe.
FN void rayMeetsChildren(vec3 origin, vec3 inverse, BvhNode node, float tMax, OUT(vec4) enter, OUT(vec4) leave) {
  PRECISE vec4 x0 = (node.minX - vec4(origin.x)) * inverse.x;
  PRECISE vec4 x1 = (node.maxX - vec4(origin.x)) * inverse.x;
  PRECISE vec4 y0 = (node.minY - vec4(origin.y)) * inverse.y;
  PRECISE vec4 y1 = (node.maxY - vec4(origin.y)) * inverse.y;
  PRECISE vec4 z0 = (node.minZ - vec4(origin.z)) * inverse.z;
  PRECISE vec4 z1 = (node.maxZ - vec4(origin.z)) * inverse.z;
  enter = max(max(min(x0, x1), min(y0, y1)), max(min(z0, z1), vec4(0.0f)));
  PRECISE vec4 farT = min(min(max(x0, x1), max(y0, y1)), min(max(z0, z1), vec4(tMax))) * 1.0000004f;
  leave = farT;
}

// One compare-exchange of a sorting network: keys i < j end in order; equal
// keys keep their order.
FN void sortChildPair(INOUT(vec4) key, INOUT(uvec4) slot, int i, int j) {
  if (key[j] < key[i]) {
    float k = key[i];
    key[i] = key[j];
    key[j] = k;
    uint s = slot[i];
    slot[i] = slot[j];
    slot[j] = s;
  }
}

// The walk's rule for a primitive met at distance t (negative: missed):
// the nearest hit in (0, hit.t) is kept, and of equal distances the lowest
// primitive, so the hit does not depend on the order of the walk.
FN void keepNearerHit(float t, uint primitive, INOUT(ObjectHit) hit, INOUT(bool) found) {
  if (t > 0.0f && (t < hit.t || (found && t == hit.t && primitive < hit.primitive))) {
    hit.t = t;
    hit.primitive = primitive;
    found = true;
  }
}

// The closest primitive the ray meets at a distance in (0, tMax), through
// the four-wide BVH (device_shared.h: BvhNode) with a fixed stack: the
// children a node's ray meets are pushed far to near, so the nearest is
// taken next, and an entry whose box begins beyond the closest hit so far
// is dropped unread. Of primitives met at the same distance, the lowest
// index wins, so the hit does not depend on the order of the walk. With
// anyHit, returns at the first one (visibility tests).
FN bool intersectObjects(vec3 origin, vec3 direction, float tMax, bool anyHit, OUT(ObjectHit) hit) {
#ifdef SPECTRACE_CPU_WALK_STEP
  // The CPU's own walk, the same hit (host/kernel/beam_kernel.h:
  // cpuIntersectObjects); portableWalk keeps this text for tests.
  if (!portableWalk) return cpuIntersectObjects(origin, direction, tMax, anyHit, hit);
#endif
  hit.t = tMax;
  hit.primitive = 0u;
  bool found = false;
  vec3 inverse = inverseDirection(direction);
  uint stackEntry[kBvhStackSize];  // child << kBvhCountBits | count
  float stackEnter[kBvhStackSize];
  uint depth = 0u;
  uint child = 0u;  // the root, or with bvhRootLeaf the root's only leaf
  uint count = constants.bvhRootLeaf;
  while (true) {
    if (count > 0u) {
      for (uint i = 0u; i < count; ++i)
        keepNearerHit(intersectPrimitive(origin, direction, readPrimitive(child + i)), child + i, hit, found);
      if (found && anyHit) break;
    } else {
      BvhNode node = readBvhNode(child);
      vec4 enter;
      vec4 leave;
      rayMeetsChildren(origin, inverse, node, hit.t, enter, leave);
      // Children the ray misses (and empty slots) sort last, at 3.4e38
      // (beyond any reach: tMax is at most 3.0e38). A fixed network of
      // five compare-exchanges sorts the rest near to far: the same steps
      // in every lane, where an insertion sort's loop would diverge.
      bvec4 met = bvec4(enter.x <= leave.x, enter.y <= leave.y, enter.z <= leave.z, enter.w <= leave.w);
      met = bvec4(met.x && (node.count.x > 0u || node.child.x > 0u), met.y && (node.count.y > 0u || node.child.y > 0u),
                  met.z && (node.count.z > 0u || node.child.z > 0u), met.w && (node.count.w > 0u || node.child.w > 0u));
      vec4 key = vec4(met.x ? enter.x : 3.4e38f, met.y ? enter.y : 3.4e38f, met.z ? enter.z : 3.4e38f,
                      met.w ? enter.w : 3.4e38f);
      uvec4 slot = uvec4(0u, 1u, 2u, 3u);
      sortChildPair(key, slot, 0, 1);
      sortChildPair(key, slot, 2, 3);
      sortChildPair(key, slot, 0, 2);
      sortChildPair(key, slot, 1, 3);
      sortChildPair(key, slot, 1, 2);
      // Far to near onto the stack, the nearest on top.
      for (int k = 3; k >= 0; --k) {
        if (key[k] == 3.4e38f) continue;
        stackEntry[depth] = (node.child[slot[k]] << kBvhCountBits) | node.count[slot[k]];
        stackEnter[depth] = key[k];
        depth += 1u;
        prefetchBvhChild(node.child[slot[k]], node.count[slot[k]]);
      }
    }
    // The nearest entry that the closest hit so far leaves in reach (with
    // the box test's widening).
    PRECISE float reach = hit.t * 1.0000004f;
    bool next = false;
    while (depth > 0u && !next) {
      depth -= 1u;
      next = stackEnter[depth] <= reach;
    }
    if (!next) break;
    child = stackEntry[depth] >> kBvhCountBits;
    count = stackEntry[depth] & ((1u << kBvhCountBits) - 1u);
  }
  return found;
}

// The camera's body, in the camera frame: the box |x| <= half width,
// |y| <= half height (camera.h: cameraBodyHalfSize), 0 <= z <= cameraFrontZ
// (its model's front plane: a pinhole's aperture; 0 for a bare sensor, a
// flat plate). A beam that enters it through the aperture and lands on the
// sensor is counted (at wavelength lambda, keeping `transmission` of its
// flux); any other beam that meets it is absorbed. Returns the distance to
// the body (negative: the ray misses it), and whether the beam is counted,
// at `cell`.
FN float intersectCamera(vec3 origin, vec3 direction, float lambda, OUT(bool) counted, OUT(uvec2) cell,
                         OUT(float) transmission) {
  counted = hitSensor(origin, direction, lambda, cell, transmission);
  if (counted) {
    PRECISE float toFront = (origin.z - constants.cameraFrontZ) / -direction.z;
    return toFront;
  }
  vec3 inverse = inverseDirection(direction);
  vec2 halfSize = cameraBodyHalfSize();
  vec3 lo = vec3(-halfSize.x, -halfSize.y, 0.0f);
  vec3 hi = vec3(halfSize.x, halfSize.y, constants.cameraFrontZ);
  PRECISE vec3 t0 = (lo - origin) * inverse;
  PRECISE vec3 t1 = (hi - origin) * inverse;
  vec3 nearT = min(t0, t1);
  vec3 farT = max(t0, t1);
  float enter = max(max(nearT.x, nearT.y), max(nearT.z, 0.0f));
  float leave = min(min(farT.x, farT.y), farT.z);
  return enter <= leave ? enter : -1.0f;
}

#endif  // SPECTRACE_OBJECTS_H
