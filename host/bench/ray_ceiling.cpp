#include "bench/ray_ceiling.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <thread>

#include <glm/geometric.hpp>

#include "bench/optics_bench.h"
#include "compile/compile_scene.h"
#include "compile/wide_bvh.h"
#include "backend/cpu_code.h"
#include "kernel/beam_kernel.h"
#include "rng/philox.h"

#ifdef SPECTRACE_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

namespace spectrace {
namespace {

// Far enough for any scene, and finite: the box test scales it by 1 + 4e-7.
constexpr float kFar = 1.0e30f;

// Rays [0, n) split into interleaved blocks over `threads` threads.
void forEachBlock(size_t n, unsigned threads, const std::function<void(size_t, size_t)>& work) {
  constexpr size_t kBlock = 4096;
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t begin; (begin = next.fetch_add(kBlock, std::memory_order_relaxed)) < n;)
      work(begin, std::min(n, begin + kBlock));
  };
  std::vector<std::jthread> pool;
  for (unsigned t = 1; t < std::max(1u, threads); ++t) pool.emplace_back(worker);
  worker();
}

double secondsOf(const std::function<void()>& run) {
  const auto start = std::chrono::steady_clock::now();
  run();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

glm::dvec3 unitVector(double u1, double u2) {
  const double z = 1.0 - 2.0 * u1, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * std::numbers::pi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

}  // namespace

RayCeilingGeometry meshCeilingGeometry(uint64_t triangles) {
  CompiledScene compiled = compileScene(opticsMeshScene(triangles), 1);
  return {std::move(compiled.device.primitives), std::move(compiled.device.bvhNodes)};
}

std::vector<CeilingRay> incoherentRays(const RayCeilingGeometry& geometry, uint64_t count, uint64_t seed) {
  glm::vec3 rootLo, rootHi;
  nodeBounds(geometry.nodes.at(0), rootLo, rootHi);
  const glm::dvec3 lo(rootLo), hi(rootHi);
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  std::vector<CeilingRay> rays(count);
  for (uint64_t i = 0; i < count; ++i) {
    const auto a = philoxWords(seed, i, 0), b = philoxWords(seed, i, 1);
    auto u = [](uint32_t w) { return (double(w) + 0.5) * 0x1p-32; };
    const glm::dvec3 origin = centre + 3.0 * radius * unitVector(u(a[0]), u(a[1]));
    const glm::dvec3 target = centre + 1.25 * radius * std::cbrt(u(a[2])) * unitVector(u(a[3]), u(b[0]));
    rays[i] = {glm::vec3(origin), glm::vec3(glm::normalize(target - origin))};
  }
  return rays;
}

namespace {

// Rays [begin, end) walked one at a time.
inline void walkRays(device::BeamKernel& kernel, std::span<const CeilingRay> rays, std::span<CeilingHit> hits,
                     size_t begin, size_t end) {
  for (size_t i = begin; i < end; ++i) {
    device::BeamKernel::ObjectHit hit;
    const bool found = kernel.intersectObjects(rays[i].origin, rays[i].direction, kFar, false, hit);
    hits[i] = {found, hit.primitive, hit.t};
  }
}

// Rays [begin, end) walked kCeilingWalksInFlight at a time, one node or
// leaf of each in turn, as the CPU tracer's threads step their beams'
// walks (runInterleaved).
inline void walkRaysInTurn(device::BeamKernel& kernel, std::span<const CeilingRay> rays, std::span<CeilingHit> hits,
                           size_t begin, size_t end) {
  device::BeamKernel::WalkState walks[kCeilingWalksInFlight];
  constexpr size_t kIdle = SIZE_MAX;
  size_t rayOf[kCeilingWalksInFlight];
  std::fill(rayOf, rayOf + kCeilingWalksInFlight, kIdle);
  size_t next = begin, live = 0;
  const auto start = [&](size_t k) {
    kernel.startWalk(walks[k], rays[next].origin, rays[next].direction, kFar, false);
    rayOf[k] = next++;
    ++live;
  };
  for (size_t k = 0; k < kCeilingWalksInFlight && next < end; ++k) start(k);
  while (live > 0) {
    for (size_t k = 0; k < kCeilingWalksInFlight; ++k) {
      if (rayOf[k] == kIdle || kernel.stepWalk(walks[k])) continue;
      hits[rayOf[k]] = {walks[k].found, walks[k].hit.primitive, walks[k].hit.t};
      rayOf[k] = kIdle;
      --live;
      if (next < end) start(k);
    }
  }
}

inline void walkBlock(device::BeamKernel& kernel, std::span<const CeilingRay> rays, std::span<CeilingHit> hits,
                      size_t begin, size_t end, bool inTurn) {
  if (inTurn) walkRaysInTurn(kernel, rays, hits, begin, end);
  else walkRays(kernel, rays, hits, begin, end);
}

// The walks compiled for the baseline and for x86-64-v3, each with the
// walk inlined whole (the CPU tracer's entry points do the same,
// cpu_tracer.cpp), so that the ceiling times the machine code the renderer
// runs on this processor (fastestCpuCode), not the baseline's.
__attribute__((flatten)) void walkBlockBaseline(device::BeamKernel& kernel, std::span<const CeilingRay> rays,
                                                std::span<CeilingHit> hits, size_t begin, size_t end, bool inTurn) {
  walkBlock(kernel, rays, hits, begin, end, inTurn);
}
#if defined(__x86_64__)
__attribute__((flatten, target("arch=x86-64-v3"))) void walkBlockV3(device::BeamKernel& kernel,
                                                                    std::span<const CeilingRay> rays,
                                                                    std::span<CeilingHit> hits, size_t begin,
                                                                    size_t end, bool inTurn) {
  walkBlock(kernel, rays, hits, begin, end, inTurn);
}
#endif

void traceSpectraceBlocks(const RayCeilingGeometry& geometry, std::span<const CeilingRay> rays,
                          std::span<CeilingHit> hits, unsigned threads, bool inTurn) {
  device::TraceConstants constants{};
  constants.objectPrimitives = uint32_t(geometry.primitives.size());
  const CpuCode code = fastestCpuCode();
  forEachBlock(rays.size(), threads, [&](size_t begin, size_t end) {
    // Each thread its own kernel, as the CPU reference does (its shared
    // functions cannot be const).
    device::BeamKernel kernel(constants, {}, {}, {});
    kernel.setObjects(geometry.primitives, geometry.nodes, {}, {});
#if defined(__x86_64__)
    if (code == CpuCode::X86_64_V3) return walkBlockV3(kernel, rays, hits, begin, end, inTurn);
#endif
    walkBlockBaseline(kernel, rays, hits, begin, end, inTurn);
  });
}

}  // namespace

void traceSpectrace(const RayCeilingGeometry& geometry, std::span<const CeilingRay> rays, std::span<CeilingHit> hits,
                    unsigned threads) {
  traceSpectraceBlocks(geometry, rays, hits, threads, false);
}

void traceSpectraceInterleaved(const RayCeilingGeometry& geometry, std::span<const CeilingRay> rays,
                               std::span<CeilingHit> hits, unsigned threads) {
  traceSpectraceBlocks(geometry, rays, hits, threads, true);
}

HitComparison compareHits(std::span<const CeilingHit> a, std::span<const CeilingHit> b, double relative) {
  HitComparison c;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].hit != b[i].hit) {
      ++c.hitMiss;
      continue;
    }
    if (!a[i].hit) continue;
    ++c.bothHit;
    const double d = std::abs(double(a[i].t) - double(b[i].t)) / double(a[i].t);
    if (d > relative) ++c.distance;
    if (a[i].primitive != b[i].primitive) ++c.otherPrimitive;
    else c.largestRelativeDistance = std::max(c.largestRelativeDistance, d);
  }
  return c;
}

