#pragma once
// The bench's ray ceiling (Ceiling section): closest-hit rays through the
// optics bench's mesh, traced by the shared kernel's BVH walk
// (shaders/objects.h: intersectObjects, on the CPU through BeamKernel) and
// by Intel Embree, a measured ceiling for CPU ray tracing.
//
// Embree stays in the bench: the renderer keeps the shared kernel's
// intersection tests, so the CPU reference and the GPU run the same code
// and give bit-identical films.
#include <atomic>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "backend/cpu_tracer.h"
#include "device_shared.h"

namespace spectrace {

// The primitives and BVH the kernel reads (compile/compile_objects.h), in
// the camera frame.
struct RayCeilingGeometry {
  std::vector<device::Primitive> primitives;
  std::vector<device::BvhNode> nodes;
  // With nodes of `nodeBytes`: the CPU reference's full nodes, or the
  // Vulkan trace's packed ones (compile/packed_bvh.h).
  double bytesPerPrimitive(size_t nodeBytes = sizeof(device::BvhNode)) const {
    return double(nodes.size() * nodeBytes + primitives.size() * sizeof(device::Primitive)) /
           double(primitives.size());
  }
};
// The optics bench's mesh scene (opticsMeshScene) of about `triangles`
// triangles, compiled.
RayCeilingGeometry meshCeilingGeometry(uint64_t triangles);

struct CeilingRay {
  glm::vec3 origin, direction;  // direction of unit length
};
struct CeilingHit {
  bool hit = false;
  uint32_t primitive = 0;  // index into RayCeilingGeometry::primitives
  float t = 0.0f;
};

// `count` incoherent rays: each from its own point, uniform on a sphere of
// three times the mesh's radius about its centre, towards a point uniform
// in a ball of 1.25 times its radius (most meet the mesh, some miss), from
// Philox words of (seed, ray index). Not the render's beams (those leave one
// spot light, more coherent): a harder, scene-independent load.
std::vector<CeilingRay> incoherentRays(const RayCeilingGeometry& geometry, uint64_t count, uint64_t seed);

// Closest hits in (0, far) of every ray, on `threads` threads, through the
// shared kernel's intersectObjects.
void traceSpectrace(const RayCeilingGeometry& geometry, std::span<const CeilingRay> rays, std::span<CeilingHit> hits,
                    unsigned threads);
// The same hits, each thread stepping kCeilingWalksInFlight walks in turn
// (BeamKernel::stepWalk), as the CPU reference's threads do with their
// beams' walks on a large tree (backend/walk_interleaver.h), as many.
constexpr size_t kCeilingWalksInFlight = CpuTracer::kBeamsInFlight;
void traceSpectraceInterleaved(const RayCeilingGeometry& geometry, std::span<const CeilingRay> rays,
                               std::span<CeilingHit> hits, unsigned threads);

// Whether the build has Embree (CMake option SPECTRACE_EMBREE, on when
// Embree 3 is found).
bool embreeAvailable();
// The same rays through Embree (a scene of the same float triangles, built
// at RTC_BUILD_QUALITY_HIGH, rtcIntersect1 on `threads` threads). Throws
// without Embree.
class EmbreeScene {
 public:
  explicit EmbreeScene(const RayCeilingGeometry& geometry, unsigned threads);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
  void trace(std::span<const CeilingRay> rays, std::span<CeilingHit> hits, unsigned threads) const;
  double buildSeconds() const { return buildSeconds_; }
  uint64_t bytes() const { return bytes_; }  // Embree's allocations, its vertex and index copies included

 private:
  struct State;
  State* state_ = nullptr;
  double buildSeconds_ = 0.0;
  uint64_t bytes_ = 0;
};

// How two sets of hits differ: hit against miss, another primitive (edge
// ties), and a distance differing by more than `relative` of itself.
struct HitComparison {
  uint64_t hitMiss = 0, otherPrimitive = 0, distance = 0, bothHit = 0;
  double largestRelativeDistance = 0.0;  // among the rays that meet the same primitive
};
HitComparison compareHits(std::span<const CeilingHit> a, std::span<const CeilingHit> b, double relative = 1e-5);

struct RayCeilingRow {
  bool embree = false;  // false: built without Embree, only spectrace's figures
  uint64_t triangles = 0, rays = 0, hits = 0;
  unsigned threads = 0;
  const char* cpuCode = "";  // the machine code of spectrace's walks (cpuCodeName)
  double bytesPerTriangle = 0.0, embreeBytesPerTriangle = 0.0;
  double vulkanBytesPerTriangle = 0.0;  // the same tree as the Vulkan trace holds it
  // Least of the rounds, in seconds, on one thread and on `threads`.
  double spectrace1 = 0.0, spectraceN = 0.0, embree1 = 0.0, embreeN = 0.0;
  // spectrace with kCeilingWalksInFlight walks in turn on each thread (as
  // the CPU reference's threads walk a tree larger than the L2 cache).
  double interleaved1 = 0.0, interleavedN = 0.0;
  uint64_t interleavedDifferences = 0;  // rays whose hit differs from one walk at a time (none expected)
  double embreeBuildSeconds = 0.0;
  HitComparison disagreements;
  // spectrace : Embree in rays per second (the first over the second).
  double ratio1() const { return embree1 / spectrace1; }
  double ratioN() const { return embreeN / spectraceN; }
  double interleavedRatio1() const { return embree1 / interleaved1; }
  double interleavedRatioN() const { return embreeN / interleavedN; }
};
RayCeilingRow runRayCeiling(uint64_t triangles, uint64_t rays, unsigned threads, const std::atomic<bool>& cancel);

}  // namespace spectrace
