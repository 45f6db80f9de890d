// Disk primitive (kernel unit; host unit: host/shapes/disk_shape.cpp):
// a: centre, b: unit normal (its facing), c.x: radius^2.
#ifndef SPECTRACE_SHAPES_DISK_H
#define SPECTRACE_SHAPES_DISK_H

FN float intersectDisk(vec3 origin, vec3 direction, Primitive p) {
  vec3 point;
  float t = intersectPlane(origin, direction, p.a, p.b, point);
  PRECISE vec3 q = point - p.a;
  return dot3(q, q) <= p.c.x ? t : -1.0f;
}

// b normalised again, as the other primitives' normals are.
FN vec3 diskNormal(Primitive p) { return unitNormal(p.b); }

FN vec3 diskSurfacePoint(Primitive p, vec3 point, vec3 n) { return pointOnPlane(p.a, point, n); }

#endif  // SPECTRACE_SHAPES_DISK_H
