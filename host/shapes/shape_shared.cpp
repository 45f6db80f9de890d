#include "shapes/shape_shared.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "camera/world_limits.h"
#include "lights/light_shared.h"

namespace spectrace {

namespace jf = json_fields;

glm::dvec3 parseCenter(const jf::Source& c, const jf::Json& v, const std::string& p) {
  return jf::getPoint(c, jf::require(c, v, p, "center"), jf::child(p, "center"), kMaxCoordinateM);
}

void parseNormal(const jf::Source& c, const jf::Json& v, const std::string& p, Shape& shape) {
  shape.normal = jf::getDirection(c, jf::require(c, v, p, "normal"), jf::child(p, "normal"));
  shape.uAxis = defaultTangent(shape.normal);
}

double parseRadius(const jf::Source& c, const jf::Json& v, const std::string& p) {
  return jf::getLength(c, jf::require(c, v, p, "radius_m"), jf::child(p, "radius_m"), kMaxCoordinateM);
}

bool allFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void checkShapePoint(const ShapeFieldCheck& check, const std::string& key, const glm::dvec3& p) {
  if (!allFinite(p)) check.fail(key, "must be finite");
  for (int i = 0; i < 3; ++i) {
    const std::string ik = key + "/" + std::to_string(i);
    if (std::abs(p[i]) > kMaxCoordinateM)
      check.fail(ik, fmt::format("must be a coordinate with magnitude <= {:g} m (got {})", kMaxCoordinateM,
                                 check.got(ik, p[i])));
  }
}

void checkShapeLength(const ShapeFieldCheck& check, const std::string& key, double value) {
  if (!(std::isfinite(value) && value > 0.0 && value <= kMaxCoordinateM))
    check.fail(key, fmt::format("must be a length in metres, > 0 and <= {:g} (got {})", kMaxCoordinateM,
                                check.got(key, value)));
}

void checkShapeUnitVector(const ShapeFieldCheck& check, const std::string& key, const glm::dvec3& v) {
  const double length = glm::length(v);
  if (!allFinite(v) || !(std::abs(length - 1.0) <= kShapeUnitEps))
    check.fail(key, fmt::format("must be a unit vector (got {}, of length {})", check.got(key, v), jf::fmtNum(length)));
}

std::string needsClosedShape(std::string_view material, std::string_view why) {
  return fmt::format("a {} needs a closed shape: a sphere or a closed mesh{}", material, why);
}

glm::dvec3 toDouble(const glm::vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }

PrimitiveBounds paddedBounds(glm::dvec3 lo, glm::dvec3 hi) {
  const double size = glm::length(hi - lo);
  for (int i = 0; i < 3; ++i) {
    const double magnitude = std::max(std::abs(lo[i]), std::abs(hi[i]));
    const double pad = 1e-6 * (magnitude + size) + 1e-30;
    lo[i] -= pad;
    hi[i] += pad;
  }
  return {lo, hi};
}

PrimitiveBounds boundsOfPoints(std::initializer_list<glm::dvec3> points) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const glm::dvec3& p : points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return paddedBounds(lo, hi);
}

}  // namespace spectrace
