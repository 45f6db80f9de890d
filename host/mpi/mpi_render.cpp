#include "mpi/mpi_render.h"

namespace spectrace::mpi {

BeamRange rankBeams(const RenderJob& job, int rank, int size) {
  return shardRange(job.firstBeam, job.beamCount(), uint64_t(rank), uint64_t(size));
}

RenderResult traceBeams(const Device& device, const RenderJob& job, const BeamRange& beams) {
  RenderOptions options = job.renderOptions();
  options.firstBeam = beams.first;
  options.beams = beams.count;
  // Rank 0 develops the summed film; a rank's own image is never written.
  options.outputs.spectral = false;
  options.loop.checkpointSeconds = 0;
  options.loop.onCheckpoint = nullptr;
  options.loop.onCheckpointFilm = nullptr;
  options.outputs.downloadFilm = true;  // the films are summed on rank 0
  return render(job.scene, options, device);
}

FilmState combinedState(const RenderJob& job, const CompiledScene& plan, const std::vector<BeamRange>& finished,
                        SpectralHistogram film) {
  FilmState state{jobFingerprint(job, plan), {}, std::move(film)};
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
