// What the primitives' kernel units share: a unit normal, the plane that
// rects, disks and triangles lie in, and the offset that keeps a beam off
// the surface it leaves (scattered, or emitted by an emitting object).
#ifndef SPECTRACE_SHAPES_SHAPE_SHARED_H
#define SPECTRACE_SHAPES_SHAPE_SHARED_H

// Whether `p` is of `type` (kPrimitive*); always false for a type the
// pipeline was specialised without (kernel_features.h), so that type's
// code is compiled out of each dispatch.
FN bool isPrimitive(Primitive p, uint type) { return SPECTRACE_PRIMITIVE_ENABLED(type) && p.type == type; }

FN vec3 unitNormal(vec3 n) {
  PRECISE vec3 unit = n * (1.0f / sqrt(dot3(n, n)));
  return unit;
}

// A plane through `centre` with normal `n` (any length): the distance and
// the point, or a negative distance when parallel or behind.
FN float intersectPlane(vec3 origin, vec3 direction, vec3 centre, vec3 n, OUT(vec3) point) {
  PRECISE float denominator = dot3(direction, n);
  PRECISE float t = denominator != 0.0f ? dot3(centre - origin, n) / denominator : -1.0f;
  PRECISE vec3 q = origin + direction * t;
  point = q;
  return t;
}

// `point` projected onto the plane through `centre` with unit normal `n`.
FN vec3 pointOnPlane(vec3 centre, vec3 point, vec3 n) {
  PRECISE vec3 onPlane = point - n * dot3(point - centre, n);
  return onPlane;
}

// Wächter and Binder, "A Fast and Robust Method for Avoiding
// Self-Intersection" (Ray Tracing Gems, ch. 6): the point moved off the
// surface along n by a fixed number of ulps (a fixed distance near the
// origin, where ulps vanish), so a ray from it cannot meet the surface it
// leaves through rounding. Near the origin the distance is 2^-20 m, what
// 256 ulps are at the threshold 1/32 m (their 2^-16 suits scenes of other
// units; in metres it shifted refracted beams by 15 um), and still a
// thousand times the rounding of a point there.
FN vec3 offsetOffSurface(vec3 point, vec3 n) {
  ivec3 ulps = ivec3(int(256.0f * n.x), int(256.0f * n.y), int(256.0f * n.z));
  vec3 moved = vec3(intBitsToFloat(floatBitsToInt(point.x) + (point.x < 0.0f ? -ulps.x : ulps.x)),
                    intBitsToFloat(floatBitsToInt(point.y) + (point.y < 0.0f ? -ulps.y : ulps.y)),
                    intBitsToFloat(floatBitsToInt(point.z) + (point.z < 0.0f ? -ulps.z : ulps.z)));
  PRECISE vec3 nudged = point + n * (1.0f / 1048576.0f);
  return vec3(abs(point.x) < 1.0f / 32.0f ? nudged.x : moved.x, abs(point.y) < 1.0f / 32.0f ? nudged.y : moved.y,
              abs(point.z) < 1.0f / 32.0f ? nudged.z : moved.z);
}

#endif  // SPECTRACE_SHAPES_SHAPE_SHARED_H
