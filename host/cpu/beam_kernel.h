#pragma once
// The CPU instance of the shared beam code (shaders/beam_math.h,
// shaders/beam_trace.h): the same text the trace shader runs, compiled as
// C++ member functions over host arrays, with Philox from Random123.
#include <span>

#include <glm/glm.hpp>

#include "device_shared.h"
#include "rng/philox.h"

namespace spectrace::device {

// GLSL names (vec3, uvec4, sqrt, min, abs, ...) for the shared code.
using namespace glm;

class BeamKernel {
 public:
  BeamKernel(const TraceConstants& traceConstants, std::span<const LightRecord> lightRecords,
             std::span<const SpectralInterval> spectralIntervals, std::span<const glm::vec3> cmfNodes = {})
      : constants(traceConstants), lights(lightRecords), intervals(spectralIntervals), cmf(cmfNodes) {}

  // Whether beam `index` is counted, its pixel and (stored) bin, and what
  // it adds to the bin (weightUnits x its weight ratio). (The shared
  // functions cannot be const-qualified, as GLSL has no such thing; the
  // kernel is small, so each thread uses its own copy.)
  bool trace(uint64_t index, uint& pixelOut, uint& binOut, uint64_t* unitsOut = nullptr) {
    float lambda, spare, ratio;
    const bool hit = traceBeam(index, pixelOut, binOut, lambda, spare, ratio);
    if (unitsOut) *unitsOut = hit ? weightUnitsOf(ratio, spare) : 0;
    return hit;
  }

 private:
  TraceConstants constants;
  std::span<const LightRecord> lights;
  std::span<const SpectralInterval> intervals;
  std::span<const glm::vec3> cmf;

  static uvec4 philox4x32(uint64_t seed, uint64_t index, uint block) {
    const auto w = spectrace::philoxWords(seed, index, block);
    return uvec4(w[0], w[1], w[2], w[3]);
  }
  uint64_t readLightCdf(uint i) const { return lights[i].selectCdfLow; }
  uint64_t readSpectralCdf(uint i) const { return intervals[i].cdfLow; }
  LightRecord readLight(uint i) const { return lights[i]; }
  SpectralInterval readInterval(uint i) const { return intervals[i]; }
  vec3 readCmf(uint i) const { return cmf[i]; }

 public:
  // The shared functions are public so tests can probe them one by one.
#include "beam_math.h"
#include "beam_trace.h"
};

}  // namespace spectrace::device
