// Which device each --device choice opens: auto takes a hardware GPU, else
// the CPU reference (never a CPU implementation of Vulkan, which is slower
// than the reference on the same cores); gpu takes any usable Vulkan device.
#include "backend/device.h"

#include <gtest/gtest.h>

#include <string>

namespace spectrace {
namespace {

TEST(DeviceChoice, AutoIsAHardwareGpuElseTheCpuReference) {
  bool hardware = false, vulkan = false;
  for (const DeviceSpec& spec : listDevices()) {
    if (spec.kind() != DeviceKind::Vulkan || !spec.capabilities.unusableBecause.empty()) continue;
    vulkan = true;
    hardware = hardware || spec.capabilities.hardwareGpu;
  }
  const auto chosen = Device::open(DeviceChoice::Auto);
  EXPECT_EQ(chosen->capabilities().hardwareGpu, hardware) << chosen->capabilities().name;
  EXPECT_EQ(chosen->capabilities().reference, !hardware) << chosen->capabilities().name;
  const std::string described = describeDevices();
  if (!hardware) {
    EXPECT_NE(described.find("--device auto uses the CPU reference"), std::string::npos) << described;
  }
  if (vulkan) {
    EXPECT_EQ(Device::open(DeviceChoice::Gpu)->kind(), DeviceKind::Vulkan);
  }
}

}  // namespace
}  // namespace spectrace
