#include "film/pixel_window.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/vec2.hpp>

namespace spectrace {

// The bound:
// - Pinhole at distance D, radius r: a beam from P (height h = P.z - D > 0)
//   through the aperture point A hits H = A (1 + D/h) - P_xy D/h, inside the
//   disk about -P_xy D/h of radius r (1 + D/h). Over a convex emitter with
//   h > 0 throughout, -P_xy D/h stays in the hull of its corners' images
//   (a perspective map keeps segments straight), and 1 + D/h <= 1 + D/h_min.
// - Bare sensor: only lasers are bounded: the beam's footprint lies within
//   R / |a.z| of where its axis meets the sensor.
PixelWindow reachablePixelWindow(const Camera& camera, std::span<const LightReach> lights) {
  const PixelWindow whole{0, 0, uint32_t(camera.pixelsX), uint32_t(camera.pixelsY)};
  const double halfW = 0.5 * camera.sensorWidthM, halfH = 0.5 * camera.sensorHeightM;
  glm::dvec2 lo(INFINITY), hi(-INFINITY);  // sensor-plane bounds of every hit
  for (const LightReach& light : lights) {
    if (camera.pinhole) {
      const double d = camera.pinhole->distanceM, r = camera.pinhole->radiusM;
      double hMin = INFINITY;
      for (const glm::dvec3& p : light.corners) {
        const double h = p.z - d;
        if (!(h > 0.0)) return whole;  // part of the emitter at or behind the aperture plane
        hMin = std::min(hMin, h);
        const glm::dvec2 centre = -glm::dvec2(p.x, p.y) * (d / h);
        lo = glm::min(lo, centre);
        hi = glm::max(hi, centre);
      }
      const double blur = r * (1.0 + d / hMin);
      lo -= blur;
      hi += blur;
    } else {
      if (!light.collimated || !(light.axis.z < 0.0)) return whole;
      const double t = light.centre.z / -light.axis.z;
      const glm::dvec2 centre(light.centre.x + t * light.axis.x, light.centre.y + t * light.axis.y);
      const double extent = light.radius / -light.axis.z;
      lo = glm::min(lo, centre - extent);
      hi = glm::max(hi, centre + extent);
    }
  }
  if (!(std::isfinite(lo.x) && std::isfinite(lo.y) && std::isfinite(hi.x) && std::isfinite(hi.y))) return whole;
  // Sensor coordinates to pixel columns and rows (hitSensor: a pinhole image
  // is flipped upright), widened by a pixel for rounding.
  const double ppmX = camera.pixelsX / camera.sensorWidthM, ppmY = camera.pixelsY / camera.sensorHeightM;
  double colLo, colHi, rowLo, rowHi;
  if (camera.pinhole) {
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
