#include "backend/cpu_device.h"

#include <algorithm>
#include <thread>

#include <fmt/format.h>

#include "backend/cpu_tracer.h"

namespace spectrace {

DeviceCapabilities CpuDevice::referenceCapabilities() {
  DeviceCapabilities c;
  c.kind = DeviceKind::Cpu;
  c.name = fmt::format("CPU reference, {} threads, {}", std::max(1u, std::thread::hardware_concurrency()),
                       cpuCodeName(fastestCpuCode()));
  c.reference = true;
  c.filmInHostMemory = true;  // its counters are the film
  return c;
}

CpuDevice::CpuDevice() : capabilities_(referenceCapabilities()) {}

std::unique_ptr<Tracer> CpuDevice::makeTracer(const CompiledScene& plan, const TracerOptions& options) const {
  return std::make_unique<CpuTracer>(plan, options.cpuThreads, options.profileStage,
                                     options.cpuCode.value_or(fastestCpuCode()));
}

CeilingResult CpuDevice::traceCeiling(const CeilingScene& scene, uint64_t beams, unsigned threads) const {
  return traceCeilingOnCpu(scene, beams, threads);
}

}  // namespace spectrace
