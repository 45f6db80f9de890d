#include "backend/cpu_tracer.h"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>
#include <thread>
#include <new>
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

CpuTracer::CpuTracer(const CompiledScene& plan, unsigned threads, uint32_t profileStage)
    : plan_(plan),
      threads_(threads ? threads : std::max(1u, std::thread::hardware_concurrency())),
      profileStage_(std::min<uint32_t>(profileStage, device::kProfileStageFull)),
      counters_(plan.film.storedCounterCount()) {  // zero, untouched (HugePageAllocator)
  // One chunk holds every stored pixel.
  plan_.device.constants.pixelsPerChunk = uint32_t(std::max<uint64_t>(1, plan.film.storedPixelCount()));
  // The profile's counting stage counts bins only (shaders/profile.h).
  if (profileStage_ <= device::kProfileStageCounting) plan_.device.constants.exactColour = 0;
}

std::string CpuTracer::deviceName() const { return fmt::format("CPU reference, {} threads", threads_); }

uint64_t CpuTracer::trace(uint64_t firstBeam, uint64_t beamCount, const std::atomic<bool>* cancel) {
  const device::BeamKernel kernel(plan_.device.constants, plan_.device.lights, plan_.device.intervals, plan_.device.aliasColumns, plan_.device.cmfTable, counters_);
  std::atomic<uint64_t> counted{0};
  // Threads take blocks of beams in order. When cancelled, each finishes
  // its block, so the traced beams stay one contiguous prefix.
  constexpr uint64_t kBlock = 1 << 16;
  const uint64_t blockCount = (beamCount + kBlock - 1) / kBlock;
  std::atomic<uint64_t> nextBlock{0};
  std::atomic<uint64_t> stoppedAtBlock{blockCount};
  auto worker = [&] {
    device::BeamKernel local = kernel;
    // Two groups of queued adds: one fills while the other's prefetched
    // lines arrive (device::PendingCounts).
    device::PendingCounts groups[2] = {device::PendingCounts(counters_), device::PendingCounts(counters_)};
    size_t filling = 0;
    local.pending = &groups[filling];
    auto nextGroupIfFull = [&] {
      if (!groups[filling].full()) return;
      filling ^= 1;
      groups[filling].flush();
      local.pending = &groups[filling];
    };
    uint64_t countedHere = 0;
    for (;;) {
      const uint64_t block = nextBlock.fetch_add(1, std::memory_order_relaxed);
      if (block >= blockCount) break;
      if (cancel && cancel->load(std::memory_order_relaxed)) {
        uint64_t expected = stoppedAtBlock.load();
        while (block < expected && !stoppedAtBlock.compare_exchange_weak(expected, block)) {}
        break;
      }
      const uint64_t end = std::min(beamCount, (block + 1) * kBlock);
      const bool wholeKernel = profileStage_ == device::kProfileStageFull;
      for (uint64_t i = block * kBlock; i < end; ++i) {
        const bool hit = wholeKernel ? local.traceAndCountBeam(firstBeam + i) : local.profileBeam(firstBeam + i, profileStage_);
        countedHere += hit ? 1 : 0;
        nextGroupIfFull();
      }
    }
    groups[0].flush();
    groups[1].flush();
    counted.fetch_add(countedHere, std::memory_order_relaxed);
  };
  std::vector<std::jthread> pool;
  for (unsigned t = 1; t < threads_; ++t) pool.emplace_back(worker);
  worker();
  pool.clear();  // joins
  countedBeams_ += counted.load();
  return std::min(beamCount, stoppedAtBlock.load() * kBlock);
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
  device::BeamKernel kernel(plan_.device.constants, plan_.device.lights, plan_.device.intervals, plan_.device.aliasColumns, plan_.device.cmfTable);
  std::vector<device::BeamRecord> records(count);
  for (uint32_t i = 0; i < count; ++i) {
    uint32_t pixel, bin;
    uint64_t units = 0;
    records[i] = kernel.trace(firstBeam + i, pixel, bin, &units)
                     ? device::BeamRecord{pixel, bin, uint32_t(units), 0u}
                     : device::BeamRecord{device::kBeamMissed, device::kBeamMissed, 0u, 0u};
  }
  return records;
}

}  // namespace spectrace
