// Rect light: a Lambertian rectangle, size_m[0] along u_axis and size_m[1]
// across, emitting on the side its normal points to.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "camera/world_limits.h"
#include "lights/light_shared.h"

namespace spectrace {

const LightTypeUnit& rectLightUnit();  // below; the table is lights/light_types.cpp

namespace {

namespace jf = json_fields;

const char* kNeedsArea = "; a rect light needs a non-zero area";

void parse(const jf::Source& c, const jf::Json& v, const std::string& ptr, Light& light) {
  parsePlacement(rectLightUnit(), c, v, ptr, light);
  const std::string sp = jf::child(ptr, "size_m");
  const jf::Json& size = jf::require(c, v, ptr, "size_m", " ([width along u_axis, height], in metres)");
  if (!size.is_array() || size.size() != 2)
    c.fail(sp, fmt::format("must be an array of 2 numbers > 0 [width, height] (got {})", jf::describe(size)));
  for (size_t i = 0; i < 2; ++i) {
    const jf::Json& e = size[i];
    if (!e.is_number() || !std::isfinite(e.get<double>()))
      c.fail(jf::child(sp, i), fmt::format("must be a length in metres, > 0 and <= {:g} (got {}){}", kMaxCoordinateM,
                                           jf::describe(e), kNeedsArea));
    light.sizeM[int(i)] = e.get<double>();
  }
  if (auto* u = jf::find(v, "u_axis")) {
    // Orthogonalised against the normal; an axis along the normal is kept
    // as it is, for validate to reject.
    const glm::dvec3 axis = jf::getDirection(c, *u, jf::child(ptr, "u_axis"));
    const glm::dvec3 ortho = axis - light.direction * glm::dot(light.direction, axis);
    const auto unit = jf::safeNormalize(ortho);
    light.uAxis = glm::length(glm::cross(axis, light.direction)) < kCollinearEps || !unit ? axis : *unit;
  } else {
    light.uAxis = defaultTangent(light.direction);
  }
}

void validate(const Light& light, const LightFieldCheck& check) {
  for (int i = 0; i < 2; ++i) checkLength(check, "size_m/" + std::to_string(i), light.sizeM[i], kNeedsArea);
  if (!(light.sizeM.x * light.sizeM.y > 0.0) || !std::isfinite(light.sizeM.x * light.sizeM.y))
    check.fail("size_m", fmt::format("the rect's area {} x {} m² is not a positive finite number",
                                     jf::fmtNum(light.sizeM.x), jf::fmtNum(light.sizeM.y)));
  const glm::dvec3& u = light.uAxis;
  if (!(std::isfinite(u.x) && std::isfinite(u.y) && std::isfinite(u.z))) check.fail("u_axis", "must be finite");
  const auto axis = jf::safeNormalize(u);
  if (!axis) check.fail("u_axis", fmt::format("must not be zero-length (got {})", check.got("u_axis", u)));
  const auto normal = jf::safeNormalize(light.direction);
  if (!normal || glm::length(glm::cross(*axis, *normal)) < kCollinearEps)
    check.fail("u_axis", fmt::format("{} is parallel to the normal; u_axis must lie (roughly) in the rect's plane",
                                     check.got("u_axis", u)));
}

void pack(const Light& light, const CameraFrame&, device::LightRecord& record, SceneData&) {
  record.param0 = float(light.sizeM.x);
  record.param1 = float(light.sizeM.y);
}

std::string unreachableBecause(const Light& light, const LightFrame& frame, const Camera& camera) {
  const double extent =
      0.5 * (light.sizeM.x * std::abs(frame.tangent.z) + light.sizeM.y * std::abs(frame.bitangent.z));
  if (std::string behind = behindPlaneBecause(frame.position.z + extent, camera); !behind.empty()) return behind;
  if (!(frame.axis.z < 1.0)) return "it faces away from the camera";
  return "";
}

double aim(const Light& light, const LightFrame& frame, const AimTarget& target, device::LightRecord& record) {
  const AreaAimGeometry g = areaAimGeometry(frame, target);
  const double bu = std::max(0.0, std::abs(g.u) - 0.5 * light.sizeM.x);
  const double bv = std::max(0.0, std::abs(g.v) - 0.5 * light.sizeM.y);
  return aimLambertian(g.normal, bu * bu + bv * bv, target, record);
}

LightReach reach(const Light& light, const LightFrame& frame) {
  return flatReach(frame, 0.5 * light.sizeM.x, 0.5 * light.sizeM.y);
}

}  // namespace

const LightTypeUnit& rectLightUnit() {
  static const LightTypeUnit unit{
      .type = LightType::Rect,
      .name = "rect",
      .keys = {"center", "normal", "size_m", "u_axis"},
      .positionKey = "center",
      .directionKey = "normal",
      .tangentFromUAxis = true,
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
