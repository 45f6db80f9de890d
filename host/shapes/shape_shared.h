#pragma once
// Helpers several shape units share: reading and checking placement keys,
// the closed-shape message, and the padded bounds of float primitives.
#include <initializer_list>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "shapes/shape_type.h"

namespace spectrace {

// Placement vectors of shapes built in code must already be unit length
// (the loader normalises what a file gives).
inline constexpr double kShapeUnitEps = 1e-9;

// "center": a point within kMaxCoordinateM.
glm::dvec3 parseCenter(const json_fields::Source& c, const json_fields::Json& v, const std::string& ptr);
// "normal" (a unit vector) into shape.normal, and its default tangent into
// shape.uAxis.
void parseNormal(const json_fields::Source& c, const json_fields::Json& v, const std::string& ptr, Shape& shape);
// "radius_m": a length.
double parseRadius(const json_fields::Source& c, const json_fields::Json& v, const std::string& ptr);

// A point within the world bounds.
void checkShapePoint(const ShapeFieldCheck& check, const std::string& key, const glm::dvec3& p);
// A length in metres, > 0 and <= kMaxCoordinateM.
void checkShapeLength(const ShapeFieldCheck& check, const std::string& key, double value);
void checkShapeUnitVector(const ShapeFieldCheck& check, const std::string& key, const glm::dvec3& v);
bool allFinite(const glm::dvec3& v);

// "a <material> needs a closed shape: a sphere or a closed mesh" and `why`.
std::string needsClosedShape(std::string_view material, std::string_view why);

glm::dvec3 toDouble(const glm::vec3& v);
// Widens a box by a little more than the float rounding of the primitive's
// own points (a few ulps of its coordinates and of its size). The ray-box
// test widens its far distance too (objects.h); a ray that only grazes a
// primitive's edge may still be pruned where a brute-force walk finds it.
PrimitiveBounds paddedBounds(glm::dvec3 lo, glm::dvec3 hi);
// The padded box of the points.
PrimitiveBounds boundsOfPoints(std::initializer_list<glm::dvec3> points);

}  // namespace spectrace
