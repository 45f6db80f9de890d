#pragma once
// Beam-by-beam comparison of the Vulkan trace with the CPU reference: for
// each beam, whether it is counted, its pixel, bin and weight units.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "kernel/beam_kernel.h"
#include "compile/compile_scene.h"
#include "backend/vulkan_tracer.h"
#include "support/test_scenes.h"

namespace spectrace::testing {

struct BeamAgreement {
  uint64_t same = 0, hits = 0, differ = 0;
  double rate = 0.0;  // same / count
};

inline bool sameRecord(const device::BeamRecord& a, const device::BeamRecord& b) {
  return a.pixel == b.pixel && a.bin == b.bin && a.ratioBits == b.ratioBits && a.contributions == b.contributions;
}

// The CPU's record of beam `index`, as the shader's record mode writes it.
inline device::BeamRecord cpuRecord(device::BeamKernel& kernel, uint64_t index) { return kernel.record(index); }

// Traces beams [firstBeam, firstBeam + count) on both devices, prints the
// first few differences and the totals, and records the agreement rate as a
// test property.
inline BeamAgreement beamByBeam(const CompiledScene& plan, uint64_t firstBeam, uint32_t count, const std::string& name) {
  VulkanTracer gpu(sharedVulkan(), plan);
  const auto records = gpu.traceRecorded(firstBeam, count);
  device::BeamKernel cpu(plan.device.constants, plan.device.lights, plan.device.intervals, plan.device.aliasColumns);
  cpu.setObjects(plan.device.primitives, plan.device.bvhNodes, plan.device.materials, plan.device.data.words());
  BeamAgreement result;
  for (uint32_t i = 0; i < count; ++i) {
    const device::BeamRecord expected = cpuRecord(cpu, firstBeam + i);
    result.hits += expected.pixel != device::kBeamMissed;
    if (sameRecord(expected, records[i])) {
      ++result.same;
    } else if (++result.differ <= 5) {
      std::printf("  %s: beam %llu differs: cpu (pixel %u, bin %u, ratio bits %08x), gpu (pixel %u, bin %u, ratio bits %08x)\n",
                  name.c_str(), (unsigned long long)(firstBeam + i), expected.pixel, expected.bin, expected.ratioBits,
                  records[i].pixel, records[i].bin, records[i].ratioBits);
    }
  }
  result.rate = double(result.same) / double(count);
  std::printf("%s: CPU/GPU beam by beam: %llu of %u identical (%.6f%%), %llu counted\n", name.c_str(),
              (unsigned long long)result.same, count, 100.0 * result.rate, (unsigned long long)result.hits);
  ::testing::Test::RecordProperty(propertyKey(name + "_agreement"), std::to_string(result.rate));
  return result;
}

}  // namespace spectrace::testing
