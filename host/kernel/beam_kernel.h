#pragma once
// The CPU instance of the shared kernel (shaders/trace.h and what it
// includes): the same text the trace shader runs, compiled as C++ member
// functions over host arrays, with Philox from Random123. The includer
// contract is shaders/kernel_interface.h; a KernelIncluder concept checks
// it here. Built with -ffp-contract=off (see host/kernel/CMakeLists.txt).
#include <algorithm>
#include <atomic>
#include <span>

#include <glm/glm.hpp>

#include "device_shared.h"
#include "kernel_interface.h"
#include "kernel/wide_walk.h"
#include "rng/philox.h"

namespace spectrace::device {

// Counts a CPU thread has computed but not yet added to the film: the
// film's counters are scattered over a large histogram, so each add is
// likely a cache miss, and an atomic add waits for its miss with nothing
// else in flight. Pending adds are prefetched when they are queued and added
// a group of beams later, when their lines have arrived. Integer adds
// commute, so the film is the same bits whatever the order.
class PendingCounts {
 public:
  // Enough for a group of beams (each adds at most a bin, X, Y, Z and a
  // squared weight).
  static constexpr size_t kCapacity = 256;

  explicit PendingCounts(std::span<uint64_t> filmCounters) : counters_(filmCounters) {}
  bool full() const { return size_ + 5 > kCapacity; }
  // A beam with camera connections can make many counts: a full group is
  // added at once rather than overrun (its lines may not have arrived yet,
  // which costs time, never a count).
  void push(uint32_t index, uint64_t amount) { pushWide(index, WideCount{amount, 0}, false); }
  // A two-word counter (words index, index + 1) when `wide`.
  void pushWide(uint32_t index, WideCount amount, bool wide = true) {
    if (size_ == kCapacity) [[unlikely]] flush();
    __builtin_prefetch(&counters_[index], 1);
    index_[size_] = index;
    amount_[size_] = amount;
    wide_[size_] = wide;
    ++size_;
  }
  void flush() {
    for (size_t i = 0; i < size_; ++i) {
      if (wide_[i]) addWide(counters_, index_[i], amount_[i]);
      else std::atomic_ref<uint64_t>(counters_[index_[i]]).fetch_add(amount_[i].low, std::memory_order_relaxed);
    }
    size_ = 0;
  }
  // The kernel's addWideCount on the CPU (trace_beams.comp's twin): the
  // low word's carry, seen by exactly the add that wrapped it, goes to the
  // high word.
  static void addWide(std::span<uint64_t> counters, uint32_t index, WideCount amount) {
    uint64_t carry = 0;
    if (amount.low != 0) {
      const uint64_t before =
          std::atomic_ref<uint64_t>(counters[index]).fetch_add(amount.low, std::memory_order_relaxed);
      carry = before + amount.low < before ? 1 : 0;
    }
    if (amount.high + carry != 0)
      std::atomic_ref<uint64_t>(counters[index + 1]).fetch_add(amount.high + carry, std::memory_order_relaxed);
  }

 private:
  std::span<uint64_t> counters_;
  size_t size_ = 0;
  uint32_t index_[kCapacity];
  WideCount amount_[kCapacity];
  bool wide_[kCapacity];
};

// GLSL names (vec3, uvec4, sqrt, min, abs, ...) for the shared code.
using namespace glm;

class BeamKernel {
 public:
  // `counters`: the film's counters of every stored pixel in one chunk
  // (constants.pixelsPerChunk must cover them), which countBeam adds to
  // with relaxed atomics; empty when the kernel only traces.
  BeamKernel(const TraceConstants& traceConstants, std::span<const LightRecord> lightRecords,
             std::span<const SpectralInterval> spectralIntervals, std::span<const AliasColumn> aliasTables,
             std::span<const glm::vec3> cmfNodes = {}, std::span<uint64_t> filmCounters = {})
      : constants(traceConstants), lights(lightRecords), intervals(spectralIntervals), aliasColumns(aliasTables),
        cmf(cmfNodes), counters(filmCounters) {}

  // The scene's objects (none unless set; constants.objectPrimitives must
  // match).
  void setObjects(std::span<const Primitive> objectPrimitives, std::span<const BvhNode> nodes,
                  std::span<const Material> objectMaterials, std::span<const uint32_t> sceneDataWords) {
    primitives = objectPrimitives;
    bvhNodes = nodes;
    materials = objectMaterials;
    sceneData = sceneDataWords;
  }

