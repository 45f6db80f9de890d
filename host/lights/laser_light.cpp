// Laser: a collimated beam of radius radius_m leaving a disk about its
// origin along its direction.
#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "camera/world_limits.h"
#include "lights/light_shared.h"

namespace spectrace {

const LightTypeUnit& laserLightUnit();  // below; the table is lights/light_types.cpp

namespace {

namespace jf = json_fields;

void parse(const jf::Source& c, const jf::Json& v, const std::string& ptr, Light& light) {
  parsePlacement(laserLightUnit(), c, v, ptr, light);
  light.radiusM = jf::getLength(c, jf::require(c, v, ptr, "radius_m"), jf::child(ptr, "radius_m"), kMaxCoordinateM);
  light.uAxis = defaultTangent(light.direction);
}

void validate(const Light& light, const LightFieldCheck& check) { checkLength(check, "radius_m", light.radiusM); }

void pack(const Light& light, const CameraFrame&, device::LightRecord& record, SceneData&) {
  record.param0 = float(light.radiusM);
}

std::string unreachableBecause(const Light& light, const LightFrame& frame, const Camera& camera) {
  const glm::dvec3& position = frame.position;
  const glm::dvec3& axis = frame.axis;
  const double extent = light.radiusM * std::sqrt(std::max(0.0, 1.0 - axis.z * axis.z));
  if (std::string behind = behindPlaneBecause(position.z + extent, camera); !behind.empty()) return behind;
  if (!(axis.z < 0.0)) return "its beam points away from the camera";
  // The beam's footprint in the camera's front plane: the disk's centre
  // moved along the axis, inside a circle of radius R / |axis.z| (the
  // ellipse's semi-major axis).
  const double t = (position.z - camera.model->frontZ()) / -axis.z;
  const glm::dvec2 centre(position.x + t * axis.x, position.y + t * axis.y);
  return camera.model->beamMissesBecause(camera, centre, light.radiusM / -axis.z);
}

double aim(const Light& light, const LightFrame& frame, const AimTarget& target, device::LightRecord& record) {
  // The beam runs along the axis, so only origins within the sphere's
  // radius of its centre's projection onto the laser's plane can reach it;
  // the slack covers the float rounding of origins and hit points.
  const glm::dvec3 toCentre = target.centre - frame.position;
  const double slack =
      1e-6 * (target.radius + glm::length(frame.position) + glm::length(target.centre) + light.radiusM);
  const float rho = floatAtLeast(target.radius + slack);
  const double radius = double(record.param0);
  if (!(double(rho) < radius)) return 1.0;
  record.aimed = 1;
  record.aimSpread = rho;
  record.aimAxis =
      glm::vec3(float(glm::dot(toCentre, frame.tangent)), float(glm::dot(toCentre, frame.bitangent)), 0.0f);
  record.aimAccept = float(radius * radius);
  return (double(rho) * double(rho)) / (radius * radius);
}

LightReach reach(const Light& light, const LightFrame& frame) {
  LightReach reach = flatReach(frame, light.radiusM, light.radiusM);  // the disk's square
  reach.collimated = true;
  reach.radius = light.radiusM;
  return reach;
}

}  // namespace

const LightTypeUnit& laserLightUnit() {
  static const LightTypeUnit unit{
      .type = LightType::Laser,
      .name = "laser",
      .keys = {"origin", "direction", "radius_m"},
      .positionKey = "origin",
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
