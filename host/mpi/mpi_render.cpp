#include "mpi/mpi_render.h"

#include "vulkan/context.h"

namespace spectrace::mpi {

std::unique_ptr<Device> openRankDevice(DeviceChoice choice, int localRank, const PipelineCacheOptions& cache,
                                       const std::function<void(const std::string&)>& log) {
  if (choice != DeviceChoice::Cpu) {
    std::vector<vk_util::DeviceInfo> gpus;
    try {
      for (const auto& info : vk_util::enumerateDevices())
        if (info.isHardware() && info.missingFeatures().empty()) gpus.push_back(info);
    } catch (const vk_util::VulkanError&) {
      // No Vulkan loader: Device::open below says so (gpu) or falls back (auto).
    }
    if (!gpus.empty()) {
      const auto& gpu = gpus[size_t(localRank) % gpus.size()];
      return Device::open(DeviceSpec{DeviceKind::Vulkan, gpu.name, int(gpu.index)}, cache, log);
    }
  }
  return Device::open(choice, log, cache);
}

BeamRange rankBeams(const RenderJob& job, int rank, int size) {
  return shardRange(job.options.firstBeam, job.beamCount(), uint64_t(rank), uint64_t(size));
}

RenderResult traceBeams(const Device& device, const RenderJob& job, const BeamRange& beams) {
  RenderOptions options = job.options;
  options.firstBeam = beams.first;
  options.beams = beams.count;
  options.seed = job.seedValue();
  // Rank 0 develops the summed film; a rank's own image is never written.
  options.spectral = false;
  options.checkpointSeconds = 0;
  options.onCheckpoint = nullptr;
  options.onCheckpointFilm = nullptr;
  options.downloadFilm = true;  // the films are summed on rank 0
  return render(job.scene, options, device);
}

FilmState combinedState(const RenderJob& job, const std::vector<BeamRange>& finished, SpectralHistogram film) {
  FilmState state{jobFingerprint(job), {}, std::move(film)};
  for (const BeamRange& range : finished) {
    if (range.count == 0) continue;
    if (!state.ranges.empty() && state.ranges.back().first + state.ranges.back().count == range.first)
      state.ranges.back().count += range.count;
    else
      state.ranges.push_back(range);
  }
  return state;
}

}  // namespace spectrace::mpi
