#pragma once
// The CPU reference as a Device: the shared kernel's C++ instance on host
// threads (cpu_tracer.h), exact, with no device limits.
#include "backend/device.h"

namespace spectrace {

class CpuDevice final : public Device {
 public:
  CpuDevice();
  // What listDevices() says of the CPU reference.
  static DeviceCapabilities referenceCapabilities();

  const DeviceCapabilities& capabilities() const override { return capabilities_; }
  std::unique_ptr<Tracer> makeTracer(const CompiledScene& plan, const TracerOptions& options = {}) const override;
  CeilingResult traceCeiling(const CeilingScene& scene, uint64_t beams, unsigned threads = 0) const override;

 private:
  DeviceCapabilities capabilities_;
};

}  // namespace spectrace
