// The colour-from-bins shortcut (compile/shortcuts.h) against the
// unshortened path, per-beam CMF sums: the bin means integrate to the exact
// tristimulus values of the sampled spectrum, the same beams give the same
// bins, and the two colour estimates of one render agree to within 5 sigma
// of the within-bin spread, where the flat bin average used without exact
// colour does not. Also when it must not apply.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/vec3.hpp>

#include "colour/colour.h"
#include "compile/compile_scene.h"
#include "render/renderer.h"
#include "spectrum/cie_data.h"
#include "spectrum/wavelength_sampler.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

constexpr int kBins = 12;  // coarse bins, so that binning error would show

Scene d65DiskScene() {
  Scene scene = testing::bareSensorScene(0.02, 0.02, 8, 8, kBins);
  Light disk = testing::surfaceLight(LightType::Disk, {0.0, 0.0, 0.01}, {0, 0, -1}, 1.0, *cieIlluminant("D65"));
  disk.radiusM = 0.01;
  scene.lights = {disk};
  return scene;
}

// Exact: sum_b P(b) mean_b = E[cmf(lambda)] = integral of the sampled
// density times the CMF, here against spdToXyz of the same (unclipped, in
// range) SPD over its integral, to integration round-off.
TEST(ColourFromBins, BinMeansIntegrateToTheSpectrumsTristimulusValues) {
  const Spd spd = *cieIlluminant("D65");
  const Spd clipped = spd.clipped(360.0, 830.0);
  const SpectralTable table = buildSpectralTable(clipped);
  const Observer& observer = cie1931Observer();
  const auto means = sampledBinCmfMeans(table.intervals, observer, 360.0, 830.0, kBins);
  // P(b) from the table's exact interval probabilities, split linearly.
  std::vector<uint64_t> lows;
  for (const auto& iv : table.intervals) lows.push_back(iv.cdfLow);
  std::vector<double> pBin(kBins, 0.0);
  const double binWidth = (830.0 - 360.0) / kBins;
  for (size_t j = 0; j < table.intervals.size(); ++j) {
    const auto& iv = table.intervals[j];
    const double p = cdfProbability(lows, j);
    // The density is linear in t, so its mass over [t0, t1] is exact:
    // F(t) = (1 - slope) t + slope t^2.
    auto F = [&](double t) { return (1.0 - iv.slope) * t + iv.slope * t * t; };
    for (int b = 0; b < kBins; ++b) {
      if (!(iv.width > 0.0f)) {
        if (int((iv.lambda0 - 360.0) / binWidth) == b) pBin[b] += p;
        continue;
      }
      const double t0 = std::clamp((360.0 + b * binWidth - iv.lambda0) / iv.width, 0.0, 1.0);
      const double t1 = std::clamp((360.0 + (b + 1) * binWidth - iv.lambda0) / iv.width, 0.0, 1.0);
      pBin[b] += p * (F(t1) - F(t0));
    }
  }
  const auto xyz = spdToXyz(clipped, observer);
  const double integral = table.integral;
  for (int k = 0; k < 3; ++k) {
    double expectation = 0.0;
    for (int b = 0; b < kBins; ++b) expectation += pBin[b] * means[b][k];
    EXPECT_NEAR(expectation / (xyz[k] / integral), 1.0, 1e-6) << "component " << k;
  }
}

