#include "bench/ceiling.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>
#include <thread>

#include "bench_shaders.h"
#include "spectrum/spd.h"
#include "vulkan/buffer.h"
#include "vulkan/compute_pipeline.h"
#include "vulkan/context.h"
#include "vulkan/timestamps.h"

namespace spectrace {
namespace {

// As shaders/ceiling.comp.
uint32_t pcgHash(uint32_t v) {
  const uint32_t state = v * 747796405u + 2891336453u;
  const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
float uniformOf(uint32_t word) { return float(word >> 8u) * (1.0f / 16777216.0f); }

// One beam of the ceiling; returns its pixel-bin counter, or -1 for a miss.
int64_t ceilingBeam(const CeilingScene& scene, uint32_t index) {
  const device::CeilingPush& g = scene.geometry;
  const uint32_t h0 = pcgHash(index), h1 = pcgHash(h0), h2 = pcgHash(h1), h3 = pcgHash(h2), h4 = pcgHash(h3);
  const float u = uniformOf(h0);
  uint32_t lo = 0, hi = g.cdfCount - 1;
  while (hi - lo > 1) {
    const uint32_t mid = (lo + hi) >> 1;
    if (scene.cdf[mid] <= u) lo = mid; else hi = mid;
  }
  const float width = scene.cdf[lo + 1] - scene.cdf[lo];
  const float t = width > 0.0f ? (u - scene.cdf[lo]) / width : 0.0f;
  const float lambda = g.lambdaMin + (float(lo) + t) * g.nmPerNode;
  const uint32_t bin = std::min(uint32_t(std::max((lambda - g.lambdaMin) * g.binsPerNm, 0.0f)), g.bins - 1);
  constexpr float kTwoPi = 6.2831853f;
  const float r = g.diskRadius * std::sqrt(uniformOf(h1));
  const float phi = kTwoPi * uniformOf(h2);
  const float ox = r * std::cos(phi), oy = r * std::sin(phi), oz = g.diskDistance;
  const float sinSq = uniformOf(h3);
  const float sinTheta = std::sqrt(sinSq), cosTheta = std::sqrt(1.0f - sinSq);
  const float psi = kTwoPi * uniformOf(h4);
  const float dx = sinTheta * std::cos(psi), dy = sinTheta * std::sin(psi);
  if (!(cosTheta > 0.0f)) return -1;
  const float s = oz / cosTheta;
  const float hx = ox + s * dx, hy = oy + s * dy;
  if (!(std::abs(hx) < g.sensorHalfSize) || !(std::abs(hy) < g.sensorHalfSize)) return -1;
  const uint32_t column = std::min(uint32_t((hx + g.sensorHalfSize) * g.pixelsPerMetre), g.pixels - 1);
  const uint32_t row = std::min(uint32_t((g.sensorHalfSize - hy) * g.pixelsPerMetre), g.pixels - 1);
  return (int64_t(row) * g.pixels + column) * g.bins + bin;
}

uint64_t countersOf(const CeilingScene& scene) {
  return uint64_t(scene.geometry.pixels) * scene.geometry.pixels * scene.geometry.bins;
}

}  // namespace

CeilingScene throughputCeilingScene() {
  CeilingScene scene;
  device::CeilingPush& g = scene.geometry;
  g.lambdaMin = 360.0f;
  g.nmPerNode = 1.0f;
  g.cdfCount = 471;
  g.bins = 64;
  g.binsPerNm = 64.0f / 470.0f;
  g.diskRadius = 0.05f;
  g.diskDistance = 0.1f;
  g.sensorHalfSize = 0.05f;
  g.pixels = 512;
  g.pixelsPerMetre = 512.0f / 0.1f;
  // The CDF of the D65 table, trapezoids between 1 nm nodes.
  const Spd d65 = *cieIlluminant("D65");
  std::vector<double> sums(g.cdfCount, 0.0);
  for (uint32_t i = 1; i < g.cdfCount; ++i)
    sums[i] = sums[i - 1] + 0.5 * (d65.evaluate(g.lambdaMin + i - 1.0) + d65.evaluate(g.lambdaMin + double(i)));
  for (double s : sums) scene.cdf.push_back(float(s / sums.back()));
  return scene;
}

CeilingResult traceCeilingOnCpu(const CeilingScene& scene, uint64_t beams, unsigned threads) {
  threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  CeilingResult result;
  result.beams = beams;
  result.counts.assign(countersOf(scene), 0);
  std::atomic<uint64_t> hits{0};
  const auto start = std::chrono::steady_clock::now();
  {
    std::vector<std::jthread> pool;
    for (unsigned t = 0; t < threads; ++t)
      pool.emplace_back([&, t] {
        uint64_t hitsHere = 0;
        for (uint64_t i = t; i < beams; i += threads) {
          const int64_t counter = ceilingBeam(scene, uint32_t(i));
          if (counter < 0) continue;
          std::atomic_ref<uint32_t>(result.counts[size_t(counter)]).fetch_add(1, std::memory_order_relaxed);
          ++hitsHere;
        }
        hits.fetch_add(hitsHere, std::memory_order_relaxed);
      });
  }  // joins
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.hits = hits.load();
  return result;
}

CeilingResult traceCeilingOnVulkan(const vk_util::Context& context, const CeilingScene& scene, uint64_t beams) {
  constexpr uint32_t kWorkgroup = 64;
  std::vector<vk_util::BindingSpec> bindings;
  for (const auto& slot : device::kCeilingBindings) bindings.push_back({slot.binding, slot.count});
  vk_util::ComputePipeline pipeline(context, embedded::spv_ceiling(), bindings, sizeof(device::CeilingPush),
                                    {{device::kSpecWorkgroupSize, kWorkgroup}});
  vk_util::Buffer cdf(context, scene.cdf.size() * sizeof(float), {}, vk_util::MemoryPlacement::DeviceLocal);
  cdf.upload(scene.cdf.data(), scene.cdf.size() * sizeof(float));
  vk_util::Buffer counts(context, countersOf(scene) * sizeof(uint32_t), {}, vk_util::MemoryPlacement::DeviceLocal);
  counts.fillZero();
  pipeline.bindBuffer(device::kBindingCeilingCdf, 0, cdf);
  pipeline.bindBuffer(device::kBindingCeilingHistogram, 0, counts);
  vk_util::TimestampQueries timestamps(context, 2);
  CeilingResult result;
  result.beams = beams;
  const uint32_t maxGroupsX = context.info().maxComputeWorkGroupCount[0];
  for (uint64_t done = 0; done < beams;) {
    const uint64_t count = std::min<uint64_t>(beams - done, uint64_t(1) << 30);
    const vk_util::DispatchGrid grid = vk_util::dispatchGridFor(count, kWorkgroup, maxGroupsX);
    device::CeilingPush push = scene.geometry;
    push.beamBase = uint32_t(done);
    push.beamCount = uint32_t(count);
    push.beamsPerRow = grid.invocationsPerRow;
    context.submitAndWait([&](const vk::raii::CommandBuffer& cb) {
      timestamps.reset(cb);
      timestamps.write(cb, 0);
      pipeline.recordDispatch(cb, &push, grid.groupsX, grid.groupsY);
      timestamps.write(cb, 1);
    });
    const auto ns = timestamps.readNanoseconds();
    result.seconds += (ns[1] - ns[0]) * 1e-9;
    done += count;
  }
  result.counts.resize(countersOf(scene));
  counts.download(result.counts.data(), result.counts.size() * sizeof(uint32_t));
  result.hits = std::accumulate(result.counts.begin(), result.counts.end(), uint64_t(0));
  return result;
}

}  // namespace spectrace
