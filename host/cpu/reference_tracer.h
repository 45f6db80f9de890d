#pragma once
// The CPU reference (--device cpu): multithreaded, drawing exactly the beams
// the GPU draws, through the same shared beam code.
#include <atomic>
#include <cstdint>

#include "cpu/spectral_histogram.h"
#include "lights/trace_plan.h"

namespace spectrace {

struct CpuTraceOptions {
  unsigned threads = 0;                         // 0: all hardware threads
  const std::atomic<bool>* cancel = nullptr;    // stops early when set
};

// Adds the hits of beams [firstBeam, firstBeam + beamCount) to `histogram`
// (shape from the plan). Returns the number of beams traced, which is less
// than beamCount only when cancelled; the beams traced are then exactly
// [firstBeam, firstBeam + returned), so no finished work is lost.
uint64_t traceOnCpu(const TracePlan& plan, uint64_t firstBeam, uint64_t beamCount,
                    SpectralHistogram& histogram, const CpuTraceOptions& options = {});

}  // namespace spectrace
