// A flat disk: "center", "normal", "radius_m". One disk primitive.
#include <glm/geometric.hpp>

#include "lights/light_shared.h"
#include "shapes/shape_shared.h"

namespace spectrace {

namespace {

namespace jf = json_fields;

void parse(const jf::Source& c, const jf::Json& v, const std::string& p, const ShapeReading&, Shape& shape) {
  shape.center = parseCenter(c, v, p);
  parseNormal(c, v, p, shape);
  shape.radiusM = parseRadius(c, v, p);
}

void validate(const Shape& shape, const ShapeFieldCheck& check) {
  checkShapePoint(check, "center", shape.center);
  checkShapeUnitVector(check, "normal", shape.normal);
  checkShapeLength(check, "radius_m", shape.radiusM);
}

std::string notClosedBecause(const Shape&, std::string_view material) {
  return needsClosedShape(material, " (a disk has no inside)");
}

void place(const Shape& shape, const CameraFrame& frame, uint32_t material, std::vector<PlacedPrimitive>& out) {
  const glm::dvec3 centre = frame.pointToLocal(shape.center);
  const glm::dvec3 n = glm::normalize(frame.directionToLocal(shape.normal));
  PlacedPrimitive placed;
  device::Primitive& p = placed.primitive;
  p.material = material;
  p.type = device::kPrimitiveDisk;
  p.a = toFloat(centre);
  p.b = toFloat(n);
  p.c = glm::vec3(float(shape.radiusM * shape.radiusM), 0.0f, 0.0f);
  // A disk of radius r with unit normal n reaches r * sqrt(1 - n_i^2)
  // along axis i.
  const glm::dvec3 reach = shape.radiusM * glm::sqrt(glm::max(glm::dvec3(1.0) - n * n, glm::dvec3(0.0)));
  placed.bounds = paddedBounds(toDouble(p.a) - reach, toDouble(p.a) + reach);
  out.push_back(placed);
}

}  // namespace

const ShapeTypeUnit& diskShapeUnit() {
  static const ShapeTypeUnit unit{
      .type = ShapeType::Disk,
      .name = "disk",
      .keys = {"center", "normal", "radius_m"},
      .parse = parse,
      .validate = validate,
      .notClosedBecause = notClosedBecause,
      .place = place,
  };
  return unit;
}

}  // namespace spectrace
