#pragma once
// The Vulkan path: trace pass (beams -> 64-bit histogram chunks) and resolve
// pass (histogram -> XYZ/RGB/irradiance), both on one device.
#include <cstdint>
#include <span>
#include <vector>

#include "cpu/resolve_cpu.h"
#include "cpu/spectral_histogram.h"
#include "lights/trace_plan.h"
#include "render/specialisation.h"
#include "vulkan/buffer.h"
#include "vulkan/compute_pipeline.h"
#include "vulkan/context.h"
#include "vulkan/timestamps.h"

namespace spectrace {

// How the histogram is split across storage buffers: whole pixels per
// chunk, each chunk within the device's maxStorageBufferRange.
struct HistogramSplit {
  uint32_t pixelsPerChunk = 0;
  uint32_t chunkCount = 0;
  // Throws vk_util::VulkanError when the histogram needs more than
  // kMaxHistogramChunks chunks.
  static HistogramSplit forDevice(uint64_t pixels, uint32_t countersPerPixel, uint64_t maxStorageBufferRange,
                                  uint64_t maxAllocation);
};

// The device's counter layout for a plan: per pixel, countersPerPixel
// 64-bit counters, the stored bins then (with exact colour) X, Y, Z, then
// (with fractional weights) the squared weights. The host histogram has
// every bin of the spectrum.
// Packs pixels [firstPixel, firstPixel + out.size() / countersPerPixel).
void packDeviceCounters(const SpectralHistogram& histogram, const TracePlan& plan, size_t firstPixel,
                        std::span<uint64_t> out);
// Unpacks device counters of pixels starting at firstPixel into `histogram`.
void unpackDeviceCounters(std::span<const uint64_t> counters, const TracePlan& plan, size_t firstPixel,
                          SpectralHistogram& histogram);
// The resolve pass's constants and the weights of the stored bins.
device::ResolveConstants resolveConstants(const TracePlan& plan, const ResolveParameters& parameters,
                                          uint32_t pixelsPerChunk);
std::vector<glm::vec3> storedBinWeights(const TracePlan& plan, const ResolveParameters& parameters);

class GpuTracer {
 public:
  // `specialisedFeatures` (SpecialisedFeature bits): the scene features the
  // trace pipeline is compiled for (absent light types, light choice,
  // pinhole, exact colour, aiming, fixed by specialisation constants); the
  // others are decided at run time. kSpecialiseNone is the general pipeline.
  GpuTracer(const vk_util::Context& context, const TracePlan& plan, uint32_t workgroupSize = 64,
            uint32_t specialisedFeatures = kSpecialiseAll);

  // Adds beams [firstBeam, firstBeam + beamCount) to the device histogram.
  // Returns the device time of the trace pass in seconds (timestamps).
  double trace(uint64_t firstBeam, uint64_t beamCount);
  void clearHistogram();
  SpectralHistogram downloadHistogram() const;
  // Replaces the device histogram (same shape as the plan's), e.g. to go on
  // from a saved partial render.
  void uploadHistogram(const SpectralHistogram& histogram);
  // Resolves on the device; `seconds` receives the device time if non-null.
  RenderImage resolve(const ResolveParameters& parameters, double* seconds = nullptr);

  // Traces beams [firstBeam, firstBeam + count) without counting them and
  // returns each beam's pixel, bin and units, or pixel kBeamMissed for a
  // beam that would not be counted.
  std::vector<device::BeamRecord> traceRecorded(uint64_t firstBeam, uint32_t count);

  const HistogramSplit& split() const { return split_; }
  uint64_t maxBeamsPerDispatch() const;

 private:
  const vk_util::Context& context_;
  TracePlan plan_;
  uint32_t workgroupSize_;
  std::vector<uint32_t> traceSpecialisation_;  // constant_id 2.. of trace_beams.comp
  HistogramSplit split_;
  vk_util::Buffer traceConstants_;
  vk_util::Buffer lights_;
  vk_util::Buffer intervals_;
  vk_util::Buffer unusedBeamRecords_;  // bound where the record path is compiled out
  vk_util::Buffer cmfTable_;
  vk_util::Buffer stats_;  // TraceStats
  std::vector<vk_util::Buffer> histogramChunks_;
  vk_util::ComputePipeline tracePipeline_;
  vk_util::ComputePipeline resolvePipeline_;
  vk_util::TimestampQueries timestamps_;
};

// Philox words for beams [firstIndex, firstIndex + count) of one block,
// computed by the shader's Philox (to check it against the CPU's).
std::vector<glm::uvec4> philoxOnGpu(const vk_util::Context& context, uint64_t seed, uint64_t firstIndex,
                                    uint32_t count, uint32_t block);

}  // namespace spectrace