#ifdef SPECTRACE_HAVE_EMBREE

struct EmbreeScene::State {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::atomic<int64_t> bytes{0};
};

namespace {
bool countBytes(void* user, ssize_t bytes, bool /*post*/) {
  static_cast<std::atomic<int64_t>*>(user)->fetch_add(bytes, std::memory_order_relaxed);
  return true;
}
}  // namespace

bool embreeAvailable() { return true; }

EmbreeScene::EmbreeScene(const RayCeilingGeometry& geometry, unsigned threads) : state_(new State) {
  const std::string config = "threads=" + std::to_string(std::max(1u, threads));
  state_->device = rtcNewDevice(config.c_str());
  if (!state_->device) {
    delete state_;
    throw std::runtime_error("Embree: rtcNewDevice failed");
  }
  rtcSetDeviceMemoryMonitorFunction(state_->device, countBytes, &state_->bytes);
  buildSeconds_ = secondsOf([&] {
    state_->scene = rtcNewScene(state_->device);
    rtcSetSceneBuildQuality(state_->scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry mesh = rtcNewGeometry(state_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(mesh, RTC_BUILD_QUALITY_HIGH);
    const size_t n = geometry.primitives.size();
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
    auto* indices = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), n));
    // The kernel's triangles keep a vertex and two edges (shapes/triangle.h);
    // Embree's, three vertices: a, a + b, a + c, rounded to float.
    for (size_t i = 0; i < n; ++i) {
      const device::Primitive& p = geometry.primitives[i];
      if (p.type != device::kPrimitiveTriangle) throw std::invalid_argument("Embree ceiling: triangles only");
      const glm::vec3 v[3] = {p.a, p.a + p.b, p.a + p.c};
      for (int k = 0; k < 3; ++k) {
        vertices[9 * i + 3 * k + 0] = v[k].x;
        vertices[9 * i + 3 * k + 1] = v[k].y;
        vertices[9 * i + 3 * k + 2] = v[k].z;
        indices[3 * i + k] = uint32_t(3 * i + k);
      }
    }
    rtcCommitGeometry(mesh);
    rtcAttachGeometry(state_->scene, mesh);
    rtcReleaseGeometry(mesh);
    rtcCommitScene(state_->scene);
  });
  bytes_ = uint64_t(std::max<int64_t>(0, state_->bytes.load()));
}

