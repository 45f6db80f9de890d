#pragma once
// Scenes built in code for tests, and a shared Vulkan context.
#include <memory>

#include "scene/scene.h"
#include "spectrum/spd.h"
#include "vulkan/context.h"

namespace spectrace::testing {

// A bare sensor at the origin looking along +z.
inline Scene bareSensorScene(double widthM, double heightM, int pixelsX, int pixelsY, int bins = 32) {
  Scene scene;
  scene.spectrum = {360.0, 830.0, bins};
  scene.camera.sensorWidthM = widthM;
  scene.camera.sensorHeightM = heightM;
  scene.camera.pixelsX = pixelsX;
  scene.camera.pixelsY = pixelsY;
  return scene;
}

inline Light pointLight(glm::dvec3 position, double powerW, Spd spd) {
  Light light;
  light.type = LightType::Point;
  light.label = "/lights/point";
  light.position = position;
  light.powerW = powerW;
  light.spdLabel = "test";
  light.spd = std::move(spd);
  return light;
}

inline Light surfaceLight(LightType type, glm::dvec3 center, glm::dvec3 normal, double powerW, Spd spd) {
  Light light = pointLight(center, powerW, std::move(spd));
  light.type = type;
  light.direction = normal;
  return light;
}

// One Vulkan context per test program (device creation is slow on lavapipe).
inline const vk_util::Context& sharedVulkan() {
  static std::unique_ptr<vk_util::Context> context = vk_util::Context::create();
  return *context;
}

}  // namespace spectrace::testing
