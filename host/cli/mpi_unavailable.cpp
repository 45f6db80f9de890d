// render --mpi in a build without MPI (CMake did not find it).
#include "cli/cli_numbers.h"
#include "cli/commands.h"

namespace spectrace::cli {

int runMpiRender(const RenderCommand&, const std::atomic<bool>&) {
  throw UsageError(
      "--mpi: this spectrace was built without MPI; install libopenmpi-dev (scripts/setup.sh does) and rebuild");
}

}  // namespace spectrace::cli
