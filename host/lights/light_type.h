#pragma once
// One unit per light type: everything the host knows about a type (its JSON
// keys, checks, device record, reachability, aiming) lives in its own file,
// lights/<type>_light.cpp, beside the kernel of the same stem in
// shaders/lights/. They are listed once, in host/lights/CMakeLists.txt
// (spectrace_unit_table), from which light_types.cpp builds the table.
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "camera/camera.h"
#include "device_data/scene_data.h"
#include "device_shared.h"
#include "json/json_fields.h"
#include "lights/light.h"

namespace spectrace {

// A light's placement in the camera frame (sensor centre at the origin,
// looking along +z; beams are counted travelling towards -z).
struct LightFrame {
  glm::dvec3 position;   // point/spot/laser origin, disk/rect centre
  glm::dvec3 axis;       // unit emission axis (spot/laser direction, disk/rect normal)
  glm::dvec3 tangent;    // with bitangent, an orthonormal frame about the axis
  glm::dvec3 bitangent;
};

// The sphere every counted beam passes through: the camera model's
// entrance (camera.h, EntranceSphere), widened by the kernel's slack. See
// lights/light_shared.h on aiming.
struct AimTarget {
  glm::dvec3 centre;
  double radius;
  // SPECTRACE_AIM_SLACK (shaders/beam_math.h): the sine by which aimed
  // cones are widened so float rounding cannot leave a countable direction out.
  double slack;
};

// Where a traced light can put beams on the sensor, conservatively: its
// emission points (corners of a convex region holding them, in the camera
// frame), and for a collimated light (a laser) its beam; the camera's model
// turns it into a region of the sensor (pixel windows).
using LightReach = EmitterReach;

// How a unit's `validate` reports a problem: throws SceneError naming the
// light's field (`key` relative to the light, e.g. "cone_deg", "size_m/0").
class LightFieldCheck {
 public:
  virtual ~LightFieldCheck() = default;
  [[noreturn]] virtual void fail(const std::string& key, const std::string& what) const = 0;
  // For "(got ...)": the value as the scene file wrote it when the scene came
  // from a file that has `key`, else `fallback`.
  virtual std::string got(const std::string& key, double fallback) const = 0;
  virtual std::string got(const std::string& key, const glm::dvec3& fallback) const = 0;
};

struct LightTypeUnit {
  LightType type;
  const char* name;  // "point", "spot", ... (the JSON "type")
  // The type's own JSON keys, besides the common type, name, power_w, spd.
  json_fields::Keys keys;
  const char* positionKey;   // the key Light::position is read from
  const char* directionKey;  // the key Light::direction is read from; nullptr: none (point)
  // The light's frame takes its tangent from Light::uAxis (rect); otherwise
  // any perpendicular of the axis will do (the type is symmetric about it).
  bool tangentFromUAxis;
  // Aimed beams carry varying weights, so counts need fractional units
  // (device::kWeightUnitsFractional).
  bool aimedWeightsVary;
  // Given as an object's "emission" rather than in "lights" (never read by
  // `parse`, not a "type" a light may name).
  bool onObject = false;

  // Reads the type's keys of the light object `v` at `ptr` into `light`
  // (types only: value ranges are `validate`'s).
  void (*parse)(const json_fields::Source& c, const json_fields::Json& v, const std::string& ptr, Light& light);
  // The type's semantic checks (the common ones are validateScene's).
  void (*validate)(const Light& light, const LightFieldCheck& check);
  // Fills the record's type parameters (in the camera `frame`): param0, param1, and whatever else
  // the type needs appended to the scene data (dataFirst, dataWords).
  void (*pack)(const Light& light, const CameraFrame& frame, device::LightRecord& record, SceneData& data);
  // Why the light can never put a beam on the sensor, or "" when it might.
  std::string (*unreachableBecause)(const Light& light, const LightFrame& frame, const Camera& camera);
  // Fills the record's aim fields when aiming helps and returns the largest
  // weight w_max; returns 1 (and leaves aimed = 0) otherwise. Needs pack first.
  double (*aim)(const Light& light, const LightFrame& frame, const AimTarget& target, device::LightRecord& record);
  LightReach (*reach)(const Light& light, const LightFrame& frame);
};

const LightTypeUnit& lightTypeUnit(LightType type);
// nullptr for an unknown name.
const LightTypeUnit* lightTypeUnitNamed(std::string_view name);
// Every unit, in LightType order.
const std::vector<const LightTypeUnit*>& lightTypeUnits();

}  // namespace spectrace
