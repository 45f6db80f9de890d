#pragma once
// A render split over MPI ranks, rank by rank: which beams a rank traces
// (each rank's device is Device::openForLocalRank's choice), and the state
// rank 0 makes of every rank's film. The MPI
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

// Traces `beams` of the job on `device` and writes no file (no checkpoints,
// no state): the film comes back in the result, for rank 0 to sum.
RenderResult traceBeams(const Device& device, const RenderJob& job, const BeamRange& beams);

// The state of the job's beams that every rank finished: `finished` holds
// each rank's traced range (empty ones are left out, neighbours joined),
// `film` the sum of their films.
FilmState combinedState(const RenderJob& job, const CompiledScene& plan, const std::vector<BeamRange>& finished,
                        SpectralHistogram film);

}  // namespace spectrace::mpi
