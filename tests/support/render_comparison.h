#pragma once
// Do two renders of one scene (aimed and analog, skipped and unskipped, ...)
// have the same expected image? Pixel by pixel within their combined
// standard errors (5 sigma), globally by chi-square, and in total. And does
// a render match its scene's exact image, by the same tests?
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "film/spectral_histogram.h"
#include "compile/compile_scene.h"
#include "reference/exact_solution.h"
#include "render/renderer.h"
#include "support/p_values.h"

namespace spectrace::testing {

// Per-pixel irradiance of a render, and its variance model Var(E) = v E.
// A pixel's estimate is k C (C its counts, k the irradiance per count). With
// plain hit counts (Poisson) v = k. With weighted counts,
// Var(E) = k^2 U S2 (S2 the squared-weight sum in the same units as C, U
// the units per beam), so v = k U S2 / C; where C = 0 the image-wide
// S2 / C stands in.
struct PixelEstimates {
  std::vector<double> irradiance;
  std::vector<double> variancePerMean;
  uint64_t countedBeams = 0;
  double totalVariance = 0.0;  // sum over pixels of v E
};

inline PixelEstimates pixelEstimates(const SpectralHistogram& h, const CompiledScene& plan, uint64_t beams) {
  const double k = plan.irradiancePerCount(beams), units = double(h.unitsPerBeam);
  const size_t pixels = size_t(h.pixelsX) * h.pixelsY;
  std::vector<double> counts(pixels, 0.0);
  double allCounts = 0.0, allSquares = 0.0;
  for (size_t p = 0; p < pixels; ++p) {
    for (uint32_t b = 0; b < h.bins; ++b) counts[p] += realOf(h.count(uint32_t(p), b));
    allCounts += counts[p];
    if (h.isWeighted()) allSquares += realOf(h.counter(device::kFilmChannelSquaredWeight, p));
  }
  const double globalShape = h.isWeighted() && allCounts > 0.0 ? units * allSquares / allCounts : 1.0;
  PixelEstimates out;
  out.countedBeams = h.countedBeams;
  for (size_t p = 0; p < pixels; ++p) {
    double shape = 1.0;
    if (h.isWeighted())
      shape = counts[p] > 0.0 ? units * realOf(h.counter(device::kFilmChannelSquaredWeight, p)) / counts[p] : globalShape;
    out.irradiance.push_back(k * counts[p]);
    out.variancePerMean.push_back(k * shape);
    out.totalVariance += k * shape * k * counts[p];
  }
  return out;
}

struct RenderComparison {
  int cells = 0;
  double chi2 = 0.0, pValue = 1.0, worstZ = 0.0, totalZ = 0.0;
};

// Compares two renders' pixels where together they expect at least
// `minHits` effective counts (E / v summed over both; below that the normal
// approximation fails). Under the hypothesis of equal expectations E, the
// best estimate of E weights each side by 1 / v, and
// Var(E1 - E2) = (v1 + v2) E; estimating each side's variance from its own
// count would understate it where that count is low. Adds a failure for
// any pixel beyond 5 sigma and for a total beyond 5 sigma.
inline RenderComparison compareRenders(const PixelEstimates& a, const PixelEstimates& b, const std::string& name,
                                       double minHits = 20.0) {
  RenderComparison result;
  double totalA = 0.0, totalB = 0.0;
  int failures = 0;
  for (size_t p = 0; p < a.irradiance.size(); ++p) {
    totalA += a.irradiance[p];
    totalB += b.irradiance[p];
    const double va = a.variancePerMean[p], vb = b.variancePerMean[p];
    const double pooled = (a.irradiance[p] / va + b.irradiance[p] / vb) / (1.0 / va + 1.0 / vb);
    if (pooled / va + pooled / vb < minHits) continue;
    const double z = (a.irradiance[p] - b.irradiance[p]) / std::sqrt((va + vb) * pooled);
    if (std::abs(z) >= 5.0 && ++failures <= 10)
      ADD_FAILURE() << name << ": pixel " << p << ": " << a.irradiance[p] << " vs " << b.irradiance[p] << " W/m^2, "
                    << z << " sigma";
    result.worstZ = std::max(result.worstZ, std::abs(z));
    result.chi2 += z * z;
    ++result.cells;
  }
  result.totalZ = (totalA - totalB) / std::sqrt(a.totalVariance + b.totalVariance);
  EXPECT_LT(std::abs(result.totalZ), 5.0) << name << ": total " << totalA << " vs " << totalB;
  if (result.cells > 0)
    result.pValue = chiSquareUpperTail(result.chi2, result.cells);
  std::printf("%s: %llu vs %llu beams counted; %d pixels compared, chi2/dof %.3f (p %.4f), worst %.2f sigma, "
              "total %+.2f sigma\n",
              name.c_str(), (unsigned long long)a.countedBeams, (unsigned long long)b.countedBeams, result.cells,
              result.cells ? result.chi2 / result.cells : 0.0, result.pValue, result.worstZ, result.totalZ);
  return result;
}

// A render's pixels against the scene's exact image (host/reference,
// exactSolution): z = (E - e) / sqrt(v e)
// with the render's variance model (testing::pixelEstimates), where the
// pixel expects at least 20 counts; 5 sigma each, a chi-square p-value
// above 1e-3, and the total within 5 sigma.
inline void expectMatchesExactImage(const Scene& scene, const RenderResult& r, uint64_t beams, const char* name) {
  const auto exact = exactSolution(scene);
  ASSERT_TRUE(exact.has_value()) << name;
  const PixelEstimates est = pixelEstimates(r.histogram, r.plan, beams);
  double chi2 = 0.0, total = 0.0, expectedTotal = 0.0, variance = 0.0, worst = 0.0;
  int cells = 0, failures = 0;
  for (size_t p = 0; p < est.irradiance.size(); ++p) {
    const double e = exact->irradiance[p], v = est.variancePerMean[p];
    total += est.irradiance[p];
    expectedTotal += e;
    variance += v * e;
    if (e / v < 20.0) continue;
    const double z = (est.irradiance[p] - e) / std::sqrt(v * e);
    if (std::abs(z) >= 5.0 && ++failures <= 10)
      ADD_FAILURE() << name << ": pixel " << p << ": " << est.irradiance[p] << " vs exact " << e << ", " << z
                    << " sigma";
    worst = std::max(worst, std::abs(z));
    chi2 += z * z;
    ++cells;
  }
  const double p = chiSquareUpperTail(chi2, cells);
  const double totalZ = (total - expectedTotal) / std::sqrt(variance);
  std::printf("%s: %d pixels, chi2/dof %.3f (p %.4f), worst %.2f sigma, total %+.2f sigma\n", name, cells,
              chi2 / cells, p, worst, totalZ);
  EXPECT_GT(cells, 300) << name;
  EXPECT_GT(p, 1e-3) << name;
  EXPECT_LT(std::abs(totalZ), 5.0) << name;
}

}  // namespace spectrace::testing
