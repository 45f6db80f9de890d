#pragma once
// The lens system camera model (camera/lens_system_camera.cpp): real
// surfaces from a prescription, traced beam by beam at each beam's own
// wavelength.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "camera/camera.h"
#include "camera/lens_prescription.h"
#include "json/json_fields.h"

namespace spectrace {

struct LensSystem {
  LensPrescription prescription;  // the last thickness solved when focusDistanceM is set
  std::optional<double> focusDistanceM;
  std::filesystem::path file;  // the lens file it came from; empty when inline
  // Where its messages point: the file (or the scene) and its surfaces'
  // JSON pointer, or in a pbrt table each surface's line.
  json_fields::Source source;
  std::string surfacesPtr;
  std::vector<int> tableLines;
  // "/camera/lens/surfaces/2/medium", or "line 9 (index)" in a table.
  std::string fieldOf(size_t surface, const std::string& key) const;
  // Where a message about the surfaces as a whole points:
  // "/camera/lens/surfaces", or in a table "its surface lines".
  std::string surfacesField() const;
  // How a message tells the reader to mark the stop in this format.
  std::string howToMarkTheStop() const;
};

std::shared_ptr<const CameraModel> lensSystemModel(LensSystem lens);
// The camera's lens system, or null when its model is another.
const LensSystem* lensSystemOf(const Camera& camera);

}  // namespace spectrace
