// Triangle primitive (kernel unit; host unit: host/shapes/mesh_shape.cpp,
// whose meshes are made of them): a: vertex 0, b, c: the edges to
// vertices 1 and 2; facing b x c (outwards for a closed mesh wound
// counter-clockwise from outside).
#ifndef SPECTRACE_SHAPES_TRIANGLE_H
#define SPECTRACE_SHAPES_TRIANGLE_H

// Möller-Trumbore. Returns the distance, or a negative number for a miss.
FN float intersectTriangle(vec3 origin, vec3 direction, Primitive p) {
  PRECISE vec3 pvec = cross3(direction, p.c);
  PRECISE float det = dot3(p.b, pvec);
  float miss = -1.0f;
  if (det == 0.0f) return miss;
  PRECISE float inverse = 1.0f / det;
  PRECISE vec3 tvec = origin - p.a;
  PRECISE float u = dot3(tvec, pvec) * inverse;
  if (!(u >= 0.0f && u <= 1.0f)) return miss;
  PRECISE vec3 qvec = cross3(tvec, p.b);
  PRECISE float v = dot3(direction, qvec) * inverse;
  if (!(v >= 0.0f && u + v <= 1.0f)) return miss;
  PRECISE float t = dot3(p.c, qvec) * inverse;
  return t;
}

FN vec3 triangleNormal(Primitive p) {
  PRECISE vec3 n = cross3(p.b, p.c);
  return unitNormal(n);
}

FN vec3 triangleSurfacePoint(Primitive p, vec3 point, vec3 n) { return pointOnPlane(p.a, point, n); }

// Emitting objects (lights/object.h): a point uniform over the triangle
// (the square's upper half folded onto the lower), and its face.
FN vec3 sampleTrianglePoint(Primitive p, float u, float v, OUT(vec3) n) {
  bool fold = u + v > 1.0f;
  float s = fold ? 1.0f - u : u;
  float r = fold ? 1.0f - v : v;
  PRECISE vec3 point = p.a + p.b * s + p.c * r;
  n = triangleNormal(p);
  return point;
}

#endif  // SPECTRACE_SHAPES_TRIANGLE_H
