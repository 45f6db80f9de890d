#pragma once
// The bench's ceiling: the throughput scene's work (a D65 disk light before
// a bare sensor) with no exactness guarantees (a hash for random numbers, a
// float CDF search, one 32-bit atomic per counted beam), on the CPU in
// plain scalar C++ and on a Vulkan device (shaders/ceiling.comp). Shows how
// close spectrace's kernel comes to what the device can do; never renders.
#include <cstdint>
#include <vector>

#include "device_shared.h"

namespace spectrace {
namespace vk_util {
class Context;
}

struct CeilingScene {
  device::CeilingPush geometry{};  // everything but the beam range
  std::vector<float> cdf;          // the spectrum's CDF at geometry.cdfCount nodes
};
// The throughput scene (spectrace bench): D65 at 1 nm over 360-830 nm, 64
// bins, a disk of radius 0.05 m at 0.1 m before a bare 0.1 m, 512x512 sensor.
CeilingScene throughputCeilingScene();

struct CeilingResult {
  uint64_t beams = 0, hits = 0;
  double seconds = 0.0;  // CPU: wall time of the trace; Vulkan: device time of the dispatches
  std::vector<uint32_t> counts;  // per pixel-bin (row-major pixels, then bins)
};
// threads = 0: all hardware threads.
CeilingResult traceCeilingOnCpu(const CeilingScene& scene, uint64_t beams, unsigned threads = 0);
CeilingResult traceCeilingOnVulkan(const vk_util::Context& context, const CeilingScene& scene, uint64_t beams);

}  // namespace spectrace
