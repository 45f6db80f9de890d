// Disk light: a Lambertian disk of radius radius_m emitting on the side its
// normal points to.
#include <algorithm>
#include <cmath>

#include "camera/world_limits.h"
#include "lights/light_shared.h"

namespace spectrace {

const LightTypeUnit& diskLightUnit();  // below; the table is lights/light_types.cpp

namespace {

namespace jf = json_fields;

void parse(const jf::Source& c, const jf::Json& v, const std::string& ptr, Light& light) {
  parsePlacement(diskLightUnit(), c, v, ptr, light);
  light.radiusM = jf::getLength(c, jf::require(c, v, ptr, "radius_m"), jf::child(ptr, "radius_m"), kMaxCoordinateM);
  light.uAxis = defaultTangent(light.direction);
}

void validate(const Light& light, const LightFieldCheck& check) { checkLength(check, "radius_m", light.radiusM); }

void pack(const Light& light, const CameraFrame&, device::LightRecord& record, SceneData&) {
  record.param0 = float(light.radiusM);
}

std::string unreachableBecause(const Light& light, const LightFrame& frame, const Camera& camera) {
  // The rim reaches highest where it tilts towards +z.
  const double extent = light.radiusM * std::sqrt(std::max(0.0, 1.0 - frame.axis.z * frame.axis.z));
  if (std::string behind = behindPlaneBecause(frame.position.z + extent, camera); !behind.empty()) return behind;
  if (!(frame.axis.z < 1.0)) return "it faces away from the camera";
  return "";
}

double aim(const Light& light, const LightFrame& frame, const AimTarget& target, device::LightRecord& record) {
  const AreaAimGeometry g = areaAimGeometry(frame, target);
  const double beyond = std::max(0.0, std::hypot(g.u, g.v) - light.radiusM);
  return aimLambertian(g.normal, beyond * beyond, target, record);
}

// The disk's square.
LightReach reach(const Light& light, const LightFrame& frame) { return flatReach(frame, light.radiusM, light.radiusM); }

}  // namespace

const LightTypeUnit& diskLightUnit() {
  static const LightTypeUnit unit{
      .type = LightType::Disk,
      .name = "disk",
      .keys = {"center", "normal", "radius_m"},
      .positionKey = "center",
      .directionKey = "normal",
      .tangentFromUAxis = false,
      .aimedWeightsVary = true,
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
