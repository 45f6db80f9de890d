// Spot light: uniform emission into a cone of half angle cone_deg about its
// direction.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "lights/light_shared.h"

namespace spectrace {

const LightTypeUnit& spotLightUnit();  // below; the table is lights/light_types.cpp

namespace {

namespace jf = json_fields;

std::string coneMessage(const std::string& got) {
  return fmt::format("must be a half angle in degrees, > 0 and <= 180 (got {})", got);
}

void parse(const jf::Source& c, const jf::Json& v, const std::string& ptr, Light& light) {
  parsePlacement(spotLightUnit(), c, v, ptr, light);
  const jf::Json& cone = jf::require(c, v, ptr, "cone_deg", " (half angle of the cone, in degrees)");
  if (!cone.is_number() || !std::isfinite(cone.get<double>()))
    c.fail(jf::child(ptr, "cone_deg"), coneMessage(jf::describe(cone)));
  light.coneHalfAngleDeg = cone.get<double>();
  light.uAxis = defaultTangent(light.direction);
}

void validate(const Light& light, const LightFieldCheck& check) {
  if (!(light.coneHalfAngleDeg > 0.0 && light.coneHalfAngleDeg <= 180.0))
    check.fail("cone_deg", coneMessage(check.got("cone_deg", light.coneHalfAngleDeg)));
}

void pack(const Light& light, const CameraFrame&, device::LightRecord& record, SceneData&) {
  // 1 - cos(a) = 2 sin^2(a/2): no cancellation for narrow cones.
  const double half = light.coneHalfAngleDeg * M_PI / 180.0;
  const double s = std::sin(0.5 * half);
  record.param0 = float(2.0 * s * s);
}

std::string unreachableBecause(const Light& light, const LightFrame& frame, const Camera& camera) {
  if (std::string behind = behindPlaneBecause(frame.position.z + 0.0, camera); !behind.empty()) return behind;
  // Some direction in the cone points towards -z iff the angle between the
  // axis and -z is below 90 degrees plus the half angle.
  const double angle = std::acos(std::clamp(-frame.axis.z, -1.0, 1.0));
  if (!(angle < M_PI / 2 + light.coneHalfAngleDeg * M_PI / 180.0)) return "its cone points away from the camera";
  return "";
}

double aim(const Light&, const LightFrame& frame, const AimTarget& target, device::LightRecord& record) {
  return aimCone(frame, target, double(record.param0), record);
}

LightReach reach(const Light&, const LightFrame& frame) { return flatReach(frame, 0.0, 0.0); }

}  // namespace

const LightTypeUnit& spotLightUnit() {
  static const LightTypeUnit unit{
      .type = LightType::Spot,
      .name = "spot",
      .keys = {"position", "direction", "cone_deg"},
      .positionKey = "position",
      .directionKey = "direction",
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
