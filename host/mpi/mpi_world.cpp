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

std::string World::rootText(const std::string& text) const {
  uint64_t size = text.size();
  MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  std::string out = isRoot() ? text : std::string(size_t(size), '\0');
  constexpr size_t kPiece = size_t(1) << 30;  // MPI counts are ints
  for (size_t start = 0; start < out.size(); start += kPiece)
    MPI_Bcast(out.data() + start, int(std::min(kPiece, out.size() - start)), MPI_CHAR, 0, MPI_COMM_WORLD);
  return out;
}

std::vector<uint64_t> World::gather(uint64_t value) const {
  std::vector<uint64_t> values(size_t(size_), 0);
  MPI_Allgather(&value, 1, MPI_UINT64_T, values.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD);
  return values;
}

namespace {

// Set on any rank whose part of the reduction found a sum that would wrap
// (MPI's user functions cannot throw); the ranks agree on it afterwards.
bool reduceOverflowed = false;

// MPI's reduction of film counters of `words` words, through the merge's
// own add (addChannel): MPI_SUM would drop a two-word counter's carry and
// let any counter wrap.
template <uint32_t words>
void addCounters(void* in, void* inout, int* length, MPI_Datatype*) {
  if (addChannel(static_cast<uint64_t*>(inout), static_cast<const uint64_t*>(in), size_t(*length) * words, words))
    reduceOverflowed = true;
}

// Sums `values` (counters of `words` words) over the ranks into rank 0's, in
// pieces that fit MPI's int counts.
void sumArrayOnRoot(std::vector<uint64_t>& values, uint32_t words, bool root) {
  MPI_Datatype counter = MPI_UINT64_T;
  MPI_Op sum;
  MPI_Op_create(words == 2 ? &addCounters<2> : &addCounters<1>, 1, &sum);
  if (words == 2) {
    MPI_Type_contiguous(2, MPI_UINT64_T, &counter);
    MPI_Type_commit(&counter);
  }
  constexpr size_t kPiece = size_t(1) << 26;  // counters: 512 MiB of one-word ones
  const size_t counters = values.size() / words;
  for (size_t start = 0; start < counters; start += kPiece) {
    const int count = int(std::min(kPiece, counters - start));
    uint64_t* data = values.data() + start * words;
    if (root) MPI_Reduce(MPI_IN_PLACE, data, count, counter, sum, 0, MPI_COMM_WORLD);
    else MPI_Reduce(data, nullptr, count, counter, sum, 0, MPI_COMM_WORLD);
  }
  MPI_Op_free(&sum);
  if (words == 2) MPI_Type_free(&counter);
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
  reduceOverflowed = false;
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c)
    sumArrayOnRoot(film.channel(c), film.counterWords(), isRoot());
  if (largestCode(reduceOverflowed ? 1 : 0) != 0)
    throw CounterOverflow("the ranks' films sum past what a counter holds (2^64 - 1, or 2^128 - 1 in two words)");
  std::vector<uint64_t> counted{film.countedBeams};
  sumArrayOnRoot(counted, 1, isRoot());
  film.countedBeams = counted[0];
}

}  // namespace spectrace::mpi
