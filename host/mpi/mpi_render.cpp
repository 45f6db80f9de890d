#include "mpi/mpi_render.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace spectrace::mpi {

using nlohmann::json;

std::vector<CompiledScene> compileJobs(const std::vector<RenderJob>& jobs) {
  std::vector<CompiledScene> plans;
  for (const RenderJob& job : jobs) plans.push_back(compileScene(job.scene, job.seedValue(), job.plan));
  return plans;
}

std::string renderIdentity(const std::vector<RenderJob>& jobs, const std::vector<CompiledScene>& plans) {
  json all = json::array();
  for (size_t i = 0; i < jobs.size(); ++i)
    all.push_back({{"scene", jobs[i].scene.sourcePath.string()},
                   {"fingerprint", fingerprintText(jobFingerprint(jobs[i], plans.at(i)))},
                   {"first_beam", jobs[i].firstBeam},
                   {"beams", jobs[i].beamCount()}});
  return all.dump();
}

std::string renderDifference(const std::string& mine, const std::string& root) {
  const json a = json::parse(mine), b = json::parse(root);
  if (a.size() != b.size())
    return fmt::format("it renders {} scene{}, rank 0 renders {}", a.size(), a.size() == 1 ? "" : "s", b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    const json &x = a[i], &y = b[i];
    // The scene's path may differ between ranks; its SHA-256 in the fingerprint decides.
    std::string field = fingerprintDifference(fingerprintOfText(x.at("fingerprint").get<std::string>()),
                                              fingerprintOfText(y.at("fingerprint").get<std::string>()));
    for (const char* key : {"first_beam", "beams"})
      if (field.empty() && x.at(key) != y.at(key)) field = fmt::format("{}: {} against {}", key, x.at(key).dump(), y.at(key).dump());
    if (!field.empty())
      return fmt::format("its render of {} is not rank 0's render of {}: they differ in {} (this rank's against rank "
                         "0's); every rank must be given the same scene, spectrum and options, or their films would "
                         "be summed into a wrong image",
                         x.at("scene").get<std::string>(), y.at("scene").get<std::string>(), field);
  }
  return "";
}

BeamRange rankBeams(const RenderJob& job, int rank, int size) {
  return shardRange(job.firstBeam, job.beamCount(), uint64_t(rank), uint64_t(size));
}

RenderResult traceBeams(const Device& device, const RenderJob& job, CompiledScene plan, const BeamRange& beams) {
  RenderOptions options = job.renderOptions();
  options.firstBeam = beams.first;
  options.beams = beams.count;
  // Rank 0 develops the summed film; a rank's own image is never written.
  options.outputs.spectral = false;
  options.loop.checkpointSeconds = 0;
  options.loop.onCheckpoint = nullptr;
  options.loop.onCheckpointFilm = nullptr;
  options.outputs.downloadFilm = true;  // the films are summed on rank 0
  return render(job.scene, std::move(plan), options, device);
}

FilmState combinedState(const RenderJob& job, const CompiledScene& plan, const std::vector<BeamRange>& finished,
                        SpectralHistogram film) {
  FilmState state{jobFingerprint(job, plan), {}, std::move(film), sceneBundleOf(job.scene)};
  for (const BeamRange& range : finished) {
    if (range.count == 0) continue;
    if (!state.ranges.empty() && state.ranges.back().first + state.ranges.back().count == range.first)
      state.ranges.back().count += range.count;
    else
      state.ranges.push_back(range);
  }
  state.irradiancePerCount = stateIrradiancePerCount(plan.irradianceScale(), state.beams());
  return state;
}

}  // namespace spectrace::mpi
