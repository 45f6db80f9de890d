// Sphere primitive (kernel unit; host unit: host/shapes/sphere_shape.cpp):
// a: centre, b.x: radius, b.y: radius^2; facing outwards.
#ifndef SPECTRACE_SHAPES_SPHERE_H
#define SPECTRACE_SHAPES_SPHERE_H

// The nearer positive root, from the discriminant in the form of Ray
// Tracing Gems ch. 7 (r^2 - |oc - (oc.d) d|^2), which keeps its precision
// for rays from far away; the roots as q and c / q avoid cancellation.
FN float intersectSphere(vec3 origin, vec3 direction, Primitive p) {
  PRECISE vec3 oc = origin - p.a;
  PRECISE float b = dot3(oc, direction);
  PRECISE vec3 f = oc - direction * b;
  PRECISE float discriminant = p.b.y - dot3(f, f);
  if (!(discriminant >= 0.0f)) return -1.0f;
  PRECISE float c = dot3(oc, oc) - p.b.y;
  PRECISE float q = b > 0.0f ? -(b + sqrt(discriminant)) : -(b - sqrt(discriminant));
  PRECISE float t0 = q;
  PRECISE float t1 = q != 0.0f ? c / q : 0.0f;
  float nearRoot = min(t0, t1);
  float farRoot = max(t0, t1);
  return nearRoot > 0.0f ? nearRoot : farRoot;
}

FN vec3 sphereNormal(Primitive p, vec3 point) {
  PRECISE vec3 n = point - p.a;
  return unitNormal(n);
}

FN vec3 sphereSurfacePoint(Primitive p, vec3 n) {
  PRECISE vec3 onSphere = p.a + n * p.b.x;
  return onSphere;
}

// Emitting objects (lights/object.h): a point uniform over the sphere, and
// its outward normal.
FN vec3 sampleSpherePoint(Primitive p, float u, float v, OUT(vec3) n) {
  n = sampleSphere(u, v);
  return sphereSurfacePoint(p, n);
}

#endif  // SPECTRACE_SHAPES_SPHERE_H
