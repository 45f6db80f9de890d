#include "film/pixel_window.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/vec2.hpp>

namespace spectrace {

// The bound: the union of what the camera's model says of each light
// (CameraModel::reachOnSensor: a pinhole bounds every light in front of its
// aperture, a bare sensor only lasers), turned into pixels.
PixelWindow reachablePixelWindow(const Camera& camera, std::span<const LightReach> lights) {
  const PixelWindow whole{0, 0, uint32_t(camera.pixelsX), uint32_t(camera.pixelsY)};
  const double halfW = 0.5 * camera.sensorWidthM, halfH = 0.5 * camera.sensorHeightM;
  glm::dvec2 lo(INFINITY), hi(-INFINITY);  // sensor-plane bounds of every hit
  for (const LightReach& light : lights) {
    const std::optional<SensorBox> box = camera.model->reachOnSensor(light);
    if (!box) return whole;
    lo = glm::min(lo, box->lo);
    hi = glm::max(hi, box->hi);
  }
  if (!(std::isfinite(lo.x) && std::isfinite(lo.y) && std::isfinite(hi.x) && std::isfinite(hi.y))) return whole;
  // Sensor coordinates to pixel columns and rows (hitSensor: an image
  // inverted on the sensor is flipped upright), widened by a pixel for
  // rounding.
  const double ppmX = camera.pixelsX / camera.sensorWidthM, ppmY = camera.pixelsY / camera.sensorHeightM;
  double colLo, colHi, rowLo, rowHi;
  if (camera.model->imageFlipped()) {
    colLo = (halfW - hi.x) * ppmX;
    colHi = (halfW - lo.x) * ppmX;
    rowLo = (lo.y + halfH) * ppmY;
    rowHi = (hi.y + halfH) * ppmY;
  } else {
    colLo = (lo.x + halfW) * ppmX;
    colHi = (hi.x + halfW) * ppmX;
    rowLo = (halfH - hi.y) * ppmY;
    rowHi = (halfH - lo.y) * ppmY;
  }
  const double maxCol = camera.pixelsX - 1, maxRow = camera.pixelsY - 1;
  const double c0 = std::clamp(std::floor(colLo) - 1.0, 0.0, maxCol), c1 = std::clamp(std::floor(colHi) + 1.0, 0.0, maxCol);
  const double r0 = std::clamp(std::floor(rowLo) - 1.0, 0.0, maxRow), r1 = std::clamp(std::floor(rowHi) + 1.0, 0.0, maxRow);
  return {uint32_t(c0), uint32_t(r0), uint32_t(c1 - c0) + 1, uint32_t(r1 - r0) + 1};
}

}  // namespace spectrace
