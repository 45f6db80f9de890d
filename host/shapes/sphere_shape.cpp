// A sphere: "center", "radius_m". One sphere primitive; it bounds a solid,
// its normal facing outwards.
#include "lights/light_shared.h"
#include "shapes/shape_shared.h"

namespace spectrace {

namespace {

namespace jf = json_fields;

void parse(const jf::Source& c, const jf::Json& v, const std::string& p, const ShapeReading&, Shape& shape) {
  shape.center = parseCenter(c, v, p);
  shape.radiusM = parseRadius(c, v, p);
  shape.closed = true;
}

void validate(const Shape& shape, const ShapeFieldCheck& check) {
  checkShapePoint(check, "center", shape.center);
  checkShapeLength(check, "radius_m", shape.radiusM);
}

std::string notClosedBecause(const Shape&, std::string_view) { return ""; }

void place(const Shape& shape, const CameraFrame& frame, uint32_t material, std::vector<PlacedPrimitive>& out) {
  const glm::dvec3 centre = frame.pointToLocal(shape.center);
  PlacedPrimitive placed;
  device::Primitive& p = placed.primitive;
  p.material = material;
  p.type = device::kPrimitiveSphere;
  p.a = toFloat(centre);
  p.b = glm::vec3(float(shape.radiusM), float(shape.radiusM * shape.radiusM), 0.0f);
  placed.bounds = paddedBounds(toDouble(p.a) - shape.radiusM, toDouble(p.a) + shape.radiusM);
  out.push_back(placed);
}

}  // namespace

const ShapeTypeUnit& sphereShapeUnit() {
  static const ShapeTypeUnit unit{
      .type = ShapeType::Sphere,
      .name = "sphere",
      .keys = {"center", "radius_m"},
      .parse = parse,
      .validate = validate,
      .notClosedBecause = notClosedBecause,
      .place = place,
  };
  return unit;
}

}  // namespace spectrace
