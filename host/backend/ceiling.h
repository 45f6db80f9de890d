#pragma once
// The bench's ceiling: the throughput scene's work (a light before a bare
// sensor) with no exactness guarantees (a hash for random numbers, a float
// CDF search, one 32-bit atomic per counted beam), on the CPU in plain
// scalar C++ (here) and on a Vulkan device (shaders/ceiling.comp, through
// Device::traceCeiling). Shows how close spectrace's kernel comes to what the
// device can do; never renders. bench/throughput_ceiling.h builds the scene.
#include <cstdint>
#include <vector>

#include "device_shared.h"

namespace spectrace {

struct CeilingScene {
  device::CeilingPush geometry{};  // everything but the beam range
  std::vector<float> cdf;          // the spectrum's CDF at geometry.cdfCount nodes
};

struct CeilingResult {
  uint64_t beams = 0, hits = 0;
  double seconds = 0.0;  // CPU: wall time of the trace; Vulkan: device time of the dispatches
  std::vector<uint32_t> counts;  // per pixel-bin (row-major pixels, then bins)
};

// The counters of a scene's film: pixels x pixels x bins.
uint64_t ceilingCountersOf(const CeilingScene& scene);
// threads = 0: all hardware threads.
CeilingResult traceCeilingOnCpu(const CeilingScene& scene, uint64_t beams, unsigned threads = 0);

}  // namespace spectrace