EmbreeScene::~EmbreeScene() {
  if (state_->scene) rtcReleaseScene(state_->scene);
  rtcReleaseDevice(state_->device);
  delete state_;
}

void EmbreeScene::trace(std::span<const CeilingRay> rays, std::span<CeilingHit> hits, unsigned threads) const {
  forEachBlock(rays.size(), threads, [&](size_t begin, size_t end) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (size_t i = begin; i < end; ++i) {
      RTCRayHit r{};
      r.ray.org_x = rays[i].origin.x;
      r.ray.org_y = rays[i].origin.y;
      r.ray.org_z = rays[i].origin.z;
      r.ray.dir_x = rays[i].direction.x;
      r.ray.dir_y = rays[i].direction.y;
      r.ray.dir_z = rays[i].direction.z;
      r.ray.tnear = 0.0f;
      r.ray.tfar = kFar;
      r.ray.mask = ~0u;
      r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      r.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(state_->scene, &context, &r);
      const bool found = r.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      hits[i] = {found, found ? r.hit.primID : 0u, found ? r.ray.tfar : kFar};
    }
  });
}

#else

bool embreeAvailable() { return false; }
EmbreeScene::EmbreeScene(const RayCeilingGeometry&, unsigned) {
  throw std::runtime_error("built without Embree (install libembree-dev and reconfigure with -DSPECTRACE_EMBREE=ON)");
}
EmbreeScene::~EmbreeScene() = default;
void EmbreeScene::trace(std::span<const CeilingRay>, std::span<CeilingHit>, unsigned) const {}

#endif

RayCeilingRow runRayCeiling(uint64_t triangles, uint64_t rayCount, unsigned threads, const std::atomic<bool>& cancel) {
  RayCeilingRow row;
  row.threads = std::max(1u, threads);
  row.cpuCode = cpuCodeName(fastestCpuCode());
  const RayCeilingGeometry geometry = meshCeilingGeometry(triangles);
  row.triangles = geometry.primitives.size();
  row.bytesPerTriangle = geometry.bytesPerPrimitive();
  row.vulkanBytesPerTriangle = geometry.bytesPerPrimitive(sizeof(device::PackedBvhNode));
  const std::vector<CeilingRay> rays = incoherentRays(geometry, rayCount, 1);
  row.rays = rays.size();
  std::vector<CeilingHit> ours(rays.size()), theirs(rays.size());
  row.embree = embreeAvailable();
  std::unique_ptr<EmbreeScene> embree;
  if (row.embree) {
    embree = std::make_unique<EmbreeScene>(geometry, row.threads);
    row.embreeBuildSeconds = embree->buildSeconds();
    row.embreeBytesPerTriangle = double(embree->bytes()) / double(row.triangles);
  }
  // Interleaved rounds, least of each, so a neighbour's load on the shared
  // cores touches every variant alike.
  constexpr int kRounds = 2;
  row.spectrace1 = row.spectraceN = row.embree1 = row.embreeN = row.interleaved1 = row.interleavedN = INFINITY;
  std::vector<CeilingHit> interleaved(rays.size());
  for (int round = 0; round < kRounds && !cancel.load(); ++round) {
    row.spectrace1 = std::min(row.spectrace1, secondsOf([&] { traceSpectrace(geometry, rays, ours, 1); }));
    row.spectraceN = std::min(row.spectraceN, secondsOf([&] { traceSpectrace(geometry, rays, ours, row.threads); }));
    row.interleaved1 =
        std::min(row.interleaved1, secondsOf([&] { traceSpectraceInterleaved(geometry, rays, interleaved, 1); }));
    row.interleavedN = std::min(
        row.interleavedN, secondsOf([&] { traceSpectraceInterleaved(geometry, rays, interleaved, row.threads); }));
    if (!embree) continue;
    row.embree1 = std::min(row.embree1, secondsOf([&] { embree->trace(rays, theirs, 1); }));
    row.embreeN = std::min(row.embreeN, secondsOf([&] { embree->trace(rays, theirs, row.threads); }));
  }
  for (const CeilingHit& h : ours) row.hits += h.hit ? 1 : 0;
  // The same walks, so the same hits, bit for bit.
  for (size_t i = 0; i < rays.size(); ++i)
    if (interleaved[i].hit != ours[i].hit || interleaved[i].primitive != ours[i].primitive ||
        interleaved[i].t != ours[i].t)
      ++row.interleavedDifferences;
  if (embree) row.disagreements = compareHits(ours, theirs);
  return row;
}

}  // namespace spectrace
