#pragma once
// The camera as a scene describes it: a sensor, optionally behind a pinhole.
// Lengths in metres, world coordinates in double.
#include <optional>

#include <glm/vec3.hpp>

namespace spectrace {

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

}  // namespace spectrace
