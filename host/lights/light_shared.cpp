#include "lights/light_shared.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "camera/world_limits.h"

namespace spectrace {

namespace jf = json_fields;

glm::vec3 toFloat(const glm::dvec3& v) { return glm::vec3(v); }

glm::dvec3 perpendicular(const glm::dvec3& n) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  return {1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x};
}

glm::dvec3 defaultTangent(const glm::dvec3& axis) {
  glm::dvec3 pick = std::abs(axis.y) > 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
  return glm::normalize(glm::cross(pick, axis));
}

double oneMinusCosFromSin(double s) { return s * s / (1.0 + std::sqrt(std::max(0.0, 1.0 - s * s))); }

float floatAtLeast(double x) {
  float f = float(x);
  return double(f) < x ? std::nextafter(f, INFINITY) : f;
}

void parsePlacement(const LightTypeUnit& unit, const jf::Source& c, const jf::Json& v, const std::string& ptr,
                    Light& light) {
  light.position = jf::getPoint(c, jf::require(c, v, ptr, unit.positionKey), jf::child(ptr, unit.positionKey),
                                kMaxCoordinateM);
  if (unit.directionKey)
    light.direction = jf::getDirection(c, jf::require(c, v, ptr, unit.directionKey), jf::child(ptr, unit.directionKey));
}

void checkLength(const LightFieldCheck& check, const std::string& key, double value, const std::string& extra) {
  if (!(std::isfinite(value) && value > 0.0 && value <= kMaxCoordinateM))
    check.fail(key, fmt::format("must be a length in metres, > 0 and <= {:g} (got {}){}", kMaxCoordinateM,
                                check.got(key, value), extra));
}

uint32_t appendAliasColumns(const AliasTable& table, SceneData& data) {
  const auto first = uint32_t(data.words().size());
  for (const device::AliasColumn& column : table.columns) {
    const uint32_t words[] = {uint32_t(column.threshold), uint32_t(column.threshold >> 32), column.alias, 0u};
    data.append(std::span<const uint32_t>(words));
  }
  return first;
}

std::string behindPlaneBecause(double highestZ, const Camera& camera) {
  if (!(highestZ > camera.model->frontZ())) return fmt::format("it lies behind {}", camera.model->frontName());
  return "";
}

LightReach flatReach(const LightFrame& frame, double u, double v) {
  LightReach reach;
  reach.centre = frame.position;
  reach.axis = frame.axis;
  for (double su : {-1.0, 1.0})
    for (double sv : {-1.0, 1.0})
      reach.corners.push_back(frame.position + frame.tangent * (su * u) + frame.bitangent * (sv * v));
  return reach;
}

double aimCone(const LightFrame& frame, const AimTarget& target, double emissionSpread, device::LightRecord& record) {
  const glm::dvec3 toCentre = target.centre - frame.position;
  const double distance = glm::length(toCentre);
  const double s = target.radius / distance + target.slack;
  if (!(s < 1.0)) return 1.0;  // inside or at the sphere: nothing to gain
  const float h = floatAtLeast(oneMinusCosFromSin(s));
  if (!(double(h) < emissionSpread)) return 1.0;
  const glm::dvec3 coneAxis = toCentre / distance;
  const glm::dvec3 coneTangent = perpendicular(coneAxis);
  record.aimed = 1;
  record.aimSpread = h;
  record.aimAxis = toFloat(coneAxis);
  record.aimTangent = toFloat(coneTangent);
  record.aimBitangent = toFloat(glm::cross(coneAxis, coneTangent));
  // Spot: sin^2 of the half angle the analog path samples (1 - cos = param0).
  const double hs = double(record.param0);
  record.aimAccept = float(hs * (2.0 - hs));
  return double(h) / emissionSpread;
}

AreaAimGeometry areaAimGeometry(const LightFrame& frame, const AimTarget& target) {
  const glm::dvec3 toCentre = target.centre - frame.position;
  return {glm::dot(toCentre, frame.axis), glm::dot(toCentre, frame.tangent), glm::dot(toCentre, frame.bitangent)};
}

double aimLambertian(double normal, double outside2, const AimTarget& target, device::LightRecord& record) {
  // The closest point of the emitter to the sphere's centre gives the
  // widest cone, so the largest 2h.
  const double closest = std::sqrt(normal * normal + outside2);
  const double s = target.radius / closest + target.slack;
  if (!(s * s < 0.5)) return 1.0;  // some origins see a wide cone: leave it analog
  // The shader evaluates 2h in float; 1e-4 covers that rounding.
  const double largest = std::min(1.0, 2.0 * oneMinusCosFromSin(s) * (1.0 + 1e-4));
  record.aimed = 1;
  record.aimWeightScale = float(1.0 / largest);
  return 1.0 / double(record.aimWeightScale);  // exactly the scale the shader uses
}

}  // namespace spectrace
