#include "camera/entrance_disk_model.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace spectrace {

std::string EntranceDiskModel::beamMissesBecause(const Camera&, const glm::dvec2& centre, double reach) const {
  if (!(glm::length(centre) < reach + radiusM_)) return std::string("its beam misses the ") + name_;
  return "";
}

EntranceSphere EntranceDiskModel::entranceSphere(const Camera&) const { return {{0.0, 0.0, distanceM_}, radiusM_}; }

// From P (height h = P.z - D > 0) the beams land inside the disk about
// -P_xy D/h of radius r |k + D/h|. Over a convex emitter with h > 0
// throughout, -P_xy D/h stays in the hull of its corners' images (a
// perspective map keeps segments straight), and the radius, monotone in
// 1/h, is largest at the least or the greatest height, both corners'.
std::optional<SensorBox> EntranceDiskModel::reachOnSensor(const EmitterReach& emitter) const {
  const double d = distanceM_;
  glm::dvec2 lo(INFINITY), hi(-INFINITY);
  double hMin = INFINITY, hMax = 0.0;
  for (const glm::dvec3& p : emitter.corners) {
    const double h = p.z - d;
    if (!(h > 0.0)) return std::nullopt;  // part of the emitter at or behind the disk's plane
    hMin = std::min(hMin, h);
    hMax = std::max(hMax, h);
    const glm::dvec2 centre = -glm::dvec2(p.x, p.y) * (d / h);
    lo = glm::min(lo, centre);
    hi = glm::max(hi, centre);
  }
  const double blur = radiusM_ * std::max(std::abs(k_ + d / hMin), std::abs(k_ + d / hMax));
  return SensorBox{lo - blur, hi + blur};
}

std::optional<double> EntranceDiskModel::cameraPathEntranceAreaM2() const { return M_PI * radiusM_ * radiusM_; }

// Ten times the slack (4e-7, shaders/beam_math.h: SPECTRACE_AIM_SLACK) by
// which float rounding widens aimed cones. Below it, whether a beam passes
// the disk is decided by the rounding of float positions and directions
// (about 6e-8 of the distance) rather than by the disk: a 1e-9 m pinhole
// at 1.1 m gave 85 times its irradiance, 1e-7 m 1.16.
double EntranceDiskModel::smallestEntranceSine() const { return 4.0e-6; }

}  // namespace spectrace
