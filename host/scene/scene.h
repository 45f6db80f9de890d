#pragma once
// Scene description, loaded from JSON and validated. All lengths in metres,
// powers in watts, wavelengths in nanometres, world coordinates in double.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "spectrum/spd.h"

namespace spectrace {

// Every message names the file, the field (as a JSON pointer such as
// /lights/2/power_w) and what is wrong.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct SpectrumRange {
  double minNm = 360.0;
  double maxNm = 830.0;
  int bins = 94;
  double binWidthNm() const { return (maxNm - minNm) / bins; }
};

enum class LightType : uint32_t { Point = 0, Spot = 1, Disk = 2, Rect = 3, Laser = 4 };
const char* lightTypeName(LightType type);

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
  std::string spdLabel;           // "D65", "blackbody 2700 K", "lamp.csv", ...
  Spd spd;                        // resolved spectrum (relative units)
  std::string name;               // optional "name" from the file; empty when absent
};

struct Pinhole {
  double distanceM = 0.0;
  double radiusM = 0.0;
};

struct Camera {
  glm::dvec3 position{0.0};
  glm::dvec3 lookAt{0.0, 0.0, 1.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double sensorWidthM = 0.036;
  double sensorHeightM = 0.024;
  int pixelsX = 360;
  int pixelsY = 240;
  std::optional<Pinhole> pinhole;
  double exposureS = 1.0;
};

struct RenderSettings {
  uint64_t beams = 10'000'000;
  uint64_t seed = 1;
};

struct Scene {
  SpectrumRange spectrum;
  Camera camera;
  std::vector<Light> lights;
  RenderSettings render;
  std::string observer = "CIE1931_2";
  std::filesystem::path sourcePath;  // empty for scenes built in code
  std::string sourceSha256;          // hex digest of the file's bytes
};

// Reads, parses and validates a scene file. Relative CSV paths resolve
// against the scene file's folder.
Scene loadScene(const std::filesystem::path& file);
// Checks the invariants of a scene built in code (the loader enforces them
// for files, with the JSON field of each value): finite coordinates, a
// camera with a viewing direction and an up vector off it, and lights with
// a non-zero direction, positive size, cone in (0, 180] degrees, and finite
// power >= 0. Throws SceneError "<file or <scene>>: <field>: <what>".
void validateScene(const Scene& scene);

// Parses JSON text; `file` is used for messages and relative paths.
Scene parseScene(const std::string& jsonText, const std::filesystem::path& file);
// Lowercase hex SHA-256 of `bytes` (OpenSSL EVP), as in Scene::sourceSha256.
std::string sceneSha256Hex(std::string_view bytes);

}  // namespace spectrace
