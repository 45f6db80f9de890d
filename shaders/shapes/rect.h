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

// Emitting objects (lights/object.h): a point uniform over the rect, and
// its face.
FN vec3 sampleRectPoint(Primitive p, float u, float v, OUT(vec3) n) {
  PRECISE vec3 point = p.a + p.b * (2.0f * u - 1.0f) + p.c * (2.0f * v - 1.0f);
  n = rectNormal(p);
  return point;
}

#endif  // SPECTRACE_SHAPES_RECT_H
