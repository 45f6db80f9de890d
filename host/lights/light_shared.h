#pragma once
// Helpers several light units share: frame and float rounding rules,
// reading placement keys, the reach of a flat emitter, and the aiming rules
// of cones (point, spot) and Lambertian area lights (disk, rect).
//
// Aimed sampling. Every counted beam passes through the target sphere
// (AimTarget). A light whose beams can be drawn only towards that sphere gets
// aimed = 1 and these parameters; each beam's weight is then (emission
// density) / (sampling density), and the light's largest weight w_max is
// folded into its selection probability (power x w_max), so the shader's
// weight ratio, weight / w_max, lies in [0, 1]:
// - point: uniform in the cone of half angle a holding the sphere, with
//   h = 1 - cos a: weight = (1 / 4 pi) / (1 / 2 pi h) = h / 2, for every beam;
// - spot (cone h_s = param0), when h < h_s: weight h / h_s inside the spot's
//   cone, 0 outside;
// - laser: origins uniform over the disk of radius rho around the target's
//   projection along the beam, when rho < R: weight rho^2 / R^2 inside the
//   laser's cross-section, 0 outside;
// - disk, rect: per origin, uniform in the cone holding the sphere (h from
//   that origin) when 2h < 1: weight cos(theta) / pi / (1 / 2 pi h) =
//   2 h cos(theta); w_max bounds 2h over the emitter from its closest point.
// Cones are widened by AimTarget::slack (SPECTRACE_AIM_SLACK) so float rounding
// cannot leave a countable direction outside them, and the values the shader
// samples with are the float values the weights are computed from.
#include <string>

#include <glm/vec3.hpp>

#include "lights/light_type.h"
#include "spectrum/alias_table.h"

namespace spectrace {

glm::vec3 toFloat(const glm::dvec3& v);
// Any unit vector perpendicular to `n` (Duff et al. 2017, branchless ONB).
glm::dvec3 perpendicular(const glm::dvec3& n);
// Default tangent for an axis: normalize(cross(pick, axis)) with pick = world
// Y (0, 1, 0), or world X (1, 0, 0) when |axis.y| > 0.9 (nearly vertical
// axes), so the tangent is never degenerate. For a rect facing -z this gives
// u = (-1, 0, 0), for one facing +z u = (1, 0, 0).
glm::dvec3 defaultTangent(const glm::dvec3& axis);
// 1 - cos(a) from sin(a) = s <= 1, without cancellation.
double oneMinusCosFromSin(double s);
// The float nearest above x (the shader must sample a cone at least this wide).
float floatAtLeast(double x);

// Reads the unit's position key (a point within kMaxCoordinateM) and, when it
// has one, its direction key (a unit vector) into `light`.
void parsePlacement(const LightTypeUnit& unit, const json_fields::Source& c, const json_fields::Json& v,
                    const std::string& ptr, Light& light);
// Appends an alias table's columns to the scene data, four words each
// (threshold low, high, alias, 0), as the kernel's sceneAliasLookup reads
// them; returns the offset of the first.
uint32_t appendAliasColumns(const AliasTable& table, SceneData& data);

// "must be a length in metres, > 0 and <= 1e+12 (got ...)" unless `value` is.
void checkLength(const LightFieldCheck& check, const std::string& key, double value, const std::string& extra = "");

// "it lies behind <the plane>" when no emission point (the highest at
// `position.z + extent`) lies beyond the sensor or aperture plane, else "".
std::string behindPlaneBecause(double highestZ, const Camera& camera);

// The corners of the rectangle of half extents u (along the tangent) and v
// (along the bitangent) about the light's position.
LightReach flatReach(const LightFrame& frame, double u, double v);

// Point and spot: beams uniform in the cone about the target sphere when it
// is narrower than the emission (1 - cos of its half angle `emissionSpread`:
// 2 for a point light, the spot's param0).
double aimCone(const LightFrame& frame, const AimTarget& target, double emissionSpread, device::LightRecord& record);

// Disk and rect: the target's centre relative to the emitter, in its frame.
struct AreaAimGeometry {
  double normal;  // along the axis
  double u, v;    // along tangent and bitangent
};
AreaAimGeometry areaAimGeometry(const LightFrame& frame, const AimTarget& target);
// Lambertian emitter whose closest point to the target's centre is at
// sqrt(normal^2 + outside2): aimed when every origin sees a narrow cone.
double aimLambertian(double normal, double outside2, const AimTarget& target, device::LightRecord& record);

}  // namespace spectrace
