#pragma once
// The camera's orthonormal frame, in double precision. All beam math runs in
// this frame (sensor centre at the origin, looking along +z), so a camera far
// from the world origin loses no float precision.
#include <glm/vec3.hpp>

#include "camera/camera.h"

namespace spectrace {

struct CameraFrame {
  glm::dvec3 origin;   // sensor centre in world coordinates
  glm::dvec3 right;    // image +x
  glm::dvec3 up;       // image +y
  glm::dvec3 forward;  // viewing direction (towards look_at)

  // Throws SceneError when look_at == position or up is parallel to the view.
  static CameraFrame fromCamera(const Camera& camera);
  glm::dvec3 pointToLocal(const glm::dvec3& world) const;
  glm::dvec3 directionToLocal(const glm::dvec3& world) const;
};

}  // namespace spectrace
