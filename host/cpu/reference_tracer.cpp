#include "cpu/reference_tracer.h"

#include <algorithm>
#include <thread>
#include <vector>

#include "cpu/beam_kernel.h"

namespace spectrace {

uint64_t traceOnCpu(const TracePlan& plan, uint64_t firstBeam, uint64_t beamCount,
                    SpectralHistogram& histogram, const CpuTraceOptions& options) {
  if (!plan.hasShapeOf(histogram)) histogram = plan.emptyHistogram();
  const device::BeamKernel kernel(plan.constants, plan.lights, plan.intervals, plan.cmfTable);
  const bool exactColour = plan.exactColour();
  uint64_t* colourSums = histogram.colourSums.data();
  uint64_t* squaredWeightSums = histogram.squaredWeightSums.data();
  std::atomic<uint64_t> counted{0};
  unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());

  // Threads take blocks of beams in order. When cancelled, each finishes
  // its block, so the traced beams stay one contiguous prefix.
  constexpr uint64_t kBlock = 1 << 16;
  const uint64_t blockCount = (beamCount + kBlock - 1) / kBlock;
  std::atomic<uint64_t> nextBlock{0};
  std::atomic<uint64_t> stoppedAtBlock{blockCount};
  uint64_t* counts = histogram.counts.data();
  const uint32_t bins = plan.bins;
  const uint32_t firstBin = plan.firstStoredBin();

  auto worker = [&] {
    device::BeamKernel local = kernel;
    uint64_t countedHere = 0;
    for (;;) {
      const uint64_t block = nextBlock.fetch_add(1, std::memory_order_relaxed);
      if (block >= blockCount) break;
      if (options.cancel && options.cancel->load(std::memory_order_relaxed)) {
        uint64_t expected = stoppedAtBlock.load();
        while (block < expected && !stoppedAtBlock.compare_exchange_weak(expected, block)) {}
        break;
      }
      const uint64_t begin = block * kBlock;
      const uint64_t end = std::min(beamCount, begin + kBlock);
      for (uint64_t i = begin; i < end; ++i) {
        uint32_t pixel, bin;
        float lambda, spare, ratio;
        // What trace_beams.comp adds, counter by counter.
        if (local.traceBeam(firstBeam + i, pixel, bin, lambda, spare, ratio)) {
          ++countedHere;
          const uint32_t fullBin = bin + firstBin;  // the kernel returns the stored bin
          std::atomic_ref<uint64_t>(counts[size_t(pixel) * bins + fullBin])
              .fetch_add(local.weightUnitsOf(ratio, spare), std::memory_order_relaxed);
          if (exactColour) {
            const glm::vec3 c = local.cmfAtWavelength(lambda) * ratio;
            uint64_t* sums = colourSums + size_t(pixel) * 3;
            for (int k = 0; k < 3; ++k)
              std::atomic_ref<uint64_t>(sums[k]).fetch_add(local.colourFixedPoint(c[k], spare), std::memory_order_relaxed);
          }
          if (squaredWeightSums)
            std::atomic_ref<uint64_t>(squaredWeightSums[pixel])
                .fetch_add(local.squaredWeightUnitsOf(ratio, spare), std::memory_order_relaxed);
        }
      }
    }
    counted.fetch_add(countedHere, std::memory_order_relaxed);
  };
  std::vector<std::jthread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  pool.clear();  // joins
  histogram.countedBeams += counted.load();
  return std::min(beamCount, stoppedAtBlock.load() * kBlock);
}

}  // namespace spectrace
