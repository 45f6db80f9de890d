#include "backend/cpu_tracer.h"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>
#include <thread>
#include <new>
#include <span>
#include <cstdint>

#include <sys/mman.h>

#include "kernel/beam_kernel.h"

namespace spectrace {

template <typename T>
T* HugePageAllocator<T>::allocate(size_t n) {
  const size_t bytes = mappedBytes(n);
  // Map an extra 2 MiB and trim, so the array starts on a 2 MiB boundary.
  void* mapped = ::mmap(nullptr, bytes + kAlignment, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) throw std::bad_alloc();
  const auto start = reinterpret_cast<uintptr_t>(mapped);
  const uintptr_t aligned = (start + kAlignment - 1) / kAlignment * kAlignment;
  if (aligned > start) ::munmap(mapped, aligned - start);
  if (const size_t tail = start + bytes + kAlignment - (aligned + bytes); tail > 0)
    ::munmap(reinterpret_cast<void*>(aligned + bytes), tail);
  ::madvise(reinterpret_cast<void*>(aligned), bytes, MADV_HUGEPAGE);  // a hint: failure changes nothing
  return reinterpret_cast<T*>(aligned);
}

template <typename T>
void HugePageAllocator<T>::deallocate(T* p, size_t n) {
  ::munmap(p, mappedBytes(n));
}

template struct HugePageAllocator<uint64_t>;

namespace {

// A thread's queued film adds: one group fills while the other's prefetched
// lines arrive (device::PendingCounts).
struct CountQueues {
  explicit CountQueues(std::span<uint64_t> counters) : groups{device::PendingCounts(counters), device::PendingCounts(counters)} {}
  device::PendingCounts groups[2];
  size_t filling = 0;
};

// Beams firstBeam + [from, to) through `kernel` (whose pending adds go to `queues`),
// the whole kernel or the profile's stage; returns the beams counted. Its
// two copies below differ only in their target: each is flattened (every
// call inlined), so the whole kernel is compiled into each, and no shared
// inline function is emitted out of line with another target's
// instructions (which the linker might then pick for the baseline).
// (Offsets from firstBeam, so that a range ending at 2^64 does not wrap.)
inline uint64_t traceBlockBody(device::BeamKernel& kernel, CountQueues& queues, uint64_t firstBeam, uint64_t from,
                               uint64_t to, uint32_t profileStage) {
  kernel.pending = &queues.groups[queues.filling];
  const bool wholeKernel = profileStage == device::kProfileStageFull;
  uint64_t counted = 0;
  for (uint64_t i = from; i < to; ++i) {
    const bool hit =
        wholeKernel ? kernel.traceAndCountBeam(firstBeam + i) : kernel.profileBeam(firstBeam + i, profileStage);
    counted += hit ? 1 : 0;
    if (queues.groups[queues.filling].full()) {
      queues.filling ^= 1;
      queues.groups[queues.filling].flush();
      kernel.pending = &queues.groups[queues.filling];
    }
  }
  return counted;
}

// Beams [first, first + count) recorded, not counted (traceRecorded).
inline void recordBeamsBody(device::BeamKernel& kernel, uint64_t first, uint32_t count, device::BeamRecord* records) {
  for (uint32_t i = 0; i < count; ++i) records[i] = kernel.record(first + i);
}

// flatten inlines the whole kernel into each of the four entry points below,
// which is what makes the CPU reference fast. Under AddressSanitizer it
// makes this one file take over four minutes to compile (four instrumented
// copies of the kernel), and speed is not what that build is for: there the
// entry points call the kernel as compiled once.
// (GCC says so with __SANITIZE_ADDRESS__, clang with __has_feature.)
#if defined(__SANITIZE_ADDRESS__)
#define SPECTRACE_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SPECTRACE_UNDER_ASAN 1
#endif
#endif
#if defined(SPECTRACE_UNDER_ASAN)
#define SPECTRACE_FLATTEN
#else
#define SPECTRACE_FLATTEN __attribute__((flatten))
#endif

SPECTRACE_FLATTEN uint64_t traceBlockBaseline(device::BeamKernel& kernel, CountQueues& queues, uint64_t firstBeam,
                                              uint64_t from, uint64_t to, uint32_t profileStage) {
  return traceBlockBody(kernel, queues, firstBeam, from, to, profileStage);
}
SPECTRACE_FLATTEN void recordBeamsBaseline(device::BeamKernel& kernel, uint64_t first, uint32_t count,
                                           device::BeamRecord* records) {
  recordBeamsBody(kernel, first, count, records);
}

#if defined(__x86_64__)
#define SPECTRACE_HAS_X86_64_V3 1
SPECTRACE_FLATTEN __attribute__((target("arch=x86-64-v3"))) uint64_t traceBlockV3(device::BeamKernel& kernel,
                                                                                  CountQueues& queues,
                                                                                  uint64_t firstBeam, uint64_t from,
                                                                                  uint64_t to, uint32_t profileStage) {
  return traceBlockBody(kernel, queues, firstBeam, from, to, profileStage);
}
SPECTRACE_FLATTEN __attribute__((target("arch=x86-64-v3"))) void recordBeamsV3(device::BeamKernel& kernel,
                                                                               uint64_t first, uint32_t count,
                                                                               device::BeamRecord* records) {
  recordBeamsBody(kernel, first, count, records);
}
#else
#define SPECTRACE_HAS_X86_64_V3 0
#endif

uint64_t traceBlock(CpuCode code, device::BeamKernel& kernel, CountQueues& queues, uint64_t firstBeam, uint64_t from,
                    uint64_t to, uint32_t profileStage) {
#if SPECTRACE_HAS_X86_64_V3
  if (code == CpuCode::X86_64_V3) return traceBlockV3(kernel, queues, firstBeam, from, to, profileStage);
#endif
  return traceBlockBaseline(kernel, queues, firstBeam, from, to, profileStage);
}

void recordBeams(CpuCode code, device::BeamKernel& kernel, uint64_t first, uint32_t count, device::BeamRecord* records) {
#if SPECTRACE_HAS_X86_64_V3
  if (code == CpuCode::X86_64_V3) return recordBeamsV3(kernel, first, count, records);
#endif
  recordBeamsBaseline(kernel, first, count, records);
}

}  // namespace

bool cpuRuns(CpuCode code) {
  if (code == CpuCode::Baseline) return true;
#if SPECTRACE_HAS_X86_64_V3
  // The checks include the operating system's support for AVX state.
  __builtin_cpu_init();
#if defined(__clang__)
  // Clang 14 names no architecture levels here: the features x86-64-v3
  // adds that it does name (LZCNT, MOVBE and F16C come with them on every
  // processor that has AVX2, BMI2 and FMA).
  return __builtin_cpu_supports("avx") && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi") &&
         __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("popcnt") &&
         __builtin_cpu_supports("sse4.2");
#else
  return __builtin_cpu_supports("x86-64-v3");
#endif
#else
  return false;
#endif
}

CpuCode fastestCpuCode() { return cpuRuns(CpuCode::X86_64_V3) ? CpuCode::X86_64_V3 : CpuCode::Baseline; }

const char* cpuCodeName(CpuCode code) { return code == CpuCode::X86_64_V3 ? "x86-64-v3" : "baseline"; }

std::optional<CpuCode> cpuCodeNamed(std::string_view name) {
  for (CpuCode code : {CpuCode::Baseline, CpuCode::X86_64_V3})
    if (name == cpuCodeName(code)) return code;
  return std::nullopt;
}

CpuTracer::CpuTracer(const CompiledScene& plan, unsigned threads, uint32_t profileStage, CpuCode code)
    : plan_(plan),
      threads_(threads ? threads : std::max(1u, std::thread::hardware_concurrency())),
      profileStage_(std::min<uint32_t>(profileStage, device::kProfileStageObjectsNoConnection)),
      code_(code),
      counters_(plan.film.storedCounterCount()) {  // zero, untouched (HugePageAllocator)
  if (!cpuRuns(code))
    throw std::invalid_argument(fmt::format("CpuTracer: this processor cannot run the {} code", cpuCodeName(code)));
  // One chunk holds every stored pixel.
  plan_.device.constants.pixelsPerChunk = uint32_t(std::max<uint64_t>(1, plan.film.storedPixelCount()));
  // The profile's counting stage counts bins only (shaders/profile.h).
  if (profileStage_ <= device::kProfileStageCounting) plan_.device.constants.exactColour = 0;
  if (profileStage_ == device::kProfileStageObjectsNoConnection) plan_.device.constants.connect = 0;
}

std::string CpuTracer::deviceName() const {
  return fmt::format("CPU reference, {} threads, {}", threads_, cpuCodeName(code_));
}

uint64_t CpuTracer::trace(uint64_t firstBeam, uint64_t beamCount, const std::atomic<bool>* cancel) {
  const device::BeamKernel kernel = beamKernel(counters_);
  std::atomic<uint64_t> counted{0};
  // Threads take blocks of beams in order. When cancelled, each finishes
  // its block, so the traced beams stay one contiguous prefix. Blocks are
  // small enough that every thread gets several (a short batch keeps both
  // cores busy) and a cancel is seen soon; the counts do not depend on them.
  const uint64_t blockBeams = std::clamp<uint64_t>(beamCount / (uint64_t(threads_) * 4), 1 << 8, 1 << 16);
  const uint64_t blockCount = (beamCount + blockBeams - 1) / blockBeams;
  std::atomic<uint64_t> nextBlock{0};
  std::atomic<uint64_t> stoppedAtBlock{blockCount};
  auto worker = [&] {
    device::BeamKernel local = kernel;
    CountQueues queues(counters_);
    uint64_t countedHere = 0;
    for (;;) {
      const uint64_t block = nextBlock.fetch_add(1, std::memory_order_relaxed);
      if (block >= blockCount) break;
      if (cancel && cancel->load(std::memory_order_relaxed)) {
        uint64_t expected = stoppedAtBlock.load();
        while (block < expected && !stoppedAtBlock.compare_exchange_weak(expected, block)) {}
        break;
      }
      const uint64_t end = std::min(beamCount, (block + 1) * blockBeams);
      countedHere += traceBlock(code_, local, queues, firstBeam, block * blockBeams, end, profileStage_);
    }
    queues.groups[0].flush();
    queues.groups[1].flush();
    counted.fetch_add(countedHere, std::memory_order_relaxed);
  };
  std::vector<std::jthread> pool;
  for (unsigned t = 1; t < threads_; ++t) pool.emplace_back(worker);
  worker();
  pool.clear();  // joins
  countedBeams_ += counted.load();
  return std::min(beamCount, stoppedAtBlock.load() * blockBeams);
}

device::BeamKernel CpuTracer::beamKernel(std::span<uint64_t> counters) const {
  const DeviceScene& scene = plan_.device;
  device::BeamKernel kernel(scene.constants, scene.lights, scene.intervals, scene.aliasColumns, scene.cmfTable, counters);
  kernel.setObjects(scene.primitives, scene.bvhNodes, scene.materials, scene.data.words());
  return kernel;
}

void CpuTracer::clear() {
  std::fill(counters_.begin(), counters_.end(), 0);
  countedBeams_ = 0;
}

SpectralHistogram CpuTracer::download() const {
  SpectralHistogram histogram = plan_.film.emptyHistogram();
  unpackDeviceCounters(counters_, plan_.film, 0, histogram);
  histogram.countedBeams = countedBeams_;
  return histogram;
}

void CpuTracer::upload(const SpectralHistogram& histogram) {
  if (!plan_.film.hasShapeOf(histogram))
    throw std::invalid_argument("CpuTracer::upload: the histogram's shape differs from the film's");
  packDeviceCounters(histogram, plan_.film, 0, counters_);
  countedBeams_ = histogram.countedBeams;
}

RenderImage CpuTracer::develop(const ResolveParameters& parameters, FilmSummary* summary) {
  RenderImage image = resolveStoredCountersOnCpu(counters_, plan_.film, parameters, summary);
  if (summary) summary->countedBeams = countedBeams_;
  return image;
}

std::vector<device::BeamRecord> CpuTracer::traceRecorded(uint64_t firstBeam, uint32_t count) {
  device::BeamKernel kernel = beamKernel({});
  std::vector<device::BeamRecord> records(count);
  recordBeams(code_, kernel, firstBeam, count, records.data());
  return records;
}

}  // namespace spectrace
