// Rect primitive (kernel unit; host unit: host/shapes/rect_shape.cpp):
// a: centre, b, c: half edges; facing b x c.
#ifndef SPECTRACE_SHAPES_RECT_H
#define SPECTRACE_SHAPES_RECT_H

FN float intersectRect(vec3 origin, vec3 direction, Primitive p) {
  vec3 point;
  float t = intersectPlane(origin, direction, p.a, cross3(p.b, p.c), point);
  PRECISE vec3 q = point - p.a;
  PRECISE float s = dot3(q, p.b) / dot3(p.b, p.b);
  PRECISE float r = dot3(q, p.c) / dot3(p.c, p.c);
  return abs(s) <= 1.0f && abs(r) <= 1.0f ? t : -1.0f;
}

FN vec3 rectNormal(Primitive p) {
  PRECISE vec3 n = cross3(p.b, p.c);
  return unitNormal(n);
}

FN vec3 rectSurfacePoint(Primitive p, vec3 point, vec3 n) { return pointOnPlane(p.a, point, n); }

#endif  // SPECTRACE_SHAPES_RECT_H
