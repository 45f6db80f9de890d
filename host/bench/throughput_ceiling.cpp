#include "bench/throughput_ceiling.h"

#include "spectrum/spd.h"

namespace spectrace {

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

}  // namespace spectrace
