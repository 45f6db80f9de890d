// The one table of camera models with a key of their own.
#include "camera/camera_types.h"

namespace spectrace {

// Each defined in its own unit, camera/<kind>_camera.cpp.
const CameraTypeUnit& pinholeCameraUnit();

const std::vector<const CameraTypeUnit*>& cameraTypeUnits() {
  static const std::vector<const CameraTypeUnit*> units = {&pinholeCameraUnit()};
  return units;
}

}  // namespace spectrace
