#pragma once
// The Vulkan tracer: trace pass (beams -> 64-bit counter chunks) and resolve
// pass (counters -> XYZ/RGB/irradiance), both on one device.
#include <cstdint>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "backend/tracer.h"
#include "film/develop.h"
#include "film/spectral_histogram.h"
#include "compile/compile_scene.h"
#include "backend/specialisation.h"
#include "backend/uniform_tables.h"
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

// Refuses, before anything is uploaded, a scene whose tables do not fit the
// device: the lights' spectral tables (one storage buffer) beyond
// `maxStorageBufferRange`, or the film beyond `deviceLocalHeapBytes` (both
// queried from the device, never assumed). Throws SceneError naming the
// scene field, the bytes needed and the limit.
void checkSceneFitsDevice(const CompiledScene& plan, uint64_t maxStorageBufferRange, uint64_t deviceLocalHeapBytes,
                          const std::string& deviceName);

// The resolve pass's constants and the weights of the stored bins.
device::ResolveConstants resolveConstants(const CompiledScene& plan, const ResolveParameters& parameters,
                                          uint32_t pixelsPerChunk);
std::vector<glm::vec3> storedBinWeights(const CompiledScene& plan, const ResolveParameters& parameters);

// A pipeline's descriptor layout from its one binding table (device_shared.h).
std::vector<vk_util::BindingSpec> bindingSpecs(std::span<const device::BindingSlot> table);

// Device buffers kept between the tracers of one device (a session's jobs).
// A tracer takes each buffer it needs by role ("histogram 0", "lights", ...)
// and gives them back when destroyed; the next tracer reuses a buffer whose
// capacity fits and allocates only when it does not. A reused buffer may be
// larger than asked: users keep their own sizes and zero what they count into.
class TracerBufferPool {
 public:
  // `usage`: what the buffer needs beyond storage and transfers (a reused
  // buffer has at least that).
  vk_util::Buffer take(const vk_util::Context& context, const std::string& role, vk::DeviceSize bytes,
                       vk_util::MemoryPlacement placement, vk::BufferUsageFlags usage = {});
  // Keeps the larger of `buffer` and any buffer already held for `role`.
  void giveBack(const std::string& role, vk_util::Buffer buffer);
  // Buffers allocated so far (reuses not counted).
  uint64_t allocations() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, vk_util::Buffer> free_;
  uint64_t allocations_ = 0;
};

// One of the scene's tables on the device: its buffer, bound at `binding`
// and, for a table the trace may read as a uniform buffer
// (uniform_tables.h), at `uniformBinding` over its first uniformBytes.
struct SceneTableBuffer {
  device::TraceBinding binding;
  std::string role;  // its name in the buffer pool
  vk_util::Buffer buffer;
  std::optional<device::TraceBinding> uniformBinding;
  vk::DeviceSize uniformBytes = 0;
};

class VulkanTracer final : public Tracer {
 public:
  // `specialisedFeatures` (SpecialisedFeature bits): the scene features the
  // trace pipeline is compiled for (absent light types, light choice,
  // pinhole, exact colour, aiming, fixed by specialisation constants); the
  // others are decided at run time. kSpecialiseNone is the general pipeline.
  // `buffers`: where its device buffers come from and go back to (a
  // device's pool, shared by its tracers); null: a pool of its own.
  // `profileStage`: the bench's cost profile (shaders/profile.h); the
  // default traces the whole kernel.
  VulkanTracer(const vk_util::Context& context, const CompiledScene& plan, uint32_t workgroupSize = 64,
               uint32_t specialisedFeatures = kSpecialiseAll, std::shared_ptr<TracerBufferPool> buffers = nullptr,
               uint32_t profileStage = device::kProfileStageFull);
  ~VulkanTracer() override;
  VulkanTracer(const VulkanTracer&) = delete;
  VulkanTracer& operator=(const VulkanTracer&) = delete;

  DeviceKind kind() const override { return DeviceKind::Vulkan; }
  std::string deviceName() const override { return context_.info().name; }
  // Cancellation is checked between dispatches.
  uint64_t trace(uint64_t firstBeam, uint64_t beamCount, const std::atomic<bool>* cancel = nullptr) override;
  void clear() override;
  SpectralHistogram download() const override;
  void upload(const SpectralHistogram& histogram) override;
  RenderImage develop(const ResolveParameters& parameters, FilmSummary* summary = nullptr) override;
  std::vector<device::BeamRecord> traceRecorded(uint64_t firstBeam, uint32_t count) override;

  const HistogramSplit& split() const { return split_; }
  uint64_t maxBeamsPerDispatch() const;

 private:
  uint64_t countedBeamsOnDevice() const;  // the trace stats' count (weighted films only)
  const vk_util::Context& context_;
  std::shared_ptr<TracerBufferPool> buffers_;  // declared before the buffers taken from it
  CompiledScene plan_;
  uint32_t workgroupSize_;
  UniformTableLayout uniformTables_;  // where the trace reads its tables (declared before them)
  std::vector<vk_util::SpecConstant> traceSpecialisation_;  // the scene's trace specialisation constants
  HistogramSplit split_;
  vk_util::Buffer traceConstants_;
  std::vector<SceneTableBuffer> sceneTables_;  // from sceneTableBuffers (vulkan_tracer.cpp), the one list
  vk_util::Buffer unusedBeamRecords_;  // bound where the record path is compiled out
  vk_util::Buffer stats_;  // TraceStats
  std::vector<uint64_t> histogramChunkBytes_;  // the used part of each chunk (a reused one may be larger)
  std::vector<vk_util::Buffer> histogramChunks_;
  // The film's first clear, on another thread while the trace pipeline
  // compiles (both take one core for tens of ms on lavapipe); the
  // constructor waits for it. Declared before the pipelines, so that if
  // one of them fails to build, the clear ends before the buffers go.
  std::future<void> firstClear_;
  vk_util::ComputePipeline tracePipeline_;
  vk_util::ComputePipeline resolvePipeline_;
  vk_util::TimestampQueries timestamps_;

  void bindTraceBuffers(vk_util::ComputePipeline& pipeline, const vk_util::Buffer& beamRecords) const;
};

// Philox words for beams [firstIndex, firstIndex + count) of one block,
// computed by the shader's Philox (to check it against the CPU's).
std::vector<glm::uvec4> philoxOnGpu(const vk_util::Context& context, uint64_t seed, uint64_t firstIndex,
                                    uint32_t count, uint32_t block);

}  // namespace spectrace
