#include "metrics/error_metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace spectrace {
namespace {

using Lab = std::array<double, 3>;

// ------------------------------------------------------------------ CIEDE2000

struct SharmaPair {
  int number;
  Lab lab1, lab2;
  double deltaE;
};

// All 34 pairs of Table 1 of G. Sharma, W. Wu, E. N. Dalal, "The CIEDE2000
// color-difference formula: implementation notes, supplementary test data,
// and mathematical observations", Color Res. Appl. 30(1):21-30, 2005
// (kL = kC = kH = 1). ΔE00 is published to 4 decimals. Pairs 7-16 exercise
// the arctangent/hue wrap (including a zero-chroma colour, pairs 7-8, and
// hue differences on either side of 180°, 9-16); 21-24 are CIE's ΔE = 1
// ellipse pairs; 33-34 are near black.
const SharmaPair kSharma[] = {
    {1, {50.0000, 2.6772, -79.7751}, {50.0000, 0.0000, -82.7485}, 2.0425},
    {2, {50.0000, 3.1571, -77.2803}, {50.0000, 0.0000, -82.7485}, 2.8615},
    {3, {50.0000, 2.8361, -74.0200}, {50.0000, 0.0000, -82.7485}, 3.4412},
    {4, {50.0000, -1.3802, -84.2814}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {5, {50.0000, -1.1848, -84.8006}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {6, {50.0000, -0.9009, -85.5211}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {7, {50.0000, 0.0000, 0.0000}, {50.0000, -1.0000, 2.0000}, 2.3669},
    {8, {50.0000, -1.0000, 2.0000}, {50.0000, 0.0000, 0.0000}, 2.3669},
    {9, {50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0009}, 7.1792},
    {10, {50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0010}, 7.1792},
    {11, {50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0011}, 7.2195},
    {12, {50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0012}, 7.2195},
    {13, {50.0000, -0.0010, 2.4900}, {50.0000, 0.0009, -2.4900}, 4.8045},
    {14, {50.0000, -0.0010, 2.4900}, {50.0000, 0.0010, -2.4900}, 4.8045},
    {15, {50.0000, -0.0010, 2.4900}, {50.0000, 0.0011, -2.4900}, 4.7461},
    {16, {50.0000, 2.5000, 0.0000}, {50.0000, 0.0000, -2.5000}, 4.3065},
    {17, {50.0000, 2.5000, 0.0000}, {73.0000, 25.0000, -18.0000}, 27.1492},
    {18, {50.0000, 2.5000, 0.0000}, {61.0000, -5.0000, 29.0000}, 22.8977},
    {19, {50.0000, 2.5000, 0.0000}, {56.0000, -27.0000, -3.0000}, 31.9030},
    {20, {50.0000, 2.5000, 0.0000}, {58.0000, 24.0000, 15.0000}, 19.4535},
    {21, {50.0000, 2.5000, 0.0000}, {50.0000, 3.1736, 0.5854}, 1.0000},
    {22, {50.0000, 2.5000, 0.0000}, {50.0000, 3.2972, 0.0000}, 1.0000},
    {23, {50.0000, 2.5000, 0.0000}, {50.0000, 1.8634, 0.5757}, 1.0000},
    {24, {50.0000, 2.5000, 0.0000}, {50.0000, 3.2592, 0.3350}, 1.0000},
    {25, {60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644},
    {26, {63.0109, -31.0961, -5.8663}, {62.8187, -29.7946, -4.0864}, 1.2630},
    {27, {61.2901, 3.7196, -5.3901}, {61.4292, 2.2480, -4.9620}, 1.8731},
    {28, {35.0831, -44.1164, 3.7933}, {35.0232, -40.0716, 1.5901}, 1.8645},
    {29, {22.7233, 20.0904, -46.6940}, {23.0331, 14.9730, -42.5619}, 2.0373},
    {30, {36.4612, 47.8580, 18.3852}, {36.2715, 50.5065, 21.2231}, 1.4146},
    {31, {90.8027, -2.0831, 1.4410}, {91.1528, -1.6435, 0.0447}, 1.4441},
    {32, {90.9257, -0.5406, -0.9208}, {88.6381, -0.8985, -0.7239}, 1.5381},
    {33, {6.7747, -0.2908, -2.4247}, {5.8714, -0.0985, -2.2286}, 0.6377},
    {34, {2.0776, 0.0795, -1.1350}, {0.9033, -0.0636, -0.5514}, 0.9082},
};

TEST(Ciede2000, MatchesSharmaWuDalalTable1) {
  // Published to 4 decimals: rounding leaves at most 5e-5.
  for (const auto& p : kSharma) {
    EXPECT_NEAR(ciede2000(p.lab1, p.lab2), p.deltaE, 1e-4) << "pair " << p.number;
    EXPECT_NEAR(ciede2000(p.lab2, p.lab1), p.deltaE, 1e-4) << "pair " << p.number << " swapped";
  }
}

TEST(Ciede2000, ZeroForIdenticalColoursAndPureLightnessForGreys) {
  EXPECT_EQ(ciede2000({50, 10, -20}, {50, 10, -20}), 0.0);
  EXPECT_EQ(ciede2000({0, 0, 0}, {0, 0, 0}), 0.0);
  // Two greys: only the lightness term, ΔL / S_L with L̄ = 71.
  const double l50 = 21.0 * 21.0;
  const double sl = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
  EXPECT_NEAR(ciede2000({100, 0, 0}, {42, 0, 0}), 58.0 / sl, 1e-12);
}

// ------------------------------------------------------------------- CIELAB

TEST(XyzToLab, WhiteIsL100) {
  const std::array<double, 3> d65{0.95047, 1.0, 1.08883};
  const Lab w = xyzToLab(d65, d65);
  EXPECT_NEAR(w[0], 100.0, 1e-12);
  EXPECT_NEAR(w[1], 0.0, 1e-12);
  EXPECT_NEAR(w[2], 0.0, 1e-12);
  const Lab w2 = xyzToLab({95.047, 100.0, 108.883}, {95.047, 100.0, 108.883});
  EXPECT_NEAR(w2[0], 100.0, 1e-12);
  EXPECT_EQ(xyzToLab({0, 0, 0}, d65)[0], 0.0);
}

TEST(XyzToLab, KnownValues) {
  const std::array<double, 3> white{0.95047, 1.0, 1.08883};
  // Cube-root branch: ratios 0.216, 0.125, 0.064 give f = 0.6, 0.5, 0.4, so
  // L* = 116·0.5 - 16 = 42, a* = 500·0.1 = 50, b* = 200·0.1 = 20.
  const Lab lab = xyzToLab({0.216 * white[0], 0.125 * white[1], 0.064 * white[2]}, white);
  EXPECT_NEAR(lab[0], 42.0, 1e-12);
  EXPECT_NEAR(lab[1], 50.0, 1e-12);
  EXPECT_NEAR(lab[2], 20.0, 1e-12);
  // Linear branch: Y/Yn = 0.001 < (6/29)^3 gives L* = (29/3)^3 · 0.001.
  EXPECT_NEAR(xyzToLab({0.00095047, 0.001, 0.00108883}, white)[0], 24389.0 / 27.0 * 0.001, 1e-12);
  // Continuity at Y/Yn = (6/29)^3, where L* = 8.
  const double eps = 216.0 / 24389.0;
  EXPECT_NEAR(xyzToLab({0, eps * (1 - 1e-12), 0}, {1, 1, 1})[0], 8.0, 1e-9);
  EXPECT_NEAR(xyzToLab({0, eps * (1 + 1e-12), 0}, {1, 1, 1})[0], 8.0, 1e-9);
  // sRGB red (IEC 61966-2-1 XYZ of the primary) against D65: the commonly
  // tabulated (53.24, 80.09, 67.20).
  const Lab red = xyzToLab({0.4124564, 0.2126729, 0.0193339}, white);
  EXPECT_NEAR(red[0], 53.24, 0.01);
  EXPECT_NEAR(red[1], 80.09, 0.01);
  EXPECT_NEAR(red[2], 67.20, 0.01);
}

// ---------------------------------------------------------- synthetic images

struct Pair {
  RenderImage render;
  ReferenceImage reference;
};

// A w x h pair whose reference has irradiance eref[i], XYZ = eref[i] x
// (0.9, 1, 1.1) and all pixels valid; the render starts as a float copy.
Pair makePair(int w, int h, const std::vector<double>& eref) {
  Pair p;
  const size_t n = size_t(w) * h;
  p.reference.width = p.render.width = w;
  p.reference.height = p.render.height = h;
  p.reference.irradiance = eref;
  p.reference.valid.assign(n, 1);
  p.reference.xyz.resize(3 * n);
  p.render.xyz.resize(3 * n);
  p.render.rgb.assign(3 * n, 0.0f);
  p.render.irradiance.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const double xyz[3] = {0.9 * eref[i], eref[i], 1.1 * eref[i]};
    for (int k = 0; k < 3; ++k) {
      p.reference.xyz[3 * i + k] = xyz[k];
      p.render.xyz[3 * i + k] = float(xyz[k]);
    }
    p.render.irradiance[i] = float(eref[i]);
  }
  return p;
}

std::vector<double> ramp(size_t n) {
  std::vector<double> e(n);
  for (size_t i = 0; i < n; ++i) e[i] = 0.5 + 0.25 * double(i);  // exact in float
  return e;
}

TEST(ErrorMetrics, UniformOnePercentHigh) {
  Pair p = makePair(8, 4, ramp(32));
  for (size_t i = 0; i < 32; ++i) p.render.irradiance[i] = float(1.01 * p.reference.irradiance[i]);
  const ErrorMetrics m = computeErrorMetrics(p.render, p.reference, {});
  EXPECT_EQ(m.pixels, 32u);
  // Float storage of the render: relative rounding <= 6e-8.
  EXPECT_NEAR(m.bias, 0.01, 1e-6);
  EXPECT_NEAR(m.relRmse, 0.01, 1e-6);
  EXPECT_NEAR(m.relMse, 1e-4, 2e-8);
  EXPECT_TRUE(std::isnan(m.estimatedRelRmse));
  EXPECT_TRUE(std::isnan(m.honesty));
}

TEST(ErrorMetrics, AlternatingErrorsSkipInvalidAndBlackPixels) {
  std::vector<double> e = ramp(12);
  e[10] = 0.0;  // valid but black in the reference: no relative error
  Pair p = makePair(4, 3, e);
  // Pixels 0-9: +2% and -2% alternately, so bias 0 and relRMSE 0.02.
  for (size_t i = 0; i < 10; ++i)
    p.render.irradiance[i] = float(p.reference.irradiance[i] * (i % 2 ? 0.98 : 1.02));
  p.render.irradiance[10] = 5.0f;  // over a black reference pixel: ignored
  p.reference.valid[11] = 0;       // invalid, however wrong
  p.render.irradiance[11] = 1e6f;
  const ErrorMetrics m = computeErrorMetrics(p.render, p.reference, {});
  EXPECT_EQ(m.pixels, 10u);
  EXPECT_NEAR(m.bias, 0.0, 1e-6);
  EXPECT_NEAR(m.relRmse, 0.02, 1e-6);
  EXPECT_NEAR(m.relMse, 4e-4, 1e-7);
}

TEST(ErrorMetrics, NoUsablePixelsGivesNaN) {
  Pair p = makePair(2, 1, {0.0, 1.0});
  p.reference.valid[1] = 0;
  const ErrorMetrics m = computeErrorMetrics(p.render, p.reference, {});
  EXPECT_EQ(m.pixels, 0u);
  EXPECT_TRUE(std::isnan(m.relMse));
  EXPECT_TRUE(std::isnan(m.bias));
  EXPECT_TRUE(std::isnan(m.deltaE2000Mean));
  EXPECT_TRUE(std::isnan(m.meanChromaticityError));
}

TEST(ErrorMetrics, RejectsMismatchedShapes) {
  Pair p = makePair(2, 2, ramp(4));
  Pair q = makePair(4, 1, ramp(4));
  EXPECT_THROW(computeErrorMetrics(p.render, q.reference, {}), std::invalid_argument);
  EXPECT_THROW(computeErrorMetrics(p.render, p.reference, std::vector<double>(3, 0.0)), std::invalid_argument);
  p.reference.valid.pop_back();
  EXPECT_THROW(computeErrorMetrics(p.render, p.reference, {}), std::invalid_argument);
}

TEST(ErrorMetrics, ChromaticityErrorOfSummedXyz) {
  Pair p = makePair(2, 1, {1.0, 1.0});
  for (size_t i = 0; i < 6; ++i) p.reference.xyz[i] = 1.0;
  for (size_t i = 0; i < 6; ++i) p.render.xyz[i] = 1.0f;
  ErrorMetrics m = computeErrorMetrics(p.render, p.reference, {});
  EXPECT_EQ(m.meanChromaticityError, 0.0);
  EXPECT_EQ(m.deltaE2000Mean, 0.0);
  EXPECT_EQ(m.deltaE2000P99, 0.0);
  EXPECT_EQ(m.deltaEPixels, 2u);
  // Render pixel 1 becomes (2, 1, 1): sums (3, 2, 2) vs (2, 2, 2), so
  // (x, y) = (3/7, 2/7) vs (1/3, 1/3), distance sqrt((2/21)^2 + (1/21)^2).
  p.render.xyz[3] = 2.0f;
  m = computeErrorMetrics(p.render, p.reference, {});
  EXPECT_NEAR(m.meanChromaticityError, std::sqrt(5.0) / 21.0, 1e-15);
  EXPECT_GT(m.deltaE2000Mean, 0.0);
  // Invalid pixels do not count.
  p.reference.valid[1] = 0;
  m = computeErrorMetrics(p.render, p.reference, {});
  EXPECT_EQ(m.meanChromaticityError, 0.0);
}

TEST(ErrorMetrics, DeltaEAgainstD65AtBrightestReferencePixel) {
  // 100 pixels whose reference is the D65 white at Y = 3 (any scale: the
  // white is the brightest reference Y), so each is Lab (100, 0, 0).
  const double Y = 3.0, wx = 0.3127, wy = 0.3290;
  std::vector<double> e(100, 1.0);
  Pair p = makePair(10, 10, e);
  for (size_t i = 0; i < 100; ++i) {
    const double xyz[3] = {Y * wx / wy, Y, Y * (1 - wx - wy) / wy};
    for (int k = 0; k < 3; ++k) {
      p.reference.xyz[3 * i + k] = xyz[k];
      p.render.xyz[3 * i + k] = float(xyz[k]);
    }
  }
  // Render pixels 7 and 42 at 1/8 of it: L* = 42, a* = b* = 0 (up to the
  // float storage), ΔE00 = 58 / S_L with L̄ = 71.
  for (size_t i : {size_t(7), size_t(42)})
    for (int k = 0; k < 3; ++k) p.render.xyz[3 * i + k] = float(p.reference.xyz[3 * i + k] / 8.0);
  const double l50 = 21.0 * 21.0;
  const double d = 58.0 / (1.0 + 0.015 * l50 / std::sqrt(20.0 + l50));
  ErrorMetrics m = computeErrorMetrics(p.render, p.reference, {});
  EXPECT_EQ(m.deltaEPixels, 100u);
  EXPECT_NEAR(m.deltaE2000Mean, 2.0 * d / 100.0, 1e-5);
  // Nearest rank: the 99th smallest of 98 zeros and two d's is d...
  EXPECT_NEAR(m.deltaE2000P99, d, 1e-5);
  // ... and of 99 zeros and one d is 0 (up to float storage).
  for (int k = 0; k < 3; ++k) p.render.xyz[3 * 42 + k] = float(p.reference.xyz[3 * 42 + k]);
  m = computeErrorMetrics(p.render, p.reference, {});
  EXPECT_NEAR(m.deltaE2000P99, 0.0, 1e-4);
  EXPECT_NEAR(m.deltaE2000Mean, d / 100.0, 1e-5);
}

// ------------------------------------------------- variance from the counts

TEST(EstimatedRelativeVariance, OneOverCMinusOneOverN) {
  SpectralHistogram h(2, 2, 3);
  // Pixel 0: no counts; 1: 4 over two bins; 2: 16; 3: all 64 beams.
  h.at(1, 0) = 1, h.at(1, 2) = 3;
  h.at(2, 1) = 16;
  h.at(3, 0) = 30, h.at(3, 1) = 30, h.at(3, 2) = 4;
  const std::vector<double> v = estimatedRelativeVariance(h, 64);
  ASSERT_EQ(v.size(), 4u);
  EXPECT_TRUE(std::isnan(v[0]));
  EXPECT_DOUBLE_EQ(v[1], 1.0 / 4 - 1.0 / 64);
  EXPECT_DOUBLE_EQ(v[2], 1.0 / 16 - 1.0 / 64);
  EXPECT_EQ(v[3], 0.0);
  EXPECT_THROW(estimatedRelativeVariance(h, 0), std::invalid_argument);
  EXPECT_THROW(estimatedRelativeVariance(h, 63), std::invalid_argument);
}

TEST(EstimatedRelativeVariance, ZeroCountPixelsAreSkippedAndCounted) {
  SpectralHistogram h(4, 1, 1);
  const uint64_t beams = 100;
  h.at(0, 0) = 0, h.at(1, 0) = 4, h.at(2, 0) = 16, h.at(3, 0) = 100;
  const double k = 0.5;  // W/m^2 per count
  Pair p = makePair(4, 1, {1.0, 1.0, 1.0, 1.0});
  // Reference: the expected irradiance k N p with p = 0.02, 0.05, 0.2, 1.
  const double pr[4] = {0.02, 0.05, 0.2, 1.0};
  for (int i = 0; i < 4; ++i) {
    p.reference.irradiance[i] = k * double(beams) * pr[i];
    p.render.irradiance[i] = float(k * double(h.at(uint32_t(i), 0)));
  }
  const ErrorMetrics m = computeErrorMetrics(p.render, p.reference, estimatedRelativeVariance(h, beams));
  EXPECT_EQ(m.pixels, 4u);
  EXPECT_EQ(m.pixelsWithoutEstimate, 1u);
  // relative errors: -1, 4/5 - 1, 16/20 - 1, 0.
  EXPECT_NEAR(m.relMse, (1.0 + 0.04 + 0.04 + 0.0) / 4.0, 1e-12);
  const double est = (0.25 - 0.01 + 1.0 / 16 - 0.01 + 0.0) / 3.0;
  EXPECT_NEAR(m.estimatedRelRmse, std::sqrt(est), 1e-12);
  // Honesty over the three estimated pixels only.
  EXPECT_NEAR(m.honesty, std::sqrt((0.04 + 0.04) / 3.0) / std::sqrt(est), 1e-12);
}

// Binomial counts at known p: the count-based estimate must predict the
// actual error. r_i = C_i/(N p_i) - 1 has variance s_i = (1 - p_i)/(N p_i)
// and is nearly normal (N p_i >= 10^4), so
//   honesty^2 = Σ r_i^2 / Σ v_i  with v_i the estimate (≈ s_i),
// and Σ r_i^2 / Σ s_i has mean 1 and standard deviation
// sqrt(2 Σ s_i^2) / Σ s_i (χ² with one degree of freedom per pixel has
// variance 2); honesty, its square root, half that. The plug-in estimate
// 1/C - 1/N overestimates s_i by a relative (1 - p)/(N p) <= 1/(N p_min) to
// first order, lowering honesty by at most half that. Tolerance: 5 sigma
// plus that bias bound.
struct BinomialRun {
  ErrorMetrics metrics;
  double tolerance = 0.0;          // on honesty
  double trueRelRmse = 0.0;        // sqrt(mean s_i)
  double biasTolerance = 0.0;      // on the mean relative error
  std::vector<double> estimate;
  Pair images;
  std::vector<double> eref;
};

template <class PofI>
BinomialRun runBinomial(int w, int hgt, uint64_t beams, PofI pOf, uint64_t seed) {
  const size_t n = size_t(w) * hgt;
  const double k = 2.5e-3;  // W/m^2 per count
  std::mt19937_64 rng(seed);
  SpectralHistogram hist(uint32_t(w), uint32_t(hgt), 3);
  BinomialRun run;
  run.eref.resize(n);
  std::vector<double> s(n);
  double pMin = 1.0;
  for (size_t i = 0; i < n; ++i) {
    const double pi = pOf(i, n);
    pMin = std::min(pMin, pi);
    run.eref[i] = k * double(beams) * pi;
    s[i] = (1.0 - pi) / (double(beams) * pi);
    const uint64_t c = std::binomial_distribution<uint64_t>(beams, pi)(rng);
    // Spread the pixel's count over the bins (the estimate uses the total).
    const uint64_t c0 = std::binomial_distribution<uint64_t>(c, 0.3)(rng);
    const uint64_t c1 = std::binomial_distribution<uint64_t>(c - c0, 0.5)(rng);
    hist.at(uint32_t(i), 0) = c0;
    hist.at(uint32_t(i), 1) = c1;
    hist.at(uint32_t(i), 2) = c - c0 - c1;
  }
  run.images = makePair(w, hgt, run.eref);
  for (size_t i = 0; i < n; ++i) {
    uint64_t c = 0;
    for (uint32_t b = 0; b < 3; ++b) c += hist.at(uint32_t(i), b);
    run.images.render.irradiance[i] = float(k * double(c));
  }
  run.estimate = estimatedRelativeVariance(hist, beams);
  run.metrics = computeErrorMetrics(run.images.render, run.images.reference, run.estimate);
  double sumS = 0.0, sumS2 = 0.0;
  for (double x : s) sumS += x, sumS2 += x * x;
  const double sigma = 0.5 * std::sqrt(2.0 * sumS2) / sumS;
  run.tolerance = 5.0 * sigma + 0.5 / (double(beams) * pMin);
  run.trueRelRmse = std::sqrt(sumS / double(n));
  // The mean of n independent r_i with variances s_i: 5 sigma.
  run.biasTolerance = 5.0 * std::sqrt(sumS) / double(n);
  return run;
}

void expectHonest(const BinomialRun& run, size_t n) {
  const ErrorMetrics& m = run.metrics;
  EXPECT_EQ(m.pixels, n);
  EXPECT_EQ(m.pixelsWithoutEstimate, 0u);
  EXPECT_LT(run.tolerance, 0.03) << "test too weak to mean anything";
  EXPECT_NEAR(m.honesty, 1.0, run.tolerance);
  // The estimate itself is close to the true mean variance (each v_i has
  // relative error ~ 1/sqrt(N p_i) <= 1%, averaged over many pixels).
  EXPECT_NEAR(m.estimatedRelRmse / run.trueRelRmse, 1.0, 0.01);
  EXPECT_NEAR(m.bias, 0.0, run.biasTolerance);
}

TEST(EstimatedRelativeVariance, HonestyOfBinomialCountsOverManyPIsOne) {
  // p log-spaced over [1e-3, 0.5] across 10^5 pixels, N = 10^7: N p >= 10^4.
  // (The small-p pixels dominate Σ s_i: about a third of the pixels count,
  // sigma ~ 0.004.)
  const int w = 400, h = 250;
  const auto pOf = [](size_t i, size_t n) { return 1e-3 * std::pow(500.0, double(i) / double(n - 1)); };
  const BinomialRun run = runBinomial(w, h, 10'000'000, pOf, 20240611);
  expectHonest(run, size_t(w) * h);
  std::printf("honesty %.5f (tolerance %.5f), estimated relRMSE %.6g, true %.6g\n", run.metrics.honesty,
              run.tolerance, run.metrics.estimatedRelRmse, run.trueRelRmse);

  // A render with twice the noise its counts claim is caught: honesty ~2.
  Pair noisy = run.images;
  for (size_t i = 0; i < run.eref.size(); ++i)
    noisy.render.irradiance[i] =
        float(run.eref[i] + 2.0 * (double(run.images.render.irradiance[i]) - run.eref[i]));
  const ErrorMetrics mn = computeErrorMetrics(noisy.render, noisy.reference, run.estimate);
  EXPECT_NEAR(mn.honesty / run.metrics.honesty, 2.0, 1e-3);
}

TEST(EstimatedRelativeVariance, HonestyAtLargePNeedsTheOneOverNTerm) {
  // p = 0.6 everywhere: the true relative variance is 0.4/(N p); without the
  // -1/N term the estimate would be 1/(N p) and honesty sqrt(0.4) ≈ 0.63.
  // sigma = 0.5 sqrt(2/n) ≈ 0.0022.
  const int w = 400, h = 250;
  const BinomialRun run = runBinomial(w, h, 1'000'000, [](size_t, size_t) { return 0.6; }, 7);
  expectHonest(run, size_t(w) * h);
  std::printf("honesty %.5f (tolerance %.5f)\n", run.metrics.honesty, run.tolerance);
}

// ------------------------------------------------------------ figure of merit

TEST(FigureOfMerit, InverseOfRelMseTimesSeconds) {
  EXPECT_DOUBLE_EQ(figureOfMerit(0.01, 2.0), 50.0);
  EXPECT_EQ(figureOfMerit(0.0, 2.0), std::numeric_limits<double>::infinity());
  EXPECT_THROW(figureOfMerit(-1.0, 2.0), std::invalid_argument);
  EXPECT_THROW(figureOfMerit(0.01, 0.0), std::invalid_argument);
  EXPECT_THROW(figureOfMerit(std::nan(""), 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace spectrace