  // Beam `index` in record mode: whether it would be counted, and its
  // (last) count's pixel, stored bin and weight ratio (its float bits),
  // ratio), with the number of counts it makes. Nothing is added to the
  // film. (The shared functions cannot be const-qualified, as GLSL has no
  // such thing; the kernel is small, so each thread uses its own copy.)
  BeamRecord record(uint64_t index) {
    BeamTally tally = emptyTally();
    recording = true;
    const bool hit = traceBeam(index, tally);
    recording = false;
    if (!hit) return BeamRecord{kBeamMissed, kBeamMissed, 0u, 0u};
    return BeamRecord{pixelOfCell(tally.cell, constants.pixelsX), tally.bin, floatBitsToUint(tally.ratio),
                      tally.contributions};
  }
  // The same, as pixel and bin.
  bool trace(uint64_t index, uint& pixelOut, uint& binOut) {
    const BeamRecord r = record(index);
    pixelOut = r.pixel;
    binOut = r.bin;
    return r.pixel != kBeamMissed;
  }

  // The includer contract (kernel_interface.h).
  static uvec4 philox4x32(uint64_t seed, uint64_t index, uint block) {
    const auto w = spectrace::philoxWords(seed, index, block);
    return uvec4(w[0], w[1], w[2], w[3]);
  }
  AliasColumn readAliasColumn(uint i) const { return aliasColumns[i]; }
  LightRecord readLight(uint i) const { return lights[i]; }
  SpectralInterval readInterval(uint i) const { return intervals[i]; }
  vec3 readCmf(uint i) const { return cmf[i]; }
  Primitive readPrimitive(uint i) const { return primitives[i]; }
  BvhNode readBvhNode(uint i) const { return bvhNodes[i]; }
  // A CPU thread has only its own ray to trace, so it waits for each miss
  // of a tree too large for the caches: the children a ray meets are
  // requested together, as soon as they are known (prefetchEntry: a node's
  // or a leaf's first two lines, with no branch on which), and the rest of
  // a leaf's primitives when it is next (on the ray ceiling, whole leaves
  // traced 1.1x the rays of their first four primitives alone).
  void prefetchBvhChild(uint child, uint count) const { prefetchChildLines(child, count, 0); }
  void prefetchEntry(WalkEntry e) const {
    const char* first = childBytes(entryChild(e), entryCount(e));
    __builtin_prefetch(first);
    __builtin_prefetch(first + 64);
  }
  // A child's bytes: a node (count 0) or a leaf's primitives.
  const char* childBytes(uint child, uint count) const {
    return count == 0 ? reinterpret_cast<const char*>(bvhNodes.data() + child)
                      : reinterpret_cast<const char*>(primitives.data() + child);
  }
  // The child's lines from byte `from` on (128 where prefetchEntry has
  // asked for the first two).
  void prefetchChildLines(uint child, uint count, size_t from) const {
    const char* first = childBytes(child, count);
    const size_t bytes = count == 0 ? sizeof(BvhNode) : size_t(count) * sizeof(Primitive);
    for (size_t offset = from; offset < bytes; offset += 64) __builtin_prefetch(first + offset);
  }
  Material readMaterial(uint i) const { return materials[i]; }
  uint32_t readSceneWord(uint i) const { return sceneData[i]; }
  // One chunk on the CPU: `chunk` is always 0. Queued when the caller gave
  // a PendingCounts (it must flush it), else added at once.
  void addCount(uint /*chunk*/, uint index, uint64_t amount) const {
    if (pending) pending->push(index, amount);
    else std::atomic_ref<uint64_t>(counters[index]).fetch_add(amount, std::memory_order_relaxed);
  }
  void addWideCount(uint /*chunk*/, uint index, WideCount amount) const {
    if (pending) pending->pushWide(index, amount);
    else PendingCounts::addWide(counters, index, amount);
  }
  PendingCounts* pending = nullptr;
  // Walk the BVH by the shader's own steps rather than wide_walk.h's
  // (tests compare the two).
  bool portableWalk = false;

 private:
  TraceConstants constants;
  std::span<const LightRecord> lights;
  std::span<const SpectralInterval> intervals;
  std::span<const AliasColumn> aliasColumns;
  std::span<const glm::vec3> cmf;
  std::span<uint64_t> counters;
  std::span<const Primitive> primitives;
  std::span<const BvhNode> bvhNodes;
  std::span<const Material> materials;
  std::span<const uint32_t> sceneData;
  bool recording = false;  // record mode: counts are noted, not added

 public:
  // The shared functions are public so tests can probe them one by one.
#define SPECTRACE_SINGLE_CHUNK true  // `counters` holds every stored pixel
#define SPECTRACE_WITH_CAMERA_PATHS  // the whole kernel (the shader has a module without them)
#define SPECTRACE_RECORDING recording
#define SPECTRACE_CPU_WALK_STEP  // wide_walk.h
#include "trace.h"
#include "profile.h"  // the bench's cost profile

