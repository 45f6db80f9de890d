#pragma once
// Several beams in flight on one CPU thread, so that their BVH walks wait
// on memory together. A walk through a tree larger than the caches waits
// for nearly every node it reads, and one ray has nothing else to do
// meanwhile; the thread's loop instead steps each beam's walk in turn (one
// node or leaf, which prefetches the next), so one walk's lines arrive
// while the others' steps run. The beams' own code (emission, materials,
// counting) stays the shared kernel's, run in a fiber per beam: it hands
// each walk to the loop and is resumed when the walk is over.
//
// Exact: each beam draws the same numbers and its walk visits the same
// nodes in the same order as it would alone (BeamKernel::stepWalk), so its
// hits are the same bits; the film's integer adds are the same set in
// another order. Fibers switch only at a walk's start and end.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <boost/context/fiber.hpp>

#include "kernel/beam_kernel.h"

namespace spectrace {

class WalkInterleaver;

// One beam in flight: its kernel (the walk hook points at `walk`), its
// fiber, and whether it waits for its walk or has run out of beams.
struct BeamFiber {
  BeamFiber(const device::BeamKernel& k, WalkInterleaver& interleaver) : kernel(k), owner(&interleaver) {}
  device::BeamKernel kernel;
  WalkInterleaver* owner;
  device::BeamKernel::WalkState walk;
  bool walking = false;
  bool finished = false;
  uint64_t counted = 0;
  boost::context::fiber fiber;      // the beam code, while the loop runs
  boost::context::fiber scheduler;  // the loop, while the beam code runs
  // The fiber's stack, for AddressSanitizer's view of the switches.
  const void* stackBottom = nullptr;
  size_t stackSize = 0;
  void* savedFakeStack = nullptr;
};

// A thread's beams in flight. `run(kernel)` is the beam loop each fiber
// runs with its own copy of `kernel`, until the thread's beams run out; it
// returns the beams it counted.
class WalkInterleaver {
 public:
  WalkInterleaver(const device::BeamKernel& kernel, size_t beamsInFlight,
                  std::function<uint64_t(device::BeamKernel&)> run);
  WalkInterleaver(const WalkInterleaver&) = delete;
  WalkInterleaver& operator=(const WalkInterleaver&) = delete;
  ~WalkInterleaver() = default;

  std::span<BeamFiber> fibers() { return fibers_; }
  // Switches into the beam's code until it hands over its next walk or
  // finishes.
  void resume(BeamFiber& beam);
  // The beams' counts, once every fiber has finished.
  uint64_t counted() const;

 private:
  static void awaitWalk(void* beam);
  friend struct FiberEntry;
  std::vector<BeamFiber> fibers_;  // reserved once: fibers hold pointers to their entries
  std::function<uint64_t(device::BeamKernel&)> run_;
  // The thread's own stack, for AddressSanitizer.
  const void* threadStackBottom_ = nullptr;
  size_t threadStackSize_ = 0;
  void* threadFakeStack_ = nullptr;
};

// Steps every fiber's walk in turn until all have finished. Inline, so
// that the CPU tracer compiles it with the kernel for each of its machine
// codes.
inline void runInterleaved(WalkInterleaver& interleaver) {
  std::span<BeamFiber> fibers = interleaver.fibers();
  size_t live = fibers.size();
  for (BeamFiber& beam : fibers) {
    interleaver.resume(beam);
    if (beam.finished) --live;
  }
  while (live > 0) {
    for (BeamFiber& beam : fibers) {
      if (!beam.walking || beam.kernel.stepWalk(beam.walk)) continue;
      beam.walking = false;
      interleaver.resume(beam);
      if (beam.finished) --live;
    }
  }
}

}  // namespace spectrace
