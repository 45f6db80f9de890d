// render --mpi: this process is one rank of an mpirun. Each rank traces the
// beams `--shard rank/size` would, the films are summed exactly on rank 0
// (host/mpi), and rank 0 alone prints progress and writes the image and the
// state. Every step ends with the ranks agreeing on its outcome, so a
// failure on one rank ends the command on all of them with one exit code.
#include <chrono>
#include <cstdio>
#include <fmt/format.h>
#include <numeric>

#include "cli/cli_numbers.h"
#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "cli/progress_line.h"
#include "mpi/mpi_render.h"
#include "mpi/mpi_world.h"

namespace spectrace::cli {
namespace {

// Runs `step` on this rank, then returns the largest exit code of any rank
// (0: every rank succeeded). A failure is printed once: by rank 0 if it
// failed, else by each rank that did, naming itself.
template <class Step>
int collectively(const mpi::World& world, Step&& step) {
  Failure failure{0, ""};
  try {
    step();
  } catch (...) {
    failure = failureOf(std::current_exception());
  }
  const int code = world.largestCode(failure.code);
  if (code == 0) return 0;
  const int rootCode = world.rootValue(failure.code);
  if (failure.code != 0 && (world.isRoot() || rootCode == 0))
    std::fprintf(stderr, "spectrace: error: %s%s\n",
                 world.isRoot() ? "" : fmt::format("rank {} of {}: ", world.rank(), world.size()).c_str(),
                 failure.message.c_str());
  return code;
}

}  // namespace

int runMpiRender(const RenderCommand& command, const std::atomic<bool>& cancel) {
  const mpi::World world;
  const bool root = world.isRoot();
  const bool talk = root && !command.quiet;
  ProgressLine progress = ProgressLine::forStderr();
  const auto say = [&progress](const std::string& line) { progress.notice(line); };
  std::vector<RenderJob> jobs;
  std::unique_ptr<Session> session;
  int code = collectively(world, [&] {
    if (command.shard || command.resume)
      throw UsageError("--mpi splits the beams over the ranks itself: it takes neither --shard nor --resume");
    RenderCommand rankCommand = command;
    rankCommand.quiet = !talk;
    // Only rank 0 writes, so only rank 0 checks (and probes) the outputs.
    jobs = renderJobsOf(rankCommand, cancel, root);
    for (const RenderJob& job : jobs)
      if (job.beamCount() < uint64_t(world.size()))
        throw UsageError(fmt::format("--mpi: {} beams cannot be split over {} ranks", job.beamCount(), world.size()));
  });
  if (code != 0) return code;

  // Every rank must trace the same render, or rank 0 would sum films of
  // different scenes, spectra or seeds into a wrong image without a word:
  // each rank compares its films' fingerprints and beams with rank 0's
  // before any beam is traced, and all stop when one differs.
  std::vector<CompiledScene> plans;
  std::string identity;
  if ((code = collectively(world, [&] {
         plans = mpi::compileJobs(jobs);
         identity = mpi::renderIdentity(jobs, plans);
       })) != 0)
    return code;
  const std::string rootIdentity = world.rootText(identity);
  code = collectively(world, [&] {
    if (std::string why = mpi::renderDifference(identity, rootIdentity); !why.empty()) throw UsageError(why);
  });
  if (code != 0) return code;

  // The device is opened once the ranks agree on what to trace.
  code = collectively(world, [&] {
    PipelineCacheOptions cache = command.pipelineCache;
    cache.enabled = cache.enabled && root;  // the pipeline cache file is rank 0's too
    std::function<void(const std::string&)> log;
    if (talk) log = say;
    session = std::make_unique<Session>(
        Device::openForLocalRank(parseDeviceChoice(command.device), world.localRank(), cache, log));
  });
  if (code != 0) return code;

  for (size_t j = 0; j < jobs.size(); ++j) {
    RenderJob& job = jobs[j];
    const auto start = std::chrono::steady_clock::now();
    const BeamRange mine = mpi::rankBeams(job, world.rank(), world.size());
    if (talk) {
      say(fmt::format("{}: {} beams over {} MPI ranks", job.scene.sourcePath.string(), job.beamCount(), world.size()));
      job.loop.log = say;
      job.loop.onStart = [&progress](uint64_t done, uint64_t total) { progress.start(total, done, "rank 0: "); };
      job.loop.onProgress = [&progress](uint64_t done, uint64_t) { progress.update(done); };
    }
    RenderResult part;
    if ((code = collectively(world, [&] { part = mpi::traceBeams(session->device(), job, std::move(plans[j]), mine); })) != 0) return code;
    if (talk) progress.finish();

    // What each rank finished (all of its range unless interrupted), and
    // the exact sum of their films on rank 0.
    const std::vector<uint64_t> done = world.gather(part.beamsTraced);
    std::vector<BeamRange> finished;
    for (int rank = 0; rank < world.size(); ++rank)
      finished.push_back({mpi::rankBeams(job, rank, world.size()).first, done[size_t(rank)]});
    const uint64_t total = std::accumulate(done.begin(), done.end(), uint64_t(0));
    if ((code = collectively(world, [&] { world.sumOnRoot(part.histogram); })) != 0) return code;

    code = collectively(world, [&] {
      if (!root || total == 0) return;
      const FilmState state = mpi::combinedState(job, part.plan, finished, std::move(part.histogram));
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const RenderResult result = session->develop(state, job.output, job.outputs.spectral, job.png, seconds);
      if (!job.state.empty()) writeFilmState(job.state, state);
      if (talk)
        say(fmt::format("{} beams in {:.2f} s ({:.1f} Mbeam/s) on {} MPI ranks; rank 0 on {}; wrote {}", total,
                        seconds, double(total) / seconds * 1e-6, world.size(), result.deviceName,
                        job.output.string()));
    });
    if (code != 0) return code;
    if (total < job.beamCount()) {
      if (root)
        std::fprintf(stderr, "spectrace: interrupted after %llu of %llu beams; the image holds the finished beams\n",
                     (unsigned long long)total, (unsigned long long)job.beamCount());
      return 130;
    }
  }
  return 0;
}

}  // namespace spectrace::cli
