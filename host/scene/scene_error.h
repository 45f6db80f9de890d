#pragma once
// The one exception for a scene that cannot be used (header only, so the
// camera and lights modules can throw it without linking the scene module).
#include <stdexcept>

namespace spectrace {

// Every message names the file, the field (as a JSON pointer such as
// /lights/2/power_w) and what is wrong.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace spectrace
