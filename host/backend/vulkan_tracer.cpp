#include "backend/vulkan_tracer.h"

#include <algorithm>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "compile/packed_bvh.h"
#include "embedded_shaders.h"
#include "json/scene_error.h"
#include "scene/scene_limits.h"

namespace spectrace {

using vk_util::Buffer;
using vk_util::MemoryPlacement;

// resolve.comp's bin loop must stay under llvmpipe's 65535 iterations for
// the largest spectrum a scene may have.
static_assert(kMaxBins / device::kResolveBinsPerIteration < 65535, "resolve.comp's bin loop would be cut short");

namespace {

// The trace's small tables are bound as storage buffers and, when they fit
// (uniform_tables.h), also as uniform buffers.
constexpr vk::BufferUsageFlags kTableUsage = vk::BufferUsageFlagBits::eUniformBuffer;

template <typename T>
Buffer uploadedBuffer(TracerBufferPool& pool, const vk_util::Context& context, const std::string& role,
                      const std::vector<T>& data, vk::BufferUsageFlags usage = {}) {
  Buffer buffer = pool.take(context, role, std::max<vk::DeviceSize>(sizeof(T) * data.size(), 16), MemoryPlacement::DeviceLocal,
                            usage);
  buffer.upload(data.data(), sizeof(T) * data.size());
  return buffer;
}

template <typename T>
SceneTableBuffer tableBuffer(TracerBufferPool& pool, const vk_util::Context& context, device::TraceBinding binding,
                             const std::string& role, const std::vector<T>& data,
                             std::optional<device::TraceBinding> uniformBinding = std::nullopt,
                             vk::DeviceSize uniformBytes = 0) {
  return {binding, role, uploadedBuffer(pool, context, role, data, uniformBinding ? kTableUsage : vk::BufferUsageFlags{}),
          uniformBinding, uniformBytes};
}

// tableBuffer of `data` padded to `length` elements (a copy only where
// padding is needed: a mesh's tables are tens of MB).
template <typename T>
SceneTableBuffer paddedTableBuffer(TracerBufferPool& pool, const vk_util::Context& context,
                                   device::TraceBinding binding, const std::string& role, const std::vector<T>& data,
                                   uint32_t length, device::TraceBinding uniformBinding, vk::DeviceSize uniformBytes) {
  if (data.size() >= length) return tableBuffer(pool, context, binding, role, data, uniformBinding, uniformBytes);
  return tableBuffer(pool, context, binding, role, paddedTable(data, length), uniformBinding, uniformBytes);
}

// The scene's tables, the one list: what each holds and where it is bound.
// Scene objects' tables hold one zero element when there are none. A new
// kind of data for the kernel belongs in the scene data (no new binding).
std::vector<SceneTableBuffer> sceneTableBuffers(TracerBufferPool& pool, const vk_util::Context& context,
                                                const CompiledScene& plan, const UniformTableLayout& uniform) {
  using namespace device;
  const DeviceScene& s = plan.device;
  std::vector<SceneTableBuffer> tables;
  tables.push_back(paddedTableBuffer(pool, context, kBindingLights, "lights", s.lights, uniform.lights,
                                     kBindingLightsUniform, uniform.lightBytes()));
  tables.push_back(paddedTableBuffer(pool, context, kBindingSpectralIntervals, "intervals", s.intervals,
                                     uniform.intervals, kBindingSpectralIntervalsUniform, uniform.intervalBytes()));
  tables.push_back(paddedTableBuffer(pool, context, kBindingAliasColumns, "alias columns", s.aliasColumns,
                                     uniform.aliasColumns, kBindingAliasColumnsUniform, uniform.aliasColumnBytes()));
  tables.push_back(paddedTableBuffer(pool, context, kBindingCmfTable, "cmf table", s.cmfTable, uniform.cmfNodes,
                                     kBindingCmfTableUniform, uniform.cmfBytes()));
  tables.push_back(paddedTableBuffer(pool, context, kBindingPrimitives, "primitives", s.primitives, uniform.primitives,
                                     kBindingPrimitivesUniform, uniform.primitiveBytes()));
  tables.push_back(paddedTableBuffer(pool, context, kBindingBvhNodes, "bvh nodes", packBvhNodes(s.bvhNodes), uniform.bvhNodes,
                                     kBindingBvhNodesUniform, uniform.bvhNodeBytes()));
  tables.push_back(paddedTableBuffer(pool, context, kBindingMaterials, "materials", s.materials, uniform.materials,
                                     kBindingMaterialsUniform, uniform.materialBytes()));
  tables.push_back(tableBuffer(pool, context, kBindingSceneData, "scene data", s.data.words()));
  return tables;
}

std::shared_ptr<TracerBufferPool> poolOrOwn(std::shared_ptr<TracerBufferPool> pool) {
  return pool ? std::move(pool) : std::make_shared<TracerBufferPool>();
}

}  // namespace

Buffer TracerBufferPool::take(const vk_util::Context& context, const std::string& role, vk::DeviceSize bytes,
                              MemoryPlacement placement, vk::BufferUsageFlags usage) {
  {
    const std::lock_guard lock(mutex_);
    const auto it = free_.find(role);
    if (it != free_.end() && it->second.size() >= bytes && it->second.placement() == placement &&
        (it->second.usage() & usage) == usage) {
      Buffer reused = std::move(it->second);
      free_.erase(it);
      return reused;
    }
    ++allocations_;
  }
  return Buffer(context, bytes, usage, placement);
}

void TracerBufferPool::giveBack(const std::string& role, Buffer buffer) {
  if (!buffer.handle()) return;
  const std::lock_guard lock(mutex_);
  auto [it, added] = free_.try_emplace(role, std::move(buffer));
  if (!added && it->second.size() < buffer.size()) it->second = std::move(buffer);
}

uint64_t TracerBufferPool::allocations() const {
  const std::lock_guard lock(mutex_);
  return allocations_;
}

std::vector<vk_util::BindingSpec> bindingSpecs(std::span<const device::BindingSlot> table) {
  std::vector<vk_util::BindingSpec> specs;
  for (const auto& slot : table) specs.push_back({slot.binding, slot.count, slot.uniform});
  return specs;
}

namespace {

// dispatchGridFor with this device's group-count limit.
vk_util::DispatchGrid dispatchShape(const vk_util::Context& context, uint64_t count, uint32_t workgroupSize) {
  return vk_util::dispatchGridFor(count, workgroupSize, context.info().maxComputeWorkGroupCount[0]);
}

// The scene specialisation constants of trace_beams.comp (device_shared.h,
// SpecConstantId): the scene's value for each feature in `features`, else
// the general pipeline's (decide at run time); and the profile stage (the
// profile's counting stage has exact colour off).
std::vector<vk_util::SpecConstant> traceSpecialisation(const CompiledScene& plan, uint32_t features,
                                                       uint32_t profileStage, const UniformTableLayout& tables) {
  uint32_t types = 0;
  bool aimed = false;
  for (const auto& light : plan.device.lights) {
    types |= 1u << light.type;
    aimed = aimed || light.aimed != 0;
  }
  uint32_t primitiveTypes = 0;
  for (const auto& primitive : plan.device.primitives) primitiveTypes |= 1u << primitive.type;
  uint32_t materialTypes = 0;
  for (const auto& material : plan.device.materials) materialTypes |= 1u << material.type;
  auto pick = [&](SpecialisedFeature f, uint32_t scene, uint32_t general) { return (features & f) ? scene : general; };
  return {{device::kSpecLightTypes, pick(kSpecialiseLightTypes, types, device::kAllLightTypes)},
          {device::kSpecSelectLight, pick(kSpecialiseLightChoice, plan.device.lights.size() > 1 ? 1u : 0u, 1u)},
          {device::kSpecCameraType,
           pick(kSpecialiseCameraType, plan.device.constants.cameraType, device::kCameraTypeAtRunTime)},
          {device::kSpecExactColour, profileStage <= device::kProfileStageCounting
                                         ? 0u
                                         : pick(kSpecialiseExactColour, plan.film.exactColour ? 1u : 0u, 2u)},
          {device::kSpecAim, pick(kSpecialiseAim, aimed ? 1u : 0u, 2u)},
          {device::kSpecProfileStage, std::min<uint32_t>(profileStage, device::kProfileStageObjectsNoConnection)},
          {device::kSpecUniformTables, tables.inUniform ? 1u : 0u},
          {device::kSpecUniformLights, tables.lights},
          {device::kSpecUniformIntervals, tables.intervals},
          {device::kSpecUniformCmfNodes, tables.cmfNodes},
          {device::kSpecUniformAliasColumns, tables.aliasColumns},
          {device::kSpecUniformObjects, tables.objectsInUniform ? 1u : 0u},
          {device::kSpecUniformPrimitives, tables.primitives},
          {device::kSpecUniformBvhNodes, tables.bvhNodes},
          {device::kSpecUniformMaterials, tables.materials},
          {device::kSpecObjects, plan.device.primitives.empty() ? 0u : 1u},
          {device::kSpecCameraPaths, (plan.device.constants.estimators & device::kEstimatorCameraPaths) != 0 ? 1u : 0u},
          {device::kSpecPrimitiveTypes, pick(kSpecialiseObjectTypes, primitiveTypes, device::kAllPrimitiveTypes)},
          {device::kSpecMaterialTypes, pick(kSpecialiseObjectTypes, materialTypes, device::kAllMaterialTypes)}};
}

// The trace shader's module: with camera paths compiled in only where the
// scene's estimators include them (trace_camera_paths.comp); lavapipe takes
// several times as long to compile that one. The bench's profile stages
// have modules of their own (trace_*_profile.comp), so that a render's
// module holds the kernel once.
std::span<const unsigned char> traceModule(const CompiledScene& plan, uint32_t profileStage) {
  const bool cameraPaths = (plan.device.constants.estimators & device::kEstimatorCameraPaths) != 0;
  if (profileStage != device::kProfileStageFull)
    return cameraPaths ? embedded::spv_trace_camera_paths_profile() : embedded::spv_trace_beams_profile();
  return cameraPaths ? embedded::spv_trace_camera_paths() : embedded::spv_trace_beams();
}

// Whether the trace pass counts counted beams itself: only when beams carry
// fractional weights. Otherwise each counted beam adds exactly one unit to
// one bin, and the sum of the bins is the count.
bool countsBeamsOnDevice(const CompiledScene& plan) { return plan.film.weightUnits != 1; }

// All specialisation constants of the trace pipeline.
std::vector<vk_util::SpecConstant> specConstants(uint32_t workgroupSize, bool record, const HistogramSplit& split,
                                                 bool countBeams, const std::vector<vk_util::SpecConstant>& scene) {
  std::vector<vk_util::SpecConstant> constants = {{device::kSpecWorkgroupSize, workgroupSize},
                                                  {device::kSpecRecordBeams, record ? 1u : 0u},
                                                  {device::kSpecHistogramChunks, split.chunkCount},
                                                  {device::kSpecCountBeams, countBeams ? 1u : 0u}};
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

void checkSceneFitsDevice(const CompiledScene& plan, uint64_t maxStorageBufferRange, uint64_t deviceLocalHeapBytes,
                          const std::string& deviceName) {
  // The intervals and their alias columns (up to twice as many) are each
  // one storage buffer.
  const uint64_t tableBytes = std::max(plan.device.intervals.size() * sizeof(device::SpectralInterval),
                                       plan.device.aliasColumns.size() * sizeof(device::AliasColumn));
  if (tableBytes > maxStorageBufferRange) {
    // Name the light with the largest table: the field to make coarser.
    size_t largest = 0;
    for (size_t i = 1; i < plan.device.lights.size(); ++i)
      if (plan.device.lights[i].spectralCount > plan.device.lights[largest].spectralCount) largest = i;
    std::string label = "/lights";
    size_t traced = 0;
    for (const LightSummary& s : plan.summaries)
      if (s.traced && traced++ == largest) label = s.label;
    throw SceneError(fmt::format(
        "/lights/*/spd: the spectral tables need {} bytes on the device ({} intervals; the largest, {}, has {}), more "
        "than the {} bytes of one storage buffer (maxStorageBufferRange of {}); use fewer table rows or lights, or "
        "--device cpu",
        tableBytes, plan.device.intervals.size(), label, plan.device.lights[largest].spectralCount,
        maxStorageBufferRange, deviceName));
  }
  const uint64_t objectBytes = std::max({plan.device.primitives.size() * sizeof(device::Primitive),
                                          plan.device.bvhNodes.size() * sizeof(device::PackedBvhNode),
                                          plan.device.materials.size() * sizeof(device::Material),
                                          plan.device.data.words().size() * sizeof(uint32_t)});
  if (objectBytes > maxStorageBufferRange)
    throw SceneError(fmt::format(
        "/objects: the objects' {} primitives, {} BVH nodes, {} materials and {} words of scene data need {} bytes in "
        "one storage buffer, more than the {} bytes of maxStorageBufferRange of {}; use fewer triangles or objects, "
        "or --device cpu",
        plan.device.primitives.size(), plan.device.bvhNodes.size(), plan.device.materials.size(),
        plan.device.data.words().size(), objectBytes, maxStorageBufferRange, deviceName));
  const uint64_t filmBytes = plan.film.storedCounterCount() * sizeof(uint64_t);
  if (deviceLocalHeapBytes > 0 && filmBytes > deviceLocalHeapBytes)
    throw SceneError(fmt::format(
        "/camera/sensor/pixels: the film ({}x{} pixels, {} counters each) needs {} bytes of device memory, more than "
        "the {} bytes of {}; use fewer pixels or bins",
        plan.film.window.width, plan.film.window.height, plan.film.countersPerPixel(), filmBytes, deviceLocalHeapBytes,
        deviceName));
}

namespace {

// The bytes of the film's stored pixels in each chunk.
std::vector<uint64_t> filmChunkBytes(const FilmLayout& film, const HistogramSplit& split) {
  std::vector<uint64_t> bytes;
  const uint64_t pixelBytes = uint64_t(film.countersPerPixel()) * sizeof(uint64_t);
  for (uint32_t c = 0; c < split.chunkCount; ++c)
    bytes.push_back(
        std::min<uint64_t>(split.pixelsPerChunk, film.storedPixelCount() - uint64_t(c) * split.pixelsPerChunk) *
        pixelBytes);
  return bytes;
}

std::vector<Buffer> takeFilmChunks(const vk_util::Context& context, const std::vector<uint64_t>& bytes,
                                   TracerBufferPool& buffers) {
  std::vector<Buffer> chunks;
  for (size_t c = 0; c < bytes.size(); ++c)
    chunks.push_back(buffers.take(context, fmt::format("histogram {}", c), bytes[c], MemoryPlacement::DeviceLocal));
  return chunks;
}

}  // namespace

VulkanTracer::VulkanTracer(const vk_util::Context& context, const CompiledScene& plan, uint32_t workgroupSize,
                           uint32_t specialisedFeatures, std::shared_ptr<TracerBufferPool> buffers,
                           uint32_t profileStage)
    : context_(context),
      buffers_(poolOrOwn(std::move(buffers))),
      plan_(plan),
      workgroupSize_(workgroupSize),
      uniformTables_(uniformTableLayout(plan.device, context.info().maxUniformBufferRange,
                                        (specialisedFeatures & kSpecialiseUniformTables) != 0)),
      traceSpecialisation_(traceSpecialisation(plan, specialisedFeatures, profileStage, uniformTables_)),
      split_((checkSceneFitsDevice(plan, context.info().maxStorageBufferRange, context.info().deviceLocalHeapBytes,
                                   context.info().name),
              HistogramSplit::forDevice(plan.film.storedPixelCount(), plan.film.countersPerPixel(),
                                        context.info().maxStorageBufferRange, context.info().maxMemoryAllocationSize))),
      traceConstants_(buffers_->take(context, "trace constants", sizeof(device::TraceConstants), MemoryPlacement::DeviceLocal,
                                     vk::BufferUsageFlagBits::eUniformBuffer)),
      sceneTables_(sceneTableBuffers(*buffers_, context, plan, uniformTables_)),
      unusedBeamRecords_(buffers_->take(context, "unused beam records", 16, MemoryPlacement::DeviceLocal)),
      stats_(buffers_->take(context, "trace stats", sizeof(device::TraceStats), MemoryPlacement::HostVisible)),
      histogramChunkBytes_(filmChunkBytes(plan.film, split_)),
      histogramChunks_(takeFilmChunks(context, histogramChunkBytes_, *buffers_)),
      firstClear_(std::async(std::launch::async, [this] { clear(); })),
      tracePipeline_(context, traceModule(plan, profileStage), bindingSpecs(device::kTraceBindings),
                     sizeof(device::TracePush), specConstants(workgroupSize, false, split_, countsBeamsOnDevice(plan), traceSpecialisation_)),
      resolvePipeline_(context, embedded::spv_resolve(), bindingSpecs(device::kResolveBindings),
                       sizeof(device::ResolvePush),
                       {{device::kSpecWorkgroupSize, workgroupSize}, {device::kSpecHistogramChunks, split_.chunkCount}}),
      timestamps_(context, 2) {
  plan_.device.constants.pixelsPerChunk = split_.pixelsPerChunk;
  if (profileStage <= device::kProfileStageCounting) plan_.device.constants.exactColour = 0;
  if (profileStage == device::kProfileStageObjectsNoConnection) plan_.device.constants.connect = 0;
  traceConstants_.upload(&plan_.device.constants, sizeof(plan_.device.constants));
  firstClear_.get();  // rethrows the clear's failure
  bindTraceBuffers(tracePipeline_, unusedBeamRecords_);
  for (uint32_t c = 0; c < device::kMaxHistogramChunks; ++c)
    resolvePipeline_.bindBuffer(device::kBindingResolveHistogram, c, histogramChunks_[c < split_.chunkCount ? c : 0]);
}

VulkanTracer::~VulkanTracer() {
  buffers_->giveBack("trace constants", std::move(traceConstants_));
  for (SceneTableBuffer& table : sceneTables_) buffers_->giveBack(table.role, std::move(table.buffer));
  buffers_->giveBack("unused beam records", std::move(unusedBeamRecords_));
  buffers_->giveBack("trace stats", std::move(stats_));
  for (size_t c = 0; c < histogramChunks_.size(); ++c)
    buffers_->giveBack(fmt::format("histogram {}", c), std::move(histogramChunks_[c]));
}

void VulkanTracer::bindTraceBuffers(vk_util::ComputePipeline& pipeline, const Buffer& beamRecords) const {
  pipeline.bindBuffer(device::kBindingTraceConstants, 0, traceConstants_);
  pipeline.bindBuffer(device::kBindingBeamRecords, 0, beamRecords);
  for (const SceneTableBuffer& table : sceneTables_) {
    pipeline.bindBuffer(table.binding, 0, table.buffer);
    // The uniform copy: the padded table (the same buffer), or its first
    // element when the storage buffer is read.
    if (table.uniformBinding) pipeline.bindBuffer(*table.uniformBinding, 0, table.buffer, 0, table.uniformBytes);
  }
  pipeline.bindBuffer(device::kBindingTraceStats, 0, stats_);
  // Unused chunk slots alias chunk 0: the descriptors must be valid even
  // though no pixel maps to them.
  for (uint32_t c = 0; c < device::kMaxHistogramChunks; ++c)
    pipeline.bindBuffer(device::kBindingHistogram, c, histogramChunks_[c < split_.chunkCount ? c : 0]);
}

void VulkanTracer::clear() {
  for (auto& chunk : histogramChunks_) chunk.fillZero();
  stats_.fillZero();
}

uint64_t VulkanTracer::maxBeamsPerDispatch() const {
  const auto& limits = context_.info().maxComputeWorkGroupCount;
  const uint64_t perDispatch = uint64_t(limits[0]) * limits[1] * workgroupSize_;
  return std::min<uint64_t>(perDispatch, uint64_t(1) << 31);
}

uint64_t VulkanTracer::trace(uint64_t firstBeam, uint64_t beamCount, const std::atomic<bool>* cancel) {
  uint64_t done = 0;
  while (done < beamCount) {
    if (cancel && cancel->load()) break;
    const uint64_t count = std::min(beamCount - done, maxBeamsPerDispatch());
    const vk_util::DispatchGrid shape = dispatchShape(context_, count, workgroupSize_);
    const device::TracePush push{firstBeam + done, uint32_t(count), shape.invocationsPerRow};
    context_.submitAndWait([&](const vk::raii::CommandBuffer& cb) {
      timestamps_.reset(cb);
      timestamps_.write(cb, 0);
      tracePipeline_.recordDispatch(cb, &push, shape.groupsX, shape.groupsY);
      timestamps_.write(cb, 1);
    });
    const auto ns = timestamps_.readNanoseconds();
    if (ns.size() == 2) traceDeviceSeconds_ += (ns[1] - ns[0]) * 1e-9;
    done += count;
  }
  return done;
}

std::vector<device::BeamRecord> VulkanTracer::traceRecorded(uint64_t firstBeam, uint32_t count) {
  vk_util::ComputePipeline recorder(context_, traceModule(plan_, device::kProfileStageFull),
                                    bindingSpecs(device::kTraceBindings), sizeof(device::TracePush),
                                    specConstants(workgroupSize_, true, split_, countsBeamsOnDevice(plan_), traceSpecialisation_));
  Buffer records(context_, std::max<uint64_t>(uint64_t(count) * sizeof(device::BeamRecord), 16), {},
                 MemoryPlacement::HostVisible);
  bindTraceBuffers(recorder, records);  // the counters and stats are left untouched in record mode
  const vk_util::DispatchGrid shape = dispatchShape(context_, count, workgroupSize_);
  const device::TracePush push{firstBeam, count, shape.invocationsPerRow};
  context_.submitAndWait([&](const vk::raii::CommandBuffer& cb) { recorder.recordDispatch(cb, &push, shape.groupsX, shape.groupsY); });
  std::vector<device::BeamRecord> result(count);
  records.download(result.data(), uint64_t(count) * sizeof(device::BeamRecord));
  return result;
}

std::vector<glm::uvec4> philoxOnGpu(const vk_util::Context& context, uint64_t seed, uint64_t firstIndex, uint32_t count,
                                    uint32_t block) {
  constexpr uint32_t kWorkgroup = 64;
  vk_util::ComputePipeline pipeline(context, embedded::spv_rng_check(), bindingSpecs(device::kRngCheckBindings),
                                    sizeof(device::RngCheckPush), {{device::kSpecWorkgroupSize, kWorkgroup}});
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

uint64_t VulkanTracer::countedBeamsOnDevice() const {
  device::TraceStats stats{};
  stats_.download(&stats, sizeof(stats));
  return stats.countedBeams;
}

SpectralHistogram VulkanTracer::download() const {
  SpectralHistogram histogram = plan_.film.emptyHistogram();
  std::vector<uint64_t> counters;
  size_t pixel = 0;
  for (size_t c = 0; c < histogramChunks_.size(); ++c) {
    counters.resize(histogramChunkBytes_[c] / sizeof(uint64_t));
    histogramChunks_[c].download(counters.data(), histogramChunkBytes_[c]);
    unpackDeviceCounters(counters, plan_.film, pixel, histogram);
    pixel += counters.size() / plan_.film.countersPerPixel();
  }
  histogram.countedBeams = countsBeamsOnDevice(plan_) ? countedBeamsOnDevice() : histogram.plainHits();
  return histogram;
}

void VulkanTracer::upload(const SpectralHistogram& histogram) {
  if (!plan_.film.hasShapeOf(histogram))
    throw std::invalid_argument("VulkanTracer::upload: the histogram's shape differs from the film's");
  const device::TraceStats stats{histogram.countedBeams};
  stats_.upload(&stats, sizeof(stats));
  std::vector<uint64_t> counters;
  size_t pixel = 0;
  for (size_t c = 0; c < histogramChunks_.size(); ++c) {
    counters.resize(histogramChunkBytes_[c] / sizeof(uint64_t));
    packDeviceCounters(histogram, plan_.film, pixel, counters);
    histogramChunks_[c].upload(counters.data(), histogramChunkBytes_[c]);
    pixel += counters.size() / plan_.film.countersPerPixel();
  }
}

device::ResolveConstants resolveConstants(const CompiledScene& plan, const ResolveParameters& parameters,
                                          uint32_t pixelsPerChunk) {
  device::ResolveConstants constants{};
  constants.pixelCount = uint32_t(plan.film.storedPixelCount());
  constants.bins = plan.film.storedBins;
  constants.pixelsPerChunk = pixelsPerChunk;
  constants.countersPerPixel = plan.film.countersPerPixel();
  constants.exactColour = parameters.useExactColour && plan.film.exactColour ? 1u : 0u;
  constants.squaredWeightOffset =
      plan.film.weighted() ? device::squaredWeightCounterOffset(plan.film.storedBins, plan.film.exactColour) : 0u;
  constants.irradiancePerCount = float(parameters.irradiancePerCount);
  const double perBeam = parameters.irradiancePerCount * double(plan.film.weightUnits);
  constants.xyzPerColourUnit = float(683.0 * perBeam / double(device::colourUnitsPerCmf(plan.film.weighted())));
  constants.weighted = plan.film.weighted() ? 1u : 0u;
  // glm is column-major: row r of M is (M[0][r], M[1][r], M[2][r]).
  const glm::dmat3& m = parameters.xyzToRgb;
  constants.xyzToRgbRow0 = glm::vec3(m[0][0], m[1][0], m[2][0]);
  constants.xyzToRgbRow1 = glm::vec3(m[0][1], m[1][1], m[2][1]);
  constants.xyzToRgbRow2 = glm::vec3(m[0][2], m[1][2], m[2][2]);
  return constants;
}

std::vector<glm::vec3> storedBinWeights(const CompiledScene& plan, const ResolveParameters& parameters) {
  std::vector<glm::vec3> weights;
  for (uint32_t b = plan.film.firstStoredBin; b < plan.film.firstStoredBin + plan.film.storedBins; ++b) {
    const auto& w = parameters.binWeights[b];
    weights.emplace_back(float(w[0]), float(w[1]), float(w[2]));
  }
  return weights;
}

RenderImage VulkanTracer::develop(const ResolveParameters& parameters, FilmSummary* summary) {
  const device::ResolveConstants constants = resolveConstants(plan_, parameters, split_.pixelsPerChunk);
  const uint64_t pixelCount = plan_.film.storedPixelCount();  // only stored pixels are resolved; the others are 0
  const std::vector<glm::vec3> weights = storedBinWeights(plan_, parameters);

  Buffer constantsBuffer = buffers_->take(context_, "resolve constants", sizeof(constants), MemoryPlacement::DeviceLocal);
  constantsBuffer.upload(&constants, sizeof(constants));
  Buffer weightsBuffer = uploadedBuffer(*buffers_, context_, "bin weights", weights);
  const uint64_t maxSliceByRange = std::min<uint64_t>(
      pixelCount, std::min(context_.info().maxStorageBufferRange, context_.info().maxMemoryAllocationSize) /
                      sizeof(device::ResolvedPixel));
  // One row of workgroups per slice.
  const uint64_t maxSlice = std::min<uint64_t>(maxSliceByRange, uint64_t(context_.info().maxComputeWorkGroupCount[0]) * workgroupSize_);
  Buffer output = buffers_->take(context_, "resolved pixels", maxSlice * sizeof(device::ResolvedPixel), MemoryPlacement::HostVisible);
  resolvePipeline_.bindBuffer(device::kBindingResolveConstants, 0, constantsBuffer);
  resolvePipeline_.bindBuffer(device::kBindingBinWeights, 0, weightsBuffer);
  resolvePipeline_.bindBuffer(device::kBindingResolvedPixels, 0, output);

  RenderImage image;
  image.width = int(plan_.film.pixelsX);
  image.height = int(plan_.film.pixelsY);
  image.rgb.assign(plan_.film.pixelCount() * 3, 0.0f);
  image.xyz.assign(plan_.film.pixelCount() * 3, 0.0f);
  image.irradiance.assign(plan_.film.pixelCount(), 0.0f);
  if (parameters.beams > 0) image.irradianceError.assign(plan_.film.pixelCount(), 0.0f);
  uint64_t totalCount = 0;  // over every pixel's bins
  FilmSummary totals;
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
      const size_t p = plan_.film.fullPixelOfStored(first + i);
      for (int k = 0; k < 3; ++k) {
        image.rgb[p * 3 + k] = slice[i].rgb[k];
        image.xyz[p * 3 + k] = slice[i].xyz[k];
      }
      image.irradiance[p] = slice[i].irradiance;
      // The error in double on the host, from the exact sums, as resolveOnCpu does.
      if (parameters.beams > 0)
        image.irradianceError[p] = irradianceErrorOfPixel(slice[i].totalCount, slice[i].squaredWeightCount,
                                                          parameters.beams, plan_.film.weightUnits,
                                                          parameters.irradiancePerCount, p);
      totalCount += slice[i].totalCount.low;  // (read only for a plain film, whose counters are one word)
      addToSummary(totals, slice[i].largestCount, slice[i].squaredWeightCount, plan_.film.weightUnits);
    }
  }
  developDeviceSeconds_ += deviceSeconds;
  if (summary) {
    // Counted on the device, or (every beam adds one unit) the bins' sum.
    totals.countedBeams = countsBeamsOnDevice(plan_) ? countedBeamsOnDevice() : totalCount;
    *summary = totals;
  }
  buffers_->giveBack("resolve constants", std::move(constantsBuffer));
  buffers_->giveBack("bin weights", std::move(weightsBuffer));
  buffers_->giveBack("resolved pixels", std::move(output));
  return image;
}

}  // namespace spectrace
