#pragma once
// The CPU reference (--device cpu): multithreaded, drawing exactly the beams
// the GPU draws through the same shared kernel (host/kernel), counting into
// the same device counter layout.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "backend/cpu_code.h"
#include "backend/tracer.h"
#include "kernel/beam_kernel.h"
#include "compile/compile_scene.h"

namespace spectrace {

// Allocates large arrays on 2 MiB boundaries from mmap and asks the kernel
// for huge pages (madvise(MADV_HUGEPAGE), a hint; "madvise" is Debian's
// default transparent-huge-page mode): counts land all over a film of up to
// gigabytes, and with 4 KiB pages nearly every one is also a TLB miss.
// mmap's pages read as zero, so value-initialised elements (vector(n)) are
// not written here: the first touch, and the kernel's zeroing, happen in
// the tracing threads, in parallel, instead of in one memset before them.
template <typename T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>&) {}
  T* allocate(size_t n);
  void deallocate(T* p, size_t n);
  // Value-initialisation of a trivial T (a number, a record of numbers):
  // the memory is already zero.
  template <typename U>
  void construct(U* p) noexcept {
    static_assert(std::is_trivial_v<U>);
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <typename U>
  bool operator==(const HugePageAllocator<U>&) const { return true; }
  static constexpr size_t kAlignment = size_t(2) << 20;
  static size_t mappedBytes(size_t n) { return (n * sizeof(T) + kAlignment - 1) / kAlignment * kAlignment; }
};

// Whether each thread keeps several beams in flight and steps their BVH
// walks in turn (backend/walk_interleaver.h). The films are the same bits
// either way; Automatic interleaves where the scene's tree and primitives
// outgrow the last-level cache, so that walks wait on main memory (a
// million-triangle mesh's 60 MB traced 1.3x as fast; a furnished room's
// 15 MB, inside a 32 MiB cache, 0.9x), and never for the bench's profile
// stages, which time the kernel's parts one beam at a time.
enum class WalkInterleaving { Automatic, Always, Never };

class CpuTracer final : public Tracer {
 public:
  // threads = 0: all hardware threads.
  // profileStage: the bench's cost profile (shaders/profile.h); the default traces the whole kernel.
  // code: the loop's machine code; one this processor cannot run throws std::invalid_argument.
  explicit CpuTracer(const CompiledScene& plan, unsigned threads = 0,
                     uint32_t profileStage = device::kProfileStageFull, CpuCode code = fastestCpuCode(),
                     WalkInterleaving interleaving = WalkInterleaving::Automatic);
  // Beams a thread keeps in flight when it interleaves. Through the ray
  // ceiling's million-triangle mesh, since a node's children are taken
  // without branches, 8, 12, 16 and 24 walks in turn on each of 2 threads
  // traced 5.7, 6.1-6.6, 5.4-6.9 and 4.7-5.7 Mray/s (two rounds each);
  // past 16, the walks' states (each with its stack) crowd the first-level
  // cache. A sphere_mesh render traces 1.01-1.03x as fast with 16 as with 8.
  static constexpr size_t kBeamsInFlight = 16;
  bool interleavesWalks() const { return interleaveWalks_; }

  DeviceKind kind() const override { return DeviceKind::Cpu; }
  std::string deviceName() const override;
  uint64_t trace(uint64_t firstBeam, uint64_t beamCount, const std::atomic<bool>* cancel = nullptr) override;
  void clear() override;
  SpectralHistogram download() const override;
  void upload(const SpectralHistogram& histogram) override;
  RenderImage develop(const ResolveParameters& parameters, FilmSummary* summary = nullptr) override;
  std::vector<device::BeamRecord> traceRecorded(uint64_t firstBeam, uint32_t count) override;

 private:
  // The shared kernel over this scene's tables, adding to `counters`.
  device::BeamKernel beamKernel(std::span<uint64_t> counters) const;
  CompiledScene plan_;
  unsigned threads_;
  uint32_t profileStage_;
  CpuCode code_;
  bool interleaveWalks_;
  std::vector<uint64_t, HugePageAllocator<uint64_t>> counters_;  // the stored pixels' counters, one chunk
  std::vector<device::BvhNode, HugePageAllocator<device::BvhNode>> bvhNodes_;
  std::vector<device::Primitive, HugePageAllocator<device::Primitive>> primitives_;
  uint64_t countedBeams_ = 0;
};

}  // namespace spectrace
