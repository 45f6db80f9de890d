// What the primitives' kernel units share: a unit normal, and the plane
// that rects, disks and triangles lie in.
#ifndef SPECTRACE_SHAPES_SHAPE_SHARED_H
#define SPECTRACE_SHAPES_SHAPE_SHARED_H

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

#endif  // SPECTRACE_SHAPES_SHAPE_SHARED_H