  // The CPU's walk (shaders/objects.h: intersectObjects hands it here) as a
  // state and a step, so that a thread can advance several beams' walks in
  // turn (host/backend/walk_interleaver.h): a walk waits on memory at nearly
  // every step, and the others' steps run while its lines arrive. Each step
  // is the shader's loop body with host/kernel/wide_walk.h's vector forms of
  // the node and leaf tests, so the walk visits the same children in the
  // same order and keeps the same hit, however its steps are interleaved.
  struct WalkState {
    WalkRay ray;
    vec3 origin;
    vec3 direction;
    ObjectHit hit;
    bool found;
    bool anyHit;
    uint depth;
    uint child;
    uint count;
    WalkEntry stack[kWalkStackSize];
  };

  void startWalk(WalkState& walk, vec3 origin, vec3 direction, float tMax, bool anyHit) {
    walk.ray = walkRayOf(origin, inverseDirection(direction));
    walk.origin = origin;
    walk.direction = direction;
    walk.hit.t = tMax;
    walk.hit.primitive = 0u;
    walk.found = false;
    walk.anyHit = anyHit;
    walk.depth = 0u;
    walk.child = 0u;  // the root, or with bvhRootLeaf the root's only leaf
    walk.count = constants.bvhRootLeaf;
  }

  // One node or leaf of the walk; false when the walk is over.
  bool stepWalk(WalkState& walk) {
    return walkStep(walk.ray, walk.origin, walk.direction, walk.anyHit, walk.hit, walk.found, walk.depth, walk.child,
                    walk.count, walk.stack);
  }
  // The step on the walk's parts, so that a walk run here keeps them in
  // local variables (in registers; a WalkState's live in memory).
  bool walkStep(const WalkRay& ray, vec3 origin, vec3 direction, bool anyHit, ObjectHit& hit, bool& found,
                uint& depth, uint& child, uint& count, WalkEntry* stack) {
    if (count > 0u) {
      // Four triangles on the lanes of a register; the scalar loop for a
      // leaf with other primitives.
      if (!nearestTriangleInLeaf(origin, direction, primitives.data() + child, child, count,
                                 [&](float t, uint primitive) { keepNearerHit(t, primitive, hit, found); }))
        for (uint i = 0u; i < count; ++i)
          keepNearerHit(intersectPrimitive(origin, direction, readPrimitive(child + i)), child + i, hit, found);
      if (found && anyHit) return false;
    } else if (nearestChildMet(ray, bvhNodes[child], hit.t, stack, depth, child, count,
                               [this](WalkEntry e) { prefetchEntry(e); })) {
      // The nearest child met, which the shader pushes and pops at once.
      prefetchChildLines(child, count, 128);
      return true;
    }
    // The nearest entry that the closest hit so far leaves in reach.
    const float reach = hit.t * 1.0000004f;
    while (depth > 0u) {
      const WalkEntry entry = stack[--depth];
      if (entryWithin(entry, reach)) {
        child = entryChild(entry);
        count = entryCount(entry);
        prefetchChildLines(child, count, 128);
        return true;
      }
    }
    return false;
  }

  // Where a thread interleaves walks, it sets these: a walk is started in
  // `handedWalk` and `awaitWalk(awaitContext)` returns once the thread has
  // stepped it to its end. Otherwise the walk runs here, step after step.
  WalkState* handedWalk = nullptr;
  void (*awaitWalk)(void*) = nullptr;
  void* awaitContext = nullptr;

  bool cpuIntersectObjects(vec3 origin, vec3 direction, float tMax, bool anyHit, ObjectHit& hit) {
    if (handedWalk != nullptr) {
      startWalk(*handedWalk, origin, direction, tMax, anyHit);
      awaitWalk(awaitContext);
      hit = handedWalk->hit;
      return handedWalk->found;
    }
    const WalkRay ray = walkRayOf(origin, inverseDirection(direction));
    hit.t = tMax;
    hit.primitive = 0u;
    bool found = false;
    uint depth = 0u;
    uint child = 0u;  // the root, or with bvhRootLeaf the root's only leaf
    uint count = constants.bvhRootLeaf;
    WalkEntry stack[kWalkStackSize];
    while (walkStep(ray, origin, direction, anyHit, hit, found, depth, child, count, stack)) {
    }
    return found;
  }
};

static_assert(KernelIncluder<BeamKernel>);

}  // namespace spectrace::device
