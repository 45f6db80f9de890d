#pragma once
// Scenes built in code for tests, and a shared Vulkan context.
#include <memory>

#include <cctype>
#include <string>

#include "camera/pinhole_camera.h"
#include "scene/scene_builders.h"
#include "spectrum/spd.h"
#include "vulkan/context.h"

namespace spectrace::testing {

using spectrace::bareSensorScene;
using spectrace::pointLight;
using spectrace::surfaceLight;

// A test-property key safe for gtest's XML output.
inline std::string propertyKey(const std::string& text) {
  std::string key;
  for (char c : text) key += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return key;
}

// Every light type at once (point, spot, disk, rect, laser; five spectra),
// near a small sensor so that many beams hit; with a pinhole, the lights
// move back behind its aperture plane.
inline Scene everyLightTypeScene(bool pinhole) {
  Scene scene = bareSensorScene(0.036, 0.024, 72, 48, 94);
  Light spot = pointLight({0.004, 0.002, 0.08}, 2.0, *cieIlluminant("A"));
  spot.type = LightType::Spot;
  spot.direction = glm::normalize(glm::dvec3(-0.05, 0.0, -1.0));
  spot.coneHalfAngleDeg = 12.0;
  Light disk = surfaceLight(LightType::Disk, {-0.01, 0.0, 0.03}, {0, 0, -1}, 3.0, makeBlackbodySpd(2700, 360, 830));
  disk.radiusM = 0.01;
  Light rect = surfaceLight(LightType::Rect, {0.01, -0.005, 0.02}, glm::normalize(glm::dvec3(0.2, 0.1, -1)), 3.0,
                            *cieIlluminant("F11"));
  rect.sizeM = {0.02, 0.01};
  rect.uAxis = {1, 0, 0};
  Light laser = surfaceLight(LightType::Laser, {0.005, 0.005, 0.1}, {0, 0, -1}, 0.01, makeLineSpd(532.0));
  laser.radiusM = 0.002;
  scene.lights = {pointLight({0.0, 0.0, 0.02}, 1.0, *cieIlluminant("D65")), spot, disk, rect, laser};
  if (pinhole) {
    scene.camera.model = pinholeModel({0.01, 0.002});
    for (auto& l : scene.lights) l.position.z += 0.02;
  }
  return scene;
}

// One Vulkan context per test program (device creation is slow on lavapipe).
inline const vk_util::Context& sharedVulkan() {
  static std::unique_ptr<vk_util::Context> context = vk_util::Context::create();
  return *context;
}

}  // namespace spectrace::testing
