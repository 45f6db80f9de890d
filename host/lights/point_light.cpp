// Point light: isotropic emission from one point.
#include "lights/light_shared.h"

namespace spectrace {

const LightTypeUnit& pointLightUnit();  // below; the table is lights/light_types.cpp

namespace {

namespace jf = json_fields;

void parse(const jf::Source& c, const jf::Json& v, const std::string& ptr, Light& light) {
  parsePlacement(pointLightUnit(), c, v, ptr, light);
}

void validate(const Light&, const LightFieldCheck&) {}

void pack(const Light&, const CameraFrame&, device::LightRecord&, SceneData&) {}

std::string unreachableBecause(const Light&, const LightFrame& frame, const Camera& camera) {
  return behindPlaneBecause(frame.position.z + 0.0, camera);
}

double aim(const Light&, const LightFrame& frame, const AimTarget& target, device::LightRecord& record) {
  return aimCone(frame, target, 2.0, record);  // the whole sphere: 1 - cos(pi) = 2
}

LightReach reach(const Light&, const LightFrame& frame) { return flatReach(frame, 0.0, 0.0); }

}  // namespace

const LightTypeUnit& pointLightUnit() {
  static const LightTypeUnit unit{
      .type = LightType::Point,
      .name = "point",
      .keys = {"position"},
      .positionKey = "position",
      .directionKey = nullptr,
      .tangentFromUAxis = false,
      .aimedWeightsVary = false,
      .parse = parse,
      .validate = validate,
      .pack = pack,
      .unreachableBecause = unreachableBecause,
      .aim = aim,
      .reach = reach,
  };
  return unit;
}

}  // namespace spectrace
