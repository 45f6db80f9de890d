// The one table of camera models with a key of their own.
#include "camera/camera_types.h"

namespace spectrace {

// Each defined in its own unit, camera/<model>_camera.cpp, listed in
// host/camera/CMakeLists.txt (spectrace_unit_table).
#include "camera_units.inc"

const std::vector<const CameraTypeUnit*>& cameraTypeUnits() {
  static const std::vector<const CameraTypeUnit*> units = {SPECTRACE_CAMERA_UNITS};
  return units;
}

}  // namespace spectrace
