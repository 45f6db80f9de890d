#pragma once
// The one exception for a scene that cannot be used. It lives in the lowest
// module, beside the JSON field errors, so the camera and lights modules can
// throw it without depending on the scene module above them.
#include <stdexcept>

namespace spectrace {

// Every message names the file, the field (as a JSON pointer such as
// /lights/2/power_w) and what is wrong.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace spectrace
