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

// Emitting objects (lights/object.h): a point uniform over the disk
// (radius sqrt(u) of the disk's, angle 2 pi v), and its face.
FN vec3 sampleDiskPoint(Primitive p, float u, float v, OUT(vec3) n) {
  n = diskNormal(p);
  vec3 t;
  vec3 b;
  frameAround(n, t, b);
  vec2 onDisk = sampleDisk(u, v, sqrt(p.c.x));
  PRECISE vec3 point = p.a + t * onDisk.x + b * onDisk.y;
  return point;
}

#endif  // SPECTRACE_SHAPES_DISK_H
