#include "backend/cpu_tracer.h"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>
#include <thread>
#include <new>
#include <span>
#include <cstdint>

#include <sys/mman.h>
#include <charconv>
#include <fstream>
#include <string>
#include <string_view>

#include "backend/walk_interleaver.h"
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
template struct HugePageAllocator<device::BvhNode>;
template struct HugePageAllocator<device::Primitive>;

namespace {

// A thread's queued film adds: one group fills while the other's prefetched
// lines arrive (device::PendingCounts).
struct CountQueues {
  explicit CountQueues(std::span<uint64_t> counters) : groups{device::PendingCounts(counters), device::PendingCounts(counters)} {}
  device::PendingCounts groups[2];
  size_t filling = 0;
};

// The beams of one trace(), in blocks that threads claim in order. When
// cancelled, a thread claims no further block, and the beams of those it
// has claimed are all traced, so the traced beams stay one contiguous
// prefix.
struct BlockClaims {
  uint64_t beamCount;
  uint64_t blockBeams;
  uint64_t blockCount;
  const std::atomic<bool>* cancel;
  std::atomic<uint64_t> nextBlock{0};
  std::atomic<uint64_t> stoppedAtBlock;
};

// A thread's beams: those of the block it holds, then the next it claims.
class BeamSource {
 public:
  explicit BeamSource(BlockClaims& claims) : claims_(claims) {}
  bool take(uint64_t& beam) {
    if (next_ == end_ && !claimBlock()) return false;
    beam = next_++;
    return true;
  }

