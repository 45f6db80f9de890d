#pragma once
// The thin lens camera model (camera/thin_lens_camera.cpp): an ideal thin
// lens, a disk of radius `apertureRadiusM` on the view axis, focused at
// `focusDistanceM` in front of it.
#include <memory>

#include "camera/camera.h"

namespace spectrace {

struct ThinLens {
  double focalLengthM = 0.0;
  double apertureRadiusM = 0.0;
  double focusDistanceM = 0.0;
  // The lens's distance s in front of the sensor: 1/f = 1/d + 1/s.
  double lensDistanceM() const { return focalLengthM * focusDistanceM / (focusDistanceM - focalLengthM); }
};

std::shared_ptr<const CameraModel> thinLensModel(const ThinLens& lens);
// The camera's thin lens, or null when its model is another.
const ThinLens* thinLensOf(const Camera& camera);

}  // namespace spectrace
