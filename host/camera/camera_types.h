#pragma once
// The kinds of camera model (camera.h): one unit each,
// camera/<kind>_camera.cpp, listed once in host/camera/CMakeLists.txt
// (spectrace_unit_table), from which cameraTypeUnits() is built.
#include <memory>
#include <string>
#include <vector>

#include "camera/camera.h"
#include "json/json_fields.h"

namespace spectrace {

struct CameraTypeUnit {
  // The key of the camera object that holds this model ("pinhole"); the
  // bare sensor, which has none, is not in the table.
  const char* key;
  // Reads the object `v` at `ptr` (types only: value ranges are the model's
  // validate).
  std::shared_ptr<const CameraModel> (*parse)(const json_fields::Source& c, const json_fields::Json& v,
                                              const std::string& ptr);
};

// Every camera model with a key of its own, in kernel id order.
const std::vector<const CameraTypeUnit*>& cameraTypeUnits();

}  // namespace spectrace