 private:
  __attribute__((noinline)) bool claimBlock() {
    const uint64_t block = claims_.nextBlock.fetch_add(1, std::memory_order_relaxed);
    if (block >= claims_.blockCount) return false;
    if (claims_.cancel && claims_.cancel->load(std::memory_order_relaxed)) {
      uint64_t expected = claims_.stoppedAtBlock.load();
      while (block < expected && !claims_.stoppedAtBlock.compare_exchange_weak(expected, block)) {}
      return false;
    }
    next_ = block * claims_.blockBeams;
    end_ = std::min(claims_.beamCount, next_ + claims_.blockBeams);
    return true;
  }
  BlockClaims& claims_;
  uint64_t next_ = 0;
  uint64_t end_ = 0;
};

// The beams `source` gives (offsets from firstBeam, so that a range ending
// at 2^64 does not wrap) through `kernel`, whose pending adds go to
// `queues`: the whole kernel or the profile's stage; returns the beams
// counted. Its copies below differ only in their target: each is
// flattened (every call inlined), so the whole kernel is compiled into
// each, and no shared inline function is emitted out of line with another
// target's instructions (which the linker might then pick for the
// baseline). With interleaved walks, each of a thread's fibers runs it
// over the thread's one source and queues.
inline uint64_t traceBeamsBody(device::BeamKernel& kernel, CountQueues& queues, BeamSource& source,
                               uint64_t firstBeam, uint32_t profileStage) {
  const bool wholeKernel = profileStage == device::kProfileStageFull;
  uint64_t counted = 0;
  for (uint64_t i; source.take(i);) {
    kernel.pending = &queues.groups[queues.filling];
    const bool hit =
        wholeKernel ? kernel.traceAndCountBeam(firstBeam + i) : kernel.profileBeam(firstBeam + i, profileStage);
    counted += hit ? 1 : 0;
    if (queues.groups[queues.filling].full()) {
      queues.filling ^= 1;
      queues.groups[queues.filling].flush();
    }
  }
  return counted;
}

// Beams [first, first + count) recorded, not counted (traceRecorded).
inline void recordBeamsBody(device::BeamKernel& kernel, uint64_t first, uint32_t count, device::BeamRecord* records) {
  for (uint32_t i = 0; i < count; ++i) records[i] = kernel.record(first + i);
}

// flatten inlines the whole kernel into each of the entry points below,
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

SPECTRACE_FLATTEN uint64_t traceBeamsBaseline(device::BeamKernel& kernel, CountQueues& queues, BeamSource& source,
                                              uint64_t firstBeam, uint32_t profileStage) {
  return traceBeamsBody(kernel, queues, source, firstBeam, profileStage);
}
SPECTRACE_FLATTEN void runInterleavedBaseline(WalkInterleaver& interleaver) { runInterleaved(interleaver); }
SPECTRACE_FLATTEN void recordBeamsBaseline(device::BeamKernel& kernel, uint64_t first, uint32_t count,
                                           device::BeamRecord* records) {
  recordBeamsBody(kernel, first, count, records);
}

#if defined(__x86_64__)
#define SPECTRACE_HAS_X86_64_V3 1
SPECTRACE_FLATTEN __attribute__((target("arch=x86-64-v3"))) uint64_t traceBeamsV3(device::BeamKernel& kernel,
                                                                                  CountQueues& queues,
                                                                                  BeamSource& source,
                                                                                  uint64_t firstBeam,
                                                                                  uint32_t profileStage) {
  return traceBeamsBody(kernel, queues, source, firstBeam, profileStage);
}
SPECTRACE_FLATTEN __attribute__((target("arch=x86-64-v3"))) void runInterleavedV3(WalkInterleaver& interleaver) {
  runInterleaved(interleaver);
}
SPECTRACE_FLATTEN __attribute__((target("arch=x86-64-v3"))) void recordBeamsV3(device::BeamKernel& kernel,
                                                                               uint64_t first, uint32_t count,
                                                                               device::BeamRecord* records) {
  recordBeamsBody(kernel, first, count, records);
}
#else
#define SPECTRACE_HAS_X86_64_V3 0
#endif

uint64_t traceBeams(CpuCode code, device::BeamKernel& kernel, CountQueues& queues, BeamSource& source,
                    uint64_t firstBeam, uint32_t profileStage) {
#if SPECTRACE_HAS_X86_64_V3
  if (code == CpuCode::X86_64_V3) return traceBeamsV3(kernel, queues, source, firstBeam, profileStage);
#endif
  return traceBeamsBaseline(kernel, queues, source, firstBeam, profileStage);
}

void runInterleaved(CpuCode code, WalkInterleaver& interleaver) {
#if SPECTRACE_HAS_X86_64_V3
  if (code == CpuCode::X86_64_V3) return runInterleavedV3(interleaver);
#endif
  runInterleavedBaseline(interleaver);
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

namespace {

// The last-level cache of the first processor, as the kernel describes it
// in sysfs (the C library's figure can be the whole package's: 320 MiB on
// a virtual machine whose cores share 32 MiB); 0 where it cannot tell.
size_t lastLevelCacheBytes() {
  size_t bytes = 0;
  unsigned level = 0;
  for (int index = 0; index < 8; ++index) {
    const std::string dir = fmt::format("/sys/devices/system/cpu/cpu0/cache/index{}/", index);
    std::ifstream levelFile(dir + "level"), sizeFile(dir + "size");
    unsigned l = 0;
    std::string size;
    if (!(levelFile >> l) || !(sizeFile >> size) || l < level) continue;
    size_t value = 0;
    const auto [end, error] = std::from_chars(size.data(), size.data() + size.size(), value);
    if (error != std::errc() || value == 0) continue;
    const std::string_view unit(end, size.data() + size.size());
    const size_t scale = unit == "K" ? size_t(1) << 10 : unit == "M" ? size_t(1) << 20 : unit.empty() ? 1 : 0;
    if (scale == 0) continue;
    level = l;
    bytes = value * scale;
  }
  return bytes;
}

// run(0), ..., run(count - 1) at once, run(0) on this thread.
template <typename Run>
void runOnThreads(size_t count, Run run) {
  std::vector<std::jthread> pool;
  for (size_t i = 1; i < count; ++i) pool.emplace_back(run, i);
  run(size_t(0));
}

// `from` into `to`, in one part per thread: the first touch of a huge page
// is the kernel's to zero (and, where memory is fragmented, to compact
// for), tens of milliseconds for a large mesh's tree on one core.
template <typename T>
void copyOnThreads(const std::vector<T>& from, std::vector<T, HugePageAllocator<T>>& to, unsigned threads) {
  to.resize(from.size());  // untouched (HugePageAllocator::construct)
  const size_t parts = std::clamp<size_t>(from.size() * sizeof(T) / (size_t(4) << 20), 1, threads);
  auto copyPart = [&](size_t part) {
    const size_t begin = from.size() * part / parts, end = from.size() * (part + 1) / parts;
    std::copy(from.begin() + ptrdiff_t(begin), from.begin() + ptrdiff_t(end), to.begin() + ptrdiff_t(begin));
  };
  runOnThreads(parts, copyPart);
}

bool interleaves(WalkInterleaving interleaving, const DeviceScene& scene, uint32_t profileStage) {
  if (interleaving != WalkInterleaving::Automatic) return interleaving == WalkInterleaving::Always;
  const size_t treeBytes =
      scene.bvhNodes.size() * sizeof(device::BvhNode) + scene.primitives.size() * sizeof(device::Primitive);
  static const size_t cacheBytes = lastLevelCacheBytes();
  return profileStage == device::kProfileStageFull && cacheBytes > 0 && treeBytes > cacheBytes;
}

}  // namespace

CpuTracer::CpuTracer(const CompiledScene& plan, unsigned threads, uint32_t profileStage, CpuCode code,
                     WalkInterleaving interleaving)
    : plan_(plan),
      threads_(threads ? threads : std::max(1u, std::thread::hardware_concurrency())),
      profileStage_(std::min<uint32_t>(profileStage, device::kProfileStageObjectsNoConnection)),
      code_(code),
      interleaveWalks_(interleaves(interleaving, plan.device, profileStage_)),
      counters_(plan.film.storedCounterCount()) {  // zero, untouched (HugePageAllocator)
  if (!cpuRuns(code))
    throw std::invalid_argument(fmt::format("CpuTracer: this processor cannot run the {} code", cpuCodeName(code)));
  // One chunk holds every stored pixel.
  plan_.device.constants.pixelsPerChunk = uint32_t(std::max<uint64_t>(1, plan.film.storedPixelCount()));
  // The profile's counting stage counts bins only (shaders/profile.h).
  if (profileStage_ <= device::kProfileStageCounting) plan_.device.constants.exactColour = 0;
  if (profileStage_ == device::kProfileStageObjectsNoConnection) plan_.device.constants.connect = 0;
  // The tree on huge pages too: a walk reads a few nodes and primitives
  // from all over it, and with 4 KiB pages most reads of a large tree also
  // miss the TLB. (Moved, so the tracer holds one copy.)
  copyOnThreads(plan_.device.bvhNodes, bvhNodes_, threads_);
  copyOnThreads(plan_.device.primitives, primitives_, threads_);
  std::vector<device::BvhNode>().swap(plan_.device.bvhNodes);
  std::vector<device::Primitive>().swap(plan_.device.primitives);
}

std::string CpuTracer::deviceName() const {
  return fmt::format("CPU reference, {} threads, {}", threads_, cpuCodeName(code_));
}

uint64_t CpuTracer::trace(uint64_t firstBeam, uint64_t beamCount, const std::atomic<bool>* cancel) {
  const device::BeamKernel kernel = beamKernel(counters_);
  std::atomic<uint64_t> counted{0};
  // Blocks are small enough that every thread gets several (a short batch
  // keeps both cores busy) and a cancel is seen soon; the counts do not
  // depend on them.
  const uint64_t blockBeams = std::clamp<uint64_t>(beamCount / (uint64_t(threads_) * 4), 1 << 8, 1 << 16);
  const uint64_t blockCount = (beamCount + blockBeams - 1) / blockBeams;
  BlockClaims claims{beamCount, blockBeams, blockCount, cancel, {0}, {blockCount}};
  auto worker = [&] {
    CountQueues queues(counters_);
    BeamSource source(claims);
    uint64_t countedHere = 0;
    if (interleaveWalks_) {
      WalkInterleaver interleaver(kernel, kBeamsInFlight, [&](device::BeamKernel& fiberKernel) {
        return traceBeams(code_, fiberKernel, queues, source, firstBeam, profileStage_);
      });
      runInterleaved(code_, interleaver);
      countedHere = interleaver.counted();
    } else {
      device::BeamKernel local = kernel;
      countedHere = traceBeams(code_, local, queues, source, firstBeam, profileStage_);
    }
    queues.groups[0].flush();
    queues.groups[1].flush();
    counted.fetch_add(countedHere, std::memory_order_relaxed);
  };
  runOnThreads(threads_, [&](size_t) { worker(); });
  countedBeams_ += counted.load();
  return std::min(beamCount, claims.stoppedAtBlock.load() * blockBeams);
}

device::BeamKernel CpuTracer::beamKernel(std::span<uint64_t> counters) const {
  const DeviceScene& scene = plan_.device;
  device::BeamKernel kernel(scene.constants, scene.lights, scene.intervals, scene.aliasColumns, scene.cmfTable, counters);
  kernel.setObjects(primitives_, bvhNodes_, scene.materials, scene.data.words());
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
