#include "render/gpu_tracer.h"

#include <algorithm>
#include <stdexcept>
#include <fmt/format.h>

#include "embedded_shaders.h"

namespace spectrace {

using vk_util::Buffer;
using vk_util::MemoryPlacement;

namespace {

template <typename T>
Buffer uploadedBuffer(const vk_util::Context& context, const std::vector<T>& data) {
  Buffer buffer(context, std::max<vk::DeviceSize>(sizeof(T) * data.size(), 16), {}, MemoryPlacement::DeviceLocal);
  buffer.upload(data.data(), sizeof(T) * data.size());
  return buffer;
}

std::vector<vk_util::BindingSpec> traceBindings() {
  return {{device::kBindingTraceConstants}, {device::kBindingLights}, {device::kBindingSpectralIntervals},
          {device::kBindingHistogram, device::kMaxHistogramChunks}, {device::kBindingBeamRecords},
          {device::kBindingCmfTable}, {device::kBindingTraceStats}};
}

// 2D dispatch shape for `count` invocations: rows of at most the device's
// group-count limit.
struct DispatchShape {
  uint32_t groupsX, groupsY, invocationsPerRow;
};
DispatchShape dispatchShape(const vk_util::Context& context, uint64_t count, uint32_t workgroupSize) {
  const uint64_t groups = (count + workgroupSize - 1) / workgroupSize;
  const uint32_t groupsX = uint32_t(std::min<uint64_t>(groups, context.info().maxComputeWorkGroupCount[0]));
  return {groupsX, uint32_t((groups + groupsX - 1) / groupsX), groupsX * workgroupSize};
}

// Specialisation constants 2..6 of trace_beams.comp (device_shared.h,
// kSpec*): the scene's value for each feature in `features`, else the
// general pipeline's (decide at run time).
std::vector<uint32_t> traceSpecialisation(const TracePlan& plan, uint32_t features) {
  uint32_t types = 0;
  bool aimed = false;
  for (const auto& light : plan.lights) {
    types |= 1u << light.type;
    aimed = aimed || light.aimed != 0;
  }
  auto pick = [&](SpecialisedFeature f, uint32_t scene, uint32_t general) { return (features & f) ? scene : general; };
  return {pick(kSpecialiseLightTypes, types, 31u), pick(kSpecialiseLightChoice, plan.lights.size() > 1 ? 1u : 0u, 1u),
          pick(kSpecialisePinhole, plan.constants.apertureDistance > 0.0f ? 1u : 0u, 2u),
          pick(kSpecialiseExactColour, plan.exactColour() ? 1u : 0u, 2u), pick(kSpecialiseAim, aimed ? 1u : 0u, 2u)};
}

// Specialisation constants in constant_id order.
std::vector<uint32_t> specConstants(uint32_t workgroupSize, bool record, const std::vector<uint32_t>& scene) {
  std::vector<uint32_t> constants = {workgroupSize, record ? 1u : 0u};
  constants.insert(constants.end(), scene.begin(), scene.end());
  return constants;
}

}  // namespace

HistogramSplit HistogramSplit::forDevice(uint64_t pixels, uint32_t countersPerPixel, uint64_t maxStorageBufferRange,
                                         uint64_t maxAllocation) {
  const uint64_t bytesPerPixel = uint64_t(countersPerPixel) * sizeof(uint64_t);
  const uint64_t limit = std::min(maxStorageBufferRange, maxAllocation);
  const uint64_t perChunk = std::min<uint64_t>(pixels, limit / bytesPerPixel);
  if (perChunk == 0)
    throw vk_util::VulkanError(fmt::format(
        "one pixel's histogram ({} counters x 8 bytes) exceeds the device's storage buffer range of {} bytes", countersPerPixel, limit));
  HistogramSplit split;
  split.pixelsPerChunk = uint32_t(std::min<uint64_t>(perChunk, UINT32_MAX));
  split.chunkCount = uint32_t((pixels + split.pixelsPerChunk - 1) / split.pixelsPerChunk);
  if (split.chunkCount > device::kMaxHistogramChunks)
    throw vk_util::VulkanError(fmt::format(
        "the histogram needs {:.2f} GiB ({} pixels x {} counters x 8 bytes), which is {} buffers of at most "
        "maxStorageBufferRange = {} bytes; spectrace supports {}. Use fewer pixels or bins.",
        double(pixels * bytesPerPixel) / (1 << 30), pixels, countersPerPixel, split.chunkCount, limit,
        device::kMaxHistogramChunks));
  return split;
}

GpuTracer::GpuTracer(const vk_util::Context& context, const TracePlan& plan, uint32_t workgroupSize,
                     uint32_t specialisedFeatures)
    : context_(context),
      plan_(plan),
      workgroupSize_(workgroupSize),
      traceSpecialisation_(traceSpecialisation(plan, specialisedFeatures)),
      split_(HistogramSplit::forDevice(plan.storedPixelCount(), plan.countersPerPixel(), context.info().maxStorageBufferRange,
                                       context.info().maxMemoryAllocationSize)),
      traceConstants_(context, sizeof(device::TraceConstants), {}, MemoryPlacement::DeviceLocal),
      lights_(uploadedBuffer(context, plan.lights)),
      intervals_(uploadedBuffer(context, plan.intervals)),
      unusedBeamRecords_(context, 16, {}, MemoryPlacement::DeviceLocal),
      cmfTable_(uploadedBuffer(context, plan.cmfTable)),
      stats_(context, sizeof(device::TraceStats), {}, MemoryPlacement::HostVisible),
      tracePipeline_(context, embedded::spv_trace_beams(),
                     traceBindings(), sizeof(device::TracePush), specConstants(workgroupSize, false, traceSpecialisation_)),
      resolvePipeline_(context, embedded::spv_resolve(),
                       {{device::kBindingResolveConstants}, {device::kBindingBinWeights},
                        {device::kBindingResolvedPixels}, {device::kBindingResolveHistogram, device::kMaxHistogramChunks}},
                       sizeof(device::ResolvePush), {workgroupSize}),
      timestamps_(context, 2) {
  plan_.constants.pixelsPerChunk = split_.pixelsPerChunk;
  traceConstants_.upload(&plan_.constants, sizeof(plan_.constants));
  const uint64_t pixelBytes = uint64_t(plan.countersPerPixel()) * sizeof(uint64_t);
  for (uint32_t c = 0; c < split_.chunkCount; ++c) {
    const uint64_t pixels =
        std::min<uint64_t>(split_.pixelsPerChunk, plan.storedPixelCount() - uint64_t(c) * split_.pixelsPerChunk);
    histogramChunks_.emplace_back(context, pixels * pixelBytes, vk::BufferUsageFlags{}, MemoryPlacement::DeviceLocal);
  }
  tracePipeline_.bindBuffer(device::kBindingTraceConstants, 0, traceConstants_);
  tracePipeline_.bindBuffer(device::kBindingLights, 0, lights_);
  tracePipeline_.bindBuffer(device::kBindingSpectralIntervals, 0, intervals_);
  tracePipeline_.bindBuffer(device::kBindingBeamRecords, 0, unusedBeamRecords_);
  tracePipeline_.bindBuffer(device::kBindingCmfTable, 0, cmfTable_);
  tracePipeline_.bindBuffer(device::kBindingTraceStats, 0, stats_);
  // Unused chunk slots alias chunk 0: the descriptors must be valid even
  // though no pixel maps to them.
  for (uint32_t c = 0; c < device::kMaxHistogramChunks; ++c) {
    const Buffer& chunk = histogramChunks_[c < split_.chunkCount ? c : 0];
    tracePipeline_.bindBuffer(device::kBindingHistogram, c, chunk);
    resolvePipeline_.bindBuffer(device::kBindingResolveHistogram, c, chunk);
  }
  clearHistogram();
}

void GpuTracer::clearHistogram() {
  for (auto& chunk : histogramChunks_) chunk.fillZero();
  stats_.fillZero();
}

uint64_t GpuTracer::maxBeamsPerDispatch() const {
  const auto& limits = context_.info().maxComputeWorkGroupCount;
  const uint64_t perDispatch = uint64_t(limits[0]) * limits[1] * workgroupSize_;
  return std::min<uint64_t>(perDispatch, uint64_t(1) << 31);
}

double GpuTracer::trace(uint64_t firstBeam, uint64_t beamCount) {
  double seconds = 0.0;
  while (beamCount > 0) {
    const uint64_t count = std::min(beamCount, maxBeamsPerDispatch());
    const DispatchShape shape = dispatchShape(context_, count, workgroupSize_);
    const device::TracePush push{firstBeam, uint32_t(count), shape.invocationsPerRow};
    context_.submitAndWait([&](const vk::raii::CommandBuffer& cb) {
      timestamps_.reset(cb);
      timestamps_.write(cb, 0);
      tracePipeline_.recordDispatch(cb, &push, shape.groupsX, shape.groupsY);
      timestamps_.write(cb, 1);
    });
    const auto ns = timestamps_.readNanoseconds();
    if (ns.size() == 2) seconds += (ns[1] - ns[0]) * 1e-9;
    firstBeam += count;
    beamCount -= count;
  }
  return seconds;
}

std::vector<device::BeamRecord> GpuTracer::traceRecorded(uint64_t firstBeam, uint32_t count) {
  vk_util::ComputePipeline recorder(context_, embedded::spv_trace_beams(), traceBindings(), sizeof(device::TracePush),
                                    specConstants(workgroupSize_, true, traceSpecialisation_));
  Buffer records(context_, std::max<uint64_t>(uint64_t(count) * sizeof(device::BeamRecord), 16), {},
                 MemoryPlacement::HostVisible);
  recorder.bindBuffer(device::kBindingTraceConstants, 0, traceConstants_);
  recorder.bindBuffer(device::kBindingLights, 0, lights_);
  recorder.bindBuffer(device::kBindingSpectralIntervals, 0, intervals_);
  for (uint32_t c = 0; c < device::kMaxHistogramChunks; ++c)
    recorder.bindBuffer(device::kBindingHistogram, c, histogramChunks_[c < split_.chunkCount ? c : 0]);
  recorder.bindBuffer(device::kBindingBeamRecords, 0, records);
  recorder.bindBuffer(device::kBindingCmfTable, 0, cmfTable_);
  recorder.bindBuffer(device::kBindingTraceStats, 0, stats_);  // left untouched in record mode
  const DispatchShape shape = dispatchShape(context_, count, workgroupSize_);
  const device::TracePush push{firstBeam, count, shape.invocationsPerRow};
  context_.submitAndWait([&](const vk::raii::CommandBuffer& cb) { recorder.recordDispatch(cb, &push, shape.groupsX, shape.groupsY); });
  std::vector<device::BeamRecord> result(count);
  records.download(result.data(), uint64_t(count) * sizeof(device::BeamRecord));
  return result;
}

std::vector<glm::uvec4> philoxOnGpu(const vk_util::Context& context, uint64_t seed, uint64_t firstIndex, uint32_t count,
                                    uint32_t block) {
  constexpr uint32_t kWorkgroup = 64;
  vk_util::ComputePipeline pipeline(context, embedded::spv_rng_check(), {{device::kBindingRngWords}},
                                    sizeof(device::RngCheckPush), {kWorkgroup});
  Buffer words(context, std::max<uint64_t>(uint64_t(count) * sizeof(glm::uvec4), 16), {}, MemoryPlacement::HostVisible);
  pipeline.bindBuffer(device::kBindingRngWords, 0, words);
  const device::RngCheckPush push{seed, firstIndex, count, block};
  context.submitAndWait([&](const vk::raii::CommandBuffer& cb) {
    pipeline.recordDispatch(cb, &push, (count + kWorkgroup - 1) / kWorkgroup);
  });
  std::vector<glm::uvec4> result(count);
  words.download(result.data(), uint64_t(count) * sizeof(glm::uvec4));
  return result;
}

SpectralHistogram GpuTracer::downloadHistogram() const {
  SpectralHistogram histogram = plan_.emptyHistogram();
  device::TraceStats stats{};
  stats_.download(&stats, sizeof(stats));
  histogram.countedBeams = stats.countedBeams;
  std::vector<uint64_t> counters;
  size_t pixel = 0;
  for (const auto& chunk : histogramChunks_) {
    counters.resize(chunk.size() / sizeof(uint64_t));
    chunk.download(counters.data(), chunk.size());
    unpackDeviceCounters(counters, plan_, pixel, histogram);
    pixel += counters.size() / plan_.countersPerPixel();
  }
  return histogram;
}

void GpuTracer::uploadHistogram(const SpectralHistogram& histogram) {
  if (!plan_.hasShapeOf(histogram))
    throw std::invalid_argument("uploadHistogram: the histogram's shape differs from the trace plan's");
  const device::TraceStats stats{histogram.countedBeams};
  stats_.upload(&stats, sizeof(stats));
  std::vector<uint64_t> counters;
  size_t pixel = 0;
  for (auto& chunk : histogramChunks_) {
    counters.resize(chunk.size() / sizeof(uint64_t));
    packDeviceCounters(histogram, plan_, pixel, counters);
    chunk.upload(counters.data(), chunk.size());
    pixel += counters.size() / plan_.countersPerPixel();
  }
}

void packDeviceCounters(const SpectralHistogram& histogram, const TracePlan& plan, size_t firstPixel,
                        std::span<uint64_t> out) {
  const uint32_t stride = plan.countersPerPixel(), stored = plan.storedBins(), first = plan.firstStoredBin();
  // Pixels outside the stored window must be empty.
  for (uint64_t p = 0; p < plan.pixelCount(); ++p) {
    if (plan.storesPixel(p)) continue;
    for (uint32_t b = 0; b < plan.bins; ++b)
      if (histogram.counts[p * plan.bins + b] != 0)
        throw std::invalid_argument("counts in pixels outside the stored window");
  }
  for (size_t local = 0; local < out.size() / stride; ++local) {
    const size_t pixel = plan.fullPixelOfStored(firstPixel + local);
    uint64_t* dst = out.data() + local * stride;
    const auto bins = histogram.counts.begin() + pixel * plan.bins;
    for (uint32_t b = 0; b < plan.bins; ++b) {
      if ((b < first || b >= first + stored) && bins[b] != 0)
        throw std::invalid_argument("counts in bins the trimmed spectrum does not store");
    }
    std::copy_n(bins + first, stored, dst);
    uint64_t* next = dst + stored;
    if (plan.exactColour()) next = std::copy_n(histogram.colourSums.begin() + pixel * 3, 3, next);
    if (plan.weighted()) *next = histogram.squaredWeightSums[pixel];
  }
}

void unpackDeviceCounters(std::span<const uint64_t> counters, const TracePlan& plan, size_t firstPixel,
                          SpectralHistogram& histogram) {
  const uint32_t stride = plan.countersPerPixel(), stored = plan.storedBins();
  for (size_t local = 0; local < counters.size() / stride; ++local) {
    const size_t pixel = plan.fullPixelOfStored(firstPixel + local);
    const uint64_t* src = counters.data() + local * stride;
    std::copy(src, src + stored, histogram.counts.begin() + pixel * plan.bins + plan.firstStoredBin());
    const uint64_t* next = src + stored;
    if (plan.exactColour()) {
      std::copy_n(next, 3, histogram.colourSums.begin() + pixel * 3);
      next += 3;
    }
    if (plan.weighted()) histogram.squaredWeightSums[pixel] = *next;
  }
}

device::ResolveConstants resolveConstants(const TracePlan& plan, const ResolveParameters& parameters,
                                          uint32_t pixelsPerChunk) {
  device::ResolveConstants constants{};
  constants.pixelCount = uint32_t(plan.storedPixelCount());
  constants.bins = plan.storedBins();
  constants.pixelsPerChunk = pixelsPerChunk;
  constants.countersPerPixel = plan.countersPerPixel();
  constants.exactColour = parameters.useExactColour && plan.exactColour() ? 1u : 0u;
  constants.irradiancePerCount = float(parameters.irradiancePerCount);
  const double perBeam = parameters.irradiancePerCount * double(plan.constants.weightUnits);
  constants.xyzPerColourUnit = float(683.0 * perBeam / device::kColourFixedPointScale);
  // glm is column-major: row r of M is (M[0][r], M[1][r], M[2][r]).
  const glm::dmat3& m = parameters.xyzToRgb;
  constants.xyzToRgbRow0 = glm::vec3(m[0][0], m[1][0], m[2][0]);
  constants.xyzToRgbRow1 = glm::vec3(m[0][1], m[1][1], m[2][1]);
  constants.xyzToRgbRow2 = glm::vec3(m[0][2], m[1][2], m[2][2]);
  return constants;
}

std::vector<glm::vec3> storedBinWeights(const TracePlan& plan, const ResolveParameters& parameters) {
  std::vector<glm::vec3> weights;
  for (uint32_t b = plan.firstStoredBin(); b < plan.firstStoredBin() + plan.storedBins(); ++b) {
    const auto& w = parameters.binWeights[b];
    weights.emplace_back(float(w[0]), float(w[1]), float(w[2]));
  }
  return weights;
}

RenderImage GpuTracer::resolve(const ResolveParameters& parameters, double* seconds) {
  const device::ResolveConstants constants = resolveConstants(plan_, parameters, split_.pixelsPerChunk);
  const uint64_t pixelCount = plan_.storedPixelCount();  // only stored pixels are resolved; the others are 0
  const std::vector<glm::vec3> weights = storedBinWeights(plan_, parameters);

  Buffer constantsBuffer(context_, sizeof(constants), {}, MemoryPlacement::DeviceLocal);
  constantsBuffer.upload(&constants, sizeof(constants));
  Buffer weightsBuffer = uploadedBuffer(context_, weights);
  const uint64_t maxSliceByRange = std::min<uint64_t>(
      pixelCount, std::min(context_.info().maxStorageBufferRange, context_.info().maxMemoryAllocationSize) /
                      sizeof(device::ResolvedPixel));
  // One row of workgroups per slice.
  const uint64_t maxSlice = std::min<uint64_t>(maxSliceByRange, uint64_t(context_.info().maxComputeWorkGroupCount[0]) * workgroupSize_);
  Buffer output(context_, maxSlice * sizeof(device::ResolvedPixel), {}, MemoryPlacement::HostVisible);
  resolvePipeline_.bindBuffer(device::kBindingResolveConstants, 0, constantsBuffer);
  resolvePipeline_.bindBuffer(device::kBindingBinWeights, 0, weightsBuffer);
  resolvePipeline_.bindBuffer(device::kBindingResolvedPixels, 0, output);

  RenderImage image;
  image.width = int(plan_.pixelsX);
  image.height = int(plan_.pixelsY);
  image.rgb.assign(plan_.pixelCount() * 3, 0.0f);
  image.xyz.assign(plan_.pixelCount() * 3, 0.0f);
  image.irradiance.assign(plan_.pixelCount(), 0.0f);
  std::vector<device::ResolvedPixel> slice(maxSlice);
  double deviceSeconds = 0.0;
  for (uint64_t first = 0; first < pixelCount; first += maxSlice) {
    const uint32_t count = uint32_t(std::min(maxSlice, pixelCount - first));
    const device::ResolvePush push{uint32_t(first), count};
    context_.submitAndWait([&](const vk::raii::CommandBuffer& cb) {
      timestamps_.reset(cb);
      timestamps_.write(cb, 0);
      resolvePipeline_.recordDispatch(cb, &push, (count + workgroupSize_ - 1) / workgroupSize_);
      timestamps_.write(cb, 1);
    });
    const auto ns = timestamps_.readNanoseconds();
    if (ns.size() == 2) deviceSeconds += (ns[1] - ns[0]) * 1e-9;
    output.download(slice.data(), count * sizeof(device::ResolvedPixel));
    for (uint32_t i = 0; i < count; ++i) {
      const size_t p = plan_.fullPixelOfStored(first + i);
      for (int k = 0; k < 3; ++k) {
        image.rgb[p * 3 + k] = slice[i].rgb[k];
        image.xyz[p * 3 + k] = slice[i].xyz[k];
      }
      image.irradiance[p] = slice[i].irradiance;
    }
  }
  if (seconds) *seconds = deviceSeconds;
  return image;
}

}  // namespace spectrace
