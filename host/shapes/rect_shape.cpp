// A flat rectangle: "center", "normal", "size_m" [along u_axis, across] and
// an optional "u_axis" (as for rect lights). One rect primitive.
#include <cmath>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "camera/world_limits.h"
#include "lights/light_shared.h"
#include "shapes/shape_shared.h"

namespace spectrace {

namespace {

namespace jf = json_fields;

// "size_m": [along u_axis, across], each a length.
glm::dvec2 parseSize(const jf::Source& c, const jf::Json& v, const std::string& p) {
  const std::string sp = jf::child(p, "size_m");
  const jf::Json& size = jf::require(c, v, p, "size_m", " ([width along u_axis, height], in metres)");
  if (!size.is_array() || size.size() != 2)
    c.fail(sp, fmt::format("must be an array of 2 lengths > 0 [width, height] (got {})", jf::describe(size)));
  return {jf::getLength(c, size[0], jf::child(sp, size_t(0)), kMaxCoordinateM),
          jf::getLength(c, size[1], jf::child(sp, size_t(1)), kMaxCoordinateM)};
}

void parse(const jf::Source& c, const jf::Json& v, const std::string& p, const ShapeReading&, Shape& shape) {
  shape.center = parseCenter(c, v, p);
  parseNormal(c, v, p, shape);
  shape.sizeM = parseSize(c, v, p);
  if (auto* u = jf::find(v, "u_axis")) {
    // Orthogonalised against the normal, as for rect lights; an axis
    // along the normal is kept as it is, for validate to refuse.
    const glm::dvec3 axis = jf::getDirection(c, *u, jf::child(p, "u_axis"));
    const glm::dvec3 ortho = axis - shape.normal * glm::dot(shape.normal, axis);
    const auto unit = jf::safeNormalize(ortho);
    shape.uAxis = glm::length(glm::cross(axis, shape.normal)) < kCollinearEps || !unit ? axis : *unit;
  }
}

void validate(const Shape& shape, const ShapeFieldCheck& check) {
  checkShapePoint(check, "center", shape.center);
  checkShapeUnitVector(check, "normal", shape.normal);
  checkShapeLength(check, "size_m/0", shape.sizeM.x);
  checkShapeLength(check, "size_m/1", shape.sizeM.y);
  const glm::dvec3& u = shape.uAxis;
  if (!allFinite(u) || !jf::safeNormalize(u)) check.fail("u_axis", "must be finite and not zero-length");
  if (glm::length(glm::cross(*jf::safeNormalize(u), shape.normal)) < kCollinearEps)
    check.fail("u_axis", fmt::format("{} is parallel to the normal; u_axis must lie (roughly) in the rect's plane",
                                     check.got("u_axis", u)));
  if (!(std::abs(glm::length(u) - 1.0) <= kShapeUnitEps && std::abs(glm::dot(u, shape.normal)) <= kShapeUnitEps))
    check.fail("u_axis",
               fmt::format("must be a unit vector perpendicular to the normal (got {})", check.got("u_axis", u)));
}

std::string notClosedBecause(const Shape&, std::string_view material) {
  return needsClosedShape(material, " (a rect has no inside)");
}

void place(const Shape& shape, const CameraFrame& frame, uint32_t material, std::vector<PlacedPrimitive>& out) {
  const glm::dvec3 centre = frame.pointToLocal(shape.center);
  const glm::dvec3 n = glm::normalize(frame.directionToLocal(shape.normal));
  glm::dvec3 u = frame.directionToLocal(shape.uAxis);
  u = glm::normalize(u - n * glm::dot(u, n));
  const glm::dvec3 v = glm::cross(n, u);  // u x v = n
  PlacedPrimitive placed;
  device::Primitive& p = placed.primitive;
  p.material = material;
  p.type = device::kPrimitiveRect;
  p.a = toFloat(centre);
  p.b = toFloat(u * (0.5 * shape.sizeM.x));
  p.c = toFloat(v * (0.5 * shape.sizeM.y));
  const glm::dvec3 a = toDouble(p.a), b = toDouble(p.b), c = toDouble(p.c);
  placed.bounds = boundsOfPoints({a + b + c, a + b - c, a - b + c, a - b - c});
  out.push_back(placed);
}

}  // namespace

const ShapeTypeUnit& rectShapeUnit() {
  static const ShapeTypeUnit unit{
      .type = ShapeType::Rect,
      .name = "rect",
      .keys = {"center", "normal", "u_axis", "size_m"},
      .parse = parse,
      .validate = validate,
      .notClosedBecause = notClosedBecause,
      .place = place,
  };
  return unit;
}

}  // namespace spectrace
