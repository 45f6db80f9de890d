#pragma once
// The pinhole camera model (camera/pinhole_camera.cpp): an aperture disk of
// radius `radiusM` at `distanceM` in front of the sensor's centre.
#include <memory>

#include "camera/camera.h"

namespace spectrace {

struct Pinhole {
  double distanceM = 0.0;
  double radiusM = 0.0;
};

std::shared_ptr<const CameraModel> pinholeModel(const Pinhole& pinhole);
// The camera's pinhole, or null when its model is another.
const Pinhole* pinholeOf(const Camera& camera);

}  // namespace spectrace
