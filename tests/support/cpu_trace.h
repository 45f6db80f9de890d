#pragma once
// Tests' shorthand for the CPU reference through the Tracer interface: adds
// beams [firstBeam, firstBeam + beamCount) to `histogram` (started afresh
// when it does not have the film's shape) and returns the beams traced.
#include <atomic>
#include <cstdint>

#include "backend/cpu_tracer.h"

namespace spectrace {

struct CpuTraceOptions {
  unsigned threads = 0;                       // 0: all hardware threads
  const std::atomic<bool>* cancel = nullptr;  // stops early when set
};

inline uint64_t traceOnCpu(const CompiledScene& plan, uint64_t firstBeam, uint64_t beamCount, SpectralHistogram& histogram,
                           const CpuTraceOptions& options = {}) {
  CpuTracer tracer(plan, options.threads);
  if (plan.film.hasShapeOf(histogram)) tracer.upload(histogram);
  const uint64_t traced = tracer.trace(firstBeam, beamCount, options.cancel);
  histogram = tracer.download();
  return traced;
}

}  // namespace spectrace
