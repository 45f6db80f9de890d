#pragma once
// A render split over MPI ranks, rank by rank: what the ranks compare
// before tracing, which beams a rank traces (each rank's device is
// Device::openForLocalRank's choice), and the state rank 0 makes of every
// rank's film. The MPI
// calls themselves are mpi_world.h's; the CLI (cli/mpi_render.cpp) runs the
// steps and agrees on failures.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "backend/device.h"
#include "film/film_state.h"
#include "render/renderer.h"
#include "session/session.h"

namespace spectrace::mpi {

// The beams rank `rank` of `size` traces: exactly those of --shard rank/size.
BeamRange rankBeams(const RenderJob& job, int rank, int size);

// The jobs compiled (compileScene with each job's seed and options): once,
// for renderIdentity and for traceBeams.
std::vector<CompiledScene> compileJobs(const std::vector<RenderJob>& jobs);

// What a rank is about to render, as text to compare with rank 0's before
// any beam is traced: per job, its scene file, the fingerprint of its film
// (film/film_state.h: the scene's hash, spectrum, film, seed, options) and
// its beams. `plans`: the jobs compiled (compileScene), one per job.
std::string renderIdentity(const std::vector<RenderJob>& jobs, const std::vector<CompiledScene>& plans);
// Why this rank's renderIdentity `mine` is not rank 0's `root`: the job and
// the first field that differs, this rank's value against rank 0's; "" when
// they are the same render (their films may be summed).
std::string renderDifference(const std::string& mine, const std::string& root);

// Traces `beams` of the job, compiled as `plan`, on `device` and writes no
// file (no checkpoints, no state): the film comes back in the result, for
// rank 0 to sum.
RenderResult traceBeams(const Device& device, const RenderJob& job, CompiledScene plan, const BeamRange& beams);

// The state of the job's beams that every rank finished: `finished` holds
// each rank's traced range (empty ones are left out, neighbours joined),
// `film` the sum of their films; with the scene bundled and the irradiance
// scale of those beams.
FilmState combinedState(const RenderJob& job, const CompiledScene& plan, const std::vector<BeamRange>& finished,
                        SpectralHistogram film);

}  // namespace spectrace::mpi
