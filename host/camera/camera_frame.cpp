#include "camera/camera_frame.h"

#include <glm/geometric.hpp>

#include "json/scene_error.h"

namespace spectrace {

CameraFrame CameraFrame::fromCamera(const Camera& camera) {
  const glm::dvec3 view = camera.lookAt - camera.position;
  const double viewLength = glm::length(view);
  if (!(viewLength > 0.0)) throw SceneError("camera: look_at equals position, so there is no viewing direction");
  CameraFrame frame;
  frame.origin = camera.position;
  frame.forward = view / viewLength;
  const glm::dvec3 side = glm::cross(frame.forward, camera.up);
  const double sideLength = glm::length(side);
  if (!(sideLength > 1e-12 * glm::length(camera.up)))
    throw SceneError("camera: up is parallel to the viewing direction");
  frame.right = side / sideLength;
  frame.up = glm::cross(frame.right, frame.forward);
  return frame;
}

glm::dvec3 CameraFrame::pointToLocal(const glm::dvec3& world) const {
  return directionToLocal(world - origin);
}

glm::dvec3 CameraFrame::directionToLocal(const glm::dvec3& d) const {
  return {glm::dot(d, right), glm::dot(d, up), glm::dot(d, forward)};
}

}  // namespace spectrace
