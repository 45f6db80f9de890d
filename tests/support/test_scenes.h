#pragma once
// Scenes built in code for tests, and a shared Vulkan context.
#include <memory>

#include <cctype>
#include <string>

#include "scene/scene_builders.h"
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

// One Vulkan context per test program (device creation is slow on lavapipe).
inline const vk_util::Context& sharedVulkan() {
  static std::unique_ptr<vk_util::Context> context = vk_util::Context::create();
  return *context;
}

}  // namespace spectrace::testing
