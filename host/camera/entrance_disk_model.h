#pragma once
// What a camera model whose entrance is a disk on the view axis (the
// pinhole, the thin lens; the kernel's shaders/cameras/entrance_disk.h)
// gets from the disk alone: the front plane, aiming's sphere, the beams
// that miss it, where a light's beams can land, camera paths' entrance.
#include <optional>
#include <string>

#include "camera/camera.h"

namespace spectrace {

class EntranceDiskModel : public CameraModel {
 public:
  // A disk of radius `radiusM` at `distanceM` before the sensor's centre. A
  // beam through disk point A from a point at height h over the disk's
  // plane, offset P_xy from the axis, lands on the sensor at
  // A (k + D/h) - P_xy D/h: `k` is 1 for a pinhole, 1 - D/f for a lens.
  EntranceDiskModel(double distanceM, double radiusM, double k, const char* name)
      : distanceM_(distanceM), radiusM_(radiusM), k_(k), name_(name) {}

  double frontZ() const override { return distanceM_; }
  std::string beamMissesBecause(const Camera& camera, const glm::dvec2& centre, double reach) const override;
  EntranceSphere entranceSphere(const Camera& camera) const override;
  std::optional<SensorBox> reachOnSensor(const EmitterReach& emitter) const override;
  bool imageFlipped() const override { return true; }
  std::optional<double> cameraPathEntranceAreaM2() const override;
  double smallestEntranceSine() const override;

 protected:
  double radiusM() const { return radiusM_; }
  double k() const { return k_; }

 private:
  double distanceM_, radiusM_, k_;
  const char* name_;  // "pinhole", "thin lens": for messages
};

}  // namespace spectrace
