#pragma once
// The MPI calls of a render split over ranks (mpirun -n K spectrace render
// --mpi). Only mpi_world.cpp includes <mpi.h>: the rest of spectrace, this
// header's users included, builds without MPI's headers.
#include <cstdint>
#include <string>
#include <vector>

#include "film/spectral_histogram.h"

namespace spectrace::mpi {

// MPI itself: initialised by the constructor, finalised by the destructor.
// Only the thread that made it calls MPI (MPI_THREAD_FUNNELED).
class World {
 public:
  World();
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool isRoot() const { return rank_ == 0; }
  // This rank's place among the ranks on its node (picks its GPU).
  int localRank() const { return localRank_; }

  // The largest of every rank's `code`, on every rank: the ranks agree
  // whether one of them failed (and with which exit code) instead of
  // waiting for it forever.
  int largestCode(int code) const;
  // Rank 0's `value`, on every rank.
  int rootValue(int value) const;
  // Rank 0's `text`, on every rank (the others' `text` is not read).
  std::string rootText(const std::string& text) const;
  // Every rank's `value`, in rank order, on every rank.
  std::vector<uint64_t> gather(uint64_t value) const;
  // Sums every rank's film into rank 0's exactly (MPI_Reduce of the uint64
  // counters with MPI_SUM); the other ranks' films are left as they were.
  // Throws std::runtime_error on every rank when the films' shapes differ.
  void sumOnRoot(SpectralHistogram& film) const;

 private:
  int rank_ = 0, size_ = 1, localRank_ = 0;
};

}  // namespace spectrace::mpi
