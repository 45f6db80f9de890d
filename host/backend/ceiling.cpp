#include "backend/ceiling.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

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

}  // namespace

uint64_t ceilingCountersOf(const CeilingScene& scene) {
  return uint64_t(scene.geometry.pixels) * scene.geometry.pixels * scene.geometry.bins;
}

CeilingResult traceCeilingOnCpu(const CeilingScene& scene, uint64_t beams, unsigned threads) {
  threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  CeilingResult result;
  result.beams = beams;
  result.counts.assign(ceilingCountersOf(scene), 0);
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

}  // namespace spectrace
