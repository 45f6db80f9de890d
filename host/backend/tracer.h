#pragma once
// One interface for every device that traces beams into a film: the CPU
// reference (cpu_tracer.h) and the Vulkan tracer (vulkan_tracer.h). The
// render loop, the bench, the CLI and the tests use only this; a tracer is
// made for one compiled scene (CompiledScene) and owns that scene's film.
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "device_shared.h"
#include "film/develop.h"
#include "film/spectral_histogram.h"
#include "io/image.h"

namespace spectrace {

enum class DeviceKind { Vulkan, Cpu };
// "gpu" or "cpu", as the CLI and EXR headers name them.
const char* deviceKindName(DeviceKind kind);

class Tracer {
 public:
  virtual ~Tracer() = default;

  virtual DeviceKind kind() const = 0;
  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)" or "CPU reference, 2 threads, x86-64-v3".
  virtual std::string deviceName() const = 0;
  // "name (kind)", as written into EXR headers.
  std::string deviceLabel() const { return deviceName() + " (" + deviceKindName(kind()) + ")"; }

  // Adds beams [firstBeam, firstBeam + beamCount) to the film. Returns the
  // beams traced: all of them, or, when `cancel` was set, a prefix
  // [firstBeam, firstBeam + returned), so no finished work is lost.
  virtual uint64_t trace(uint64_t firstBeam, uint64_t beamCount, const std::atomic<bool>* cancel = nullptr) = 0;
  // Empties the film.
  virtual void clear() = 0;
  // The film as a host histogram (whole sensor and spectrum), with the
  // number of counted beams.
  virtual SpectralHistogram download() const = 0;
  // Replaces the film by `histogram` (same shape), e.g. to go on from a
  // partial render.
  virtual void upload(const SpectralHistogram& histogram) = 0;
  // Adds a film of the same scene traced over other beams (exact).
  void merge(const SpectralHistogram& other);
  // The film developed into XYZ, RGB, irradiance and (parameters.beams > 0)
  // its error estimate; `summary`, when given, gets the counted beams and
  // the largest count. Needs no download().
  virtual RenderImage develop(const ResolveParameters& parameters, FilmSummary* summary = nullptr) = 0;

  // Traces beams [firstBeam, firstBeam + count) without counting them and
  // returns each beam's pixel, bin and units, or pixel kBeamMissed for a
  // beam that would not be counted (beam-by-beam comparisons).
  virtual std::vector<device::BeamRecord> traceRecorded(uint64_t firstBeam, uint32_t count) = 0;

  // Device time of the trace and develop passes so far (timestamps; 0 on
  // devices without them).
  double traceDeviceSeconds() const { return traceDeviceSeconds_; }
  double developDeviceSeconds() const { return developDeviceSeconds_; }

 protected:
  double traceDeviceSeconds_ = 0.0;
  double developDeviceSeconds_ = 0.0;
};

}  // namespace spectrace