// One render, both estimates: per-beam sums X_pb = sum_i cmf(lambda_i) and
// X_cb = sum_b n_b mean_b. Their difference has expectation 0 and variance
// sum_b n_b Var(cmf | b) <= sum_b n_b (range_b / 2)^2, range_b the spread of
// the CMF over bin b; 5 sigma of that bound. The flat bin average misses by
// far more.
TEST(ColourFromBins, AgreesWithPerBeamColourOnTheSameBeams) {
  const Scene scene = d65DiskScene();
  RenderOptions options;
  options.beams = 4'000'000;
  options.seed = 17;
  options.device = DeviceChoice::Cpu;
  const RenderResult shortcut = render(scene, options);
  options.plan.colourFromBins = false;
  const RenderResult perBeam = render(scene, options);
  ASSERT_TRUE(shortcut.plan.film.colourFromBins);
  ASSERT_FALSE(shortcut.histogram.hasExactColour()) << "no per-beam colour counters with the shortcut";
  ASSERT_TRUE(perBeam.histogram.hasExactColour());
  ASSERT_EQ(shortcut.histogram.counts(), perBeam.histogram.counts()) << "the same beams land in the same bins";

  const Observer& observer = cie1931Observer();
  const auto flat = binAveragedCmf(observer, 360.0, 830.0, kBins);
  const auto& means = shortcut.plan.colourBinMeans;
  const uint32_t offset = shortcut.plan.film.firstStoredBin;
  const auto& h = perBeam.histogram;
  const size_t pixels = size_t(h.pixelsX) * h.pixelsY;
  std::vector<double> nBin(kBins, 0.0);
  glm::dvec3 perBeamSum(0.0);
  for (size_t p = 0; p < pixels; ++p) {
    for (uint32_t b = 0; b < h.bins; ++b) nBin[b + offset] += double(h.at(uint32_t(p), b));
    for (int k = 0; k < 3; ++k) perBeamSum[k] += double(h.colourSums()[p * 3 + k]) / device::kColourFixedPointScale;
  }
  const double binWidth = (830.0 - 360.0) / kBins;
  bool flatMissed = false;
  for (int k = 0; k < 3; ++k) {
    double fromBins = 0.0, fromFlat = 0.0, variance = 0.0, counted = 0.0;
    for (int b = 0; b < kBins; ++b) {
      double lo = INFINITY, hi = -INFINITY;
      for (int s = 0; s <= 1000; ++s) {
        const double value = cmfAt(observer, 360.0 + binWidth * (b + s / 1000.0))[k];
        lo = std::min(lo, value);
        hi = std::max(hi, value);
      }
      fromBins += nBin[b] * means[b][k];
      fromFlat += nBin[b] * flat[b][k];
      variance += nBin[b] * 0.25 * (hi - lo) * (hi - lo);
      counted += nBin[b];
    }
    variance += counted * 0.25 / (double(device::kColourFixedPointScale) * device::kColourFixedPointScale);  // rounding
    const double sigma = std::sqrt(variance);
    std::printf("component %d: per-beam %.6g, from bins %.6g, flat %.6g, sigma <= %.3g over %.0f beams\n", k,
                perBeamSum[k], fromBins, fromFlat, sigma, counted);
    EXPECT_LE(std::abs(fromBins - perBeamSum[k]), 5.0 * sigma) << "component " << k;
    flatMissed |= std::abs(fromFlat - perBeamSum[k]) > 5.0 * sigma;
  }
  EXPECT_TRUE(flatMissed) << "the test should tell the flat bin average from the exact colour";
  // And the developed images agree to the same scale: total Y.
  double yShortcut = 0.0, yPerBeam = 0.0;
  for (size_t p = 0; p < pixels; ++p) {
    yShortcut += shortcut.image.xyz[p * 3 + 1];
    yPerBeam += perBeam.image.xyz[p * 3 + 1];
  }
  EXPECT_NEAR(yShortcut / yPerBeam, 1.0, 1e-2);
}

TEST(ColourFromBins, NotTakenForLightsWithDifferentSpectra) {
  Scene scene = d65DiskScene();
  scene.lights.push_back(testing::pointLight({0.001, 0.0, 0.005}, 0.5, makeBlackbodySpd(3000, 360, 830)));
  const CompiledScene plan = compileScene(scene, 1);
  EXPECT_FALSE(plan.film.colourFromBins);
  EXPECT_TRUE(plan.film.exactColour) << "per-beam colour counters instead";
  scene.lights[1].spd = scene.lights[0].spd;  // the same spectrum: one table again
  EXPECT_TRUE(compileScene(scene, 1).film.colourFromBins);
}

}  // namespace
}  // namespace spectrace
