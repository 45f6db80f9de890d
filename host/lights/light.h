#pragma once
// A light as a scene describes it (world coordinates in double, metres,
// watts). What each type means, reads and packs is in its unit
// (lights/light_type.h).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <vector>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "camera/camera_frame.h"
#include "device_shared.h"
#include "lights/photometric_file.h"
#include "spectrum/spd.h"

namespace spectrace {

// LightType is defined in device_shared.h, numbered as the kernel numbers it.
inline constexpr uint32_t kLightTypeCount = device::kLightTypeCount;

// "point", "spot", ... (the unit's name).
const char* lightTypeName(LightType type);

// An object's surface that emits (an object's "emission"): the object's
// shape unit places its primitives, so this module needs no shape of its
// own (shapes sit above lights in the module graph).
struct EmittingSurface {
  // The object's primitives in a camera frame, as the BVH gets them.
  std::function<std::vector<device::Primitive>(const CameraFrame&)> place;
  glm::dvec3 boundsLo{0.0}, boundsHi{0.0};  // world axis-aligned box holding the surface
  bool twoSided = false;                     // emits from both faces (else along its normals)
  size_t objectIndex = 0;                    // the object's index in the scene's objects
};

struct Light {
  LightType type = LightType::Point;
  std::string label;  // JSON pointer of the light, e.g. "/lights/2", for messages
  // point/spot: `position`; laser: `origin`; disk/rect: `center`.
  glm::dvec3 position{0.0};
  // spot/laser: `direction`; disk/rect: `normal` (emitting side). Unit length.
  glm::dvec3 direction{0.0, 0.0, 1.0};
  // rect: unit vector along the first size component, perpendicular to
  // `direction`. From "u_axis" when given, else the derived default.
  glm::dvec3 uAxis{1.0, 0.0, 0.0};
  double coneHalfAngleDeg = 0.0;  // spot: `cone_deg` is the half angle
  double radiusM = 0.0;           // disk, laser
  glm::dvec2 sizeM{0.0};          // rect: full width (along uAxis) and height
  double powerW = 0.0;            // total radiant flux of the whole emission
  // power_lm when the file gave the luminous flux (powerW follows from it
  // and the spd's luminous efficacy); negative when it gave power_w.
  double powerLm = -1.0;
  std::string spdLabel;           // "D65", "blackbody 2700 K", "lamp.csv", ...
  std::filesystem::path spdFile;  // the CSV file the spd was read from (an input: never an output); else empty
  Spd spd;                        // resolved spectrum (relative units)
  std::string name;               // optional "name" from the file; empty when absent
  // photometric: the luminaire's table (read from photometryFile, an
  // input), and the world direction of its C = 0 half-plane, perpendicular
  // to `direction` (nadir); uAxis holds the same.
  std::shared_ptr<const PhotometricTable> photometry;
  std::filesystem::path photometryFile;
  // object: the emitting surface (its label is the object's
  // "/objects/<i>/emission"; position is its box's centre).
  std::shared_ptr<const EmittingSurface> surface;
};

}  // namespace spectrace
