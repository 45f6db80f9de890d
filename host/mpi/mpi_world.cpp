#include "mpi/mpi_world.h"

#include <mpi.h>

#include <algorithm>
#include <array>
#include <climits>
#include <stdexcept>

namespace spectrace::mpi {

// MPI's default error handler (MPI_ERRORS_ARE_FATAL) stays: a failed MPI
// call ends every rank of the job rather than leaving one waiting.
World::World() {
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
  MPI_Comm_rank(node, &localRank_);
  MPI_Comm_free(&node);
}

World::~World() { MPI_Finalize(); }

int World::largestCode(int code) const {
  int largest = 0;
  MPI_Allreduce(&code, &largest, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return largest;
}

int World::rootValue(int value) const {
  MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return value;
}

std::vector<uint64_t> World::gather(uint64_t value) const {
  std::vector<uint64_t> values(size_t(size_), 0);
  MPI_Allgather(&value, 1, MPI_UINT64_T, values.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD);
  return values;
}

namespace {

// Sums `values` over the ranks into rank 0's, in pieces that fit MPI's int counts.
void sumArrayOnRoot(std::vector<uint64_t>& values, bool root) {
  constexpr size_t kPiece = size_t(1) << 26;  // 512 MiB of uint64
  for (size_t start = 0; start < values.size(); start += kPiece) {
    const int count = int(std::min(kPiece, values.size() - start));
    uint64_t* data = values.data() + start;
    if (root) MPI_Reduce(MPI_IN_PLACE, data, count, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
    else MPI_Reduce(data, nullptr, count, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
  }
}

}  // namespace

void World::sumOnRoot(SpectralHistogram& film) const {
  // Every rank compiled the same scene, so the shapes agree; a mismatch
  // (a scene file changed under a running job) must fail on every rank,
  // not leave rank 0 summing arrays of different lengths.
  std::vector<uint64_t> shape{film.pixelsX, film.pixelsY, film.bins, film.unitsPerBeam};
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) shape.push_back(film.channel(c).size());
  std::vector<uint64_t> rootShape = shape;
  MPI_Bcast(rootShape.data(), int(rootShape.size()), MPI_UINT64_T, 0, MPI_COMM_WORLD);
  if (largestCode(shape == rootShape ? 0 : 1) != 0)
    throw std::runtime_error("the ranks' films differ in shape (was the scene file changed during the render?)");
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) sumArrayOnRoot(film.channel(c), isRoot());
  std::vector<uint64_t> counted{film.countedBeams};
  sumArrayOnRoot(counted, isRoot());
  film.countedBeams = counted[0];
}

}  // namespace spectrace::mpi
