// Numerical-stability tests of the wavelength and light samplers: the exact
// probabilities of the integer CDFs (read back from the very tables the
// shader uses) against independently integrated SPD shares, over extreme
// dynamic ranges, narrow lines, huge and irregular tables, zero gaps,
// clipping and every CIE table; why a float32 CDF would not do; the
// endpoints of the closed-form position sampler; and light selection over
// powers spanning 18 decades (exact pmf and a chi-square of the kernel's
// draws). The kernel draws through alias tables built from the integer
// CDFs; each table is checked to give every entry exactly its CDF width.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "kernel/beam_kernel.h"
#include "rng/philox.h"
#include "spectrum/alias_table.h"
#include "spectrum/cie_data.h"
#include "spectrum/spd.h"
#include "spectrum/wavelength_sampler.h"
#include "support/statistics.h"

namespace spectrace {
namespace {

using device::BeamKernel;
using u128 = unsigned __int128;

// The largest float the RNG yields: (2^32 - 1) >> 8 = 2^24 - 1, times 2^-24.
constexpr float kMaxUniform = 1.0f - 1.0f / 16777216.0f;

// ---------------------------------------------------------------------------
// Independent reference: the SPD's intervals, clipped to [lo, hi] by our own
// interpolation, each with its trapezoid power (f0 + f1) / 2 · Δλ in long
// double. Nothing here calls Spd::integral, Spd::clipped or the sampler.
struct RefInterval {
  double lo, hi;
  long double power;
};

std::vector<RefInterval> referenceIntervals(const Spd& spd, double lo, double hi) {
  std::vector<RefInterval> out;
  for (size_t j = 0; j + 1 < spd.lambdaNm.size(); ++j) {
    const long double x0 = spd.lambdaNm[j], x1 = spd.lambdaNm[j + 1];
    const long double f0 = spd.value[j], f1 = spd.value[j + 1];
    const double a = std::max<double>(spd.lambdaNm[j], lo), b = std::min<double>(spd.lambdaNm[j + 1], hi);
    if (!(a < b)) continue;
    const long double fa = f0 + (f1 - f0) * ((a - x0) / (x1 - x0));
    const long double fb = f0 + (f1 - f0) * ((b - x0) / (x1 - x0));
    out.push_back({a, b, 0.5L * (fa + fb) * ((long double)b - (long double)a)});
  }
  return out;
}

u128 highOf(const std::vector<uint64_t>& lows, size_t k);

// The kernel draws entry k of an integer CDF, through the alias table built
// from it, for exactly width_k of the 2^64 uniforms: the table's masses
// equal the widths (so zero widths are never drawn and positive ones always
// can be), and the kernel's aliasLookup follows the rule those masses were
// counted by, at both ends of every column and on both sides of its
// threshold.
AliasTable expectAliasDrawsExactly(const std::vector<uint64_t>& lows, const std::string& label) {
  const AliasTable table = buildAliasTable(lows);
  const auto masses = aliasMasses(table, table.columns.size());
  for (size_t k = 0; k < masses.size(); ++k)  // entries past the CDF's (padding) get nothing
    EXPECT_TRUE(masses[k] == (k < lows.size() ? highOf(lows, k) - lows[k] : 0)) << label << ": entry " << k;
  device::TraceConstants c{};
  std::vector<device::LightRecord> l(1);
  std::vector<device::SpectralInterval> iv(1);
  BeamKernel kernel(c, l, iv, table.columns);
  const u128 capacity = u128(1) << (64 - table.bits);
  for (uint32_t col = 0; col < table.columns.size(); ++col) {
    const auto& column = table.columns[col];
    const u128 primary = std::min(capacity, (u128(column.threshold) + (u128(1) << table.bits) - 1) >> table.bits);
    const u128 base = u128(col) << (64 - table.bits);
    for (u128 r : {u128(0), capacity - 1, primary > 0 ? primary - 1 : u128(0), primary < capacity ? primary : capacity - 1}) {
      const uint32_t expected = r < primary ? col : column.alias;
      EXPECT_EQ(kernel.aliasLookup(0, table.bits, uint64_t(base + r)), expected) << label << ": column " << col;
    }
  }
  return table;
}

std::vector<uint64_t> lowsOf(const SpectralTable& table) {
  std::vector<uint64_t> lows(table.intervals.size());
  for (size_t k = 0; k < lows.size(); ++k) lows[k] = table.intervals[k].cdfLow;
  return lows;
}

// Exclusive upper end of choice k (2^64 after the last).
u128 highOf(const std::vector<uint64_t>& lows, size_t k) {
  return k + 1 < lows.size() ? u128(lows[k + 1]) : u128(1) << 64;
}

struct ExactnessStats {
  double worstRelative = 0.0;   // over intervals with share >= 1e-12
  double smallestChecked = 1.0; // smallest share among those
  size_t checked = 0, tinyPositive = 0, zero = 0;
};

// Relative error allowed on a share >= 1e-12: the integer width is the share
// times 2^64 rounded down, so it is off by < 1 unit in >= 1.8e7 units
// (5.4e-8); the double weights carry ~1e-16. 1e-6 leaves ample margin while
// still catching any float32 step (2^-24 = 6e-8 per op accumulates well past
// it over a cumulative sum) or a lost interval.
constexpr double kShareTolerance = 1e-6;
constexpr double kCheckedShare = 1e-12;

// The tighter bound the integer CDF actually guarantees: rounding the share
// down to whole units of 2^-64 (plus one unit for the long double quotient
// before floor) costs < 2 / (share · 2^64) relative; the largest entry also
// absorbs the remainder of all n roundings (< n units more). 1e-12 covers
// the double weights and clipping interpolation (a few 1e-16, amplified at
// most ~1e3 by cancellation at a cut). A per-entry float32 share (2^-24 ≈
// 6e-8 relative) fails it.
double quantisationBound(double share, size_t absorbedUnits = 0) {
  return (2.0 + double(absorbedUnits)) / (share * 0x1p64) + 1e-12;
}

// Index of the entry that absorbs the remainder (the first widest).
size_t widestEntry(const std::vector<uint64_t>& lows) {
  size_t widest = 0;
  for (size_t k = 1; k < lows.size(); ++k)
    if (highOf(lows, k) - lows[k] > highOf(lows, widest) - lows[widest]) widest = k;
  return widest;
}

// Builds the sampler's table from `spd` (clipped to [lo, hi] first when
// `clip`), reads back each interval's exact probability and compares it with
// the reference share relative to the in-range power.
ExactnessStats expectSamplerExact(const Spd& spd, const std::string& label, bool clip = false, double lo = 360.0,
                                  double hi = 830.0) {
  ExactnessStats stats;
  const Spd sampled = clip ? spd.clipped(lo, hi) : spd;
  const SpectralTable table = buildSpectralTable(sampled);
  const auto ref = referenceIntervals(spd, clip ? lo : -INFINITY, clip ? hi : INFINITY);
  long double total = 0.0L;
  for (const auto& r : ref) total += r.power;
  EXPECT_GT(total, 0.0L) << label;

  // Map table intervals back to the SPD's by lambda0: the table is the
  // positive-power span [first, last] of the SPD's intervals.
  size_t first = 0, last = ref.size();
  while (first < ref.size() && !(ref[first].power > 0.0L)) ++first;
  while (last > first && !(ref[last - 1].power > 0.0L)) --last;
  const auto& iv = table.intervals;
  EXPECT_EQ(iv.size(), last - first) << label << ": table trimmed to the wrong span";
  if (iv.size() != last - first) return stats;

  const auto lows = lowsOf(table);
  const size_t widest = widestEntry(lows);
  EXPECT_EQ(lows[0], 0u) << label;
  u128 sum = 0;
  for (size_t k = 0; k < iv.size(); ++k) {
    const RefInterval& r = ref[first + k];
    EXPECT_EQ(iv[k].lambda0, float(r.lo)) << label << ": interval " << k << " maps to another SPD interval";
    // The width is the double difference rounded to float: within 1 float ulp of the reference width.
    EXPECT_NEAR(iv[k].width, r.hi - r.lo, std::max(1e-7 * (r.hi - r.lo), 1e-30)) << label << " interval " << k;

    const u128 width = highOf(lows, k) - lows[k];
    sum += width;
    const double p = cdfProbability(lows, k);
    const double share = double(r.power / total);
    if (r.power == 0.0L) {
      ++stats.zero;
      EXPECT_EQ(p, 0.0) << label << ": zero-power interval at " << r.lo << " nm is drawable";
      continue;
    }
    EXPECT_GT(p, 0.0) << label << ": positive-power interval at " << r.lo << " nm (share " << share
                      << ") can never be drawn";
    if (share < kCheckedShare) {
      ++stats.tinyPositive;
      continue;
    }
    const double rel = std::abs(p / share - 1.0);
    ++stats.checked;
    stats.smallestChecked = std::min(stats.smallestChecked, share);
    stats.worstRelative = std::max(stats.worstRelative, rel);
    EXPECT_LE(rel, kShareTolerance) << label << ": interval at " << r.lo << " nm, share " << share << ", p " << p;
    EXPECT_LE(rel, quantisationBound(share, k == widest ? iv.size() : 0))
        << label << ": interval at " << r.lo << " nm, share " << share;
  }
  // Widths partition 2^64 exactly: every 64-bit uniform selects an interval.
  EXPECT_TRUE(sum == u128(1) << 64) << label;

  // The kernel draws exactly these widths.
  expectAliasDrawsExactly(lows, label);
  std::printf("[ numerics ] %-28s %7zu intervals: %zu checked (share >= %.3g), worst rel. error %.3g; "
              "%zu tiny > 0, %zu zero\n",
              label.c_str(), iv.size(), stats.checked, stats.smallestChecked, stats.worstRelative,
              stats.tinyPositive, stats.zero);
  return stats;
}

Spd ybarSpd() {
  const CsvTable& t = cie1931Table();
  return makeTabulatedSpd(t.lambdaNm, t.data[csvColumnIndex(t, "ybar")]);
}

// ---------------------------------------------------------------------------
// 1. Sampler exactness.

TEST(SamplerExactness, ValuesFrom1eMinus30To1e30InOneTable) {
  // (i) a staircase of every decade from 1e-30 to 1e30 on a 1 nm grid;
  // (ii) 500 nodes with random magnitudes 10^U(-30, 30) and random spacing.
  std::vector<double> lambda, value;
  for (int e = -30; e <= 30; ++e) {
    lambda.push_back(400.0 + (e + 30));
    value.push_back(std::pow(10.0, e));
  }
  const auto s1 = expectSamplerExact(makeTabulatedSpd(lambda, value), "decades 1e-30..1e30");
  EXPECT_GT(s1.tinyPositive, 30u);  // the test really has shares below 1e-12 to keep positive

  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> exponent(-30.0, 30.0), gap(0.01, 2.0);
  lambda.clear();
  value.clear();
  double l = 360.0;
  for (int i = 0; i < 500; ++i) {
    lambda.push_back(l);
    value.push_back(std::pow(10.0, exponent(rng)));
    l += gap(rng);
  }
  const auto s2 = expectSamplerExact(makeTabulatedSpd(lambda, value), "random 10^U(-30,30)");
  EXPECT_GT(s2.checked, 5u);
}

TEST(SamplerExactness, NarrowLineInside1nmTable) {
  // A 0.01 nm wide triangle (549.99, 550, 550.01) with a peak of 1e9 over a
  // flat 1 nm table of 1: the line carries ~98% of the power and each of the
  // 470 broad intervals ~1e-4 (and the 549->549.99 sliver too).
  for (double peak : {1e3, 1e9, 1e15}) {
    std::vector<double> lambda, value;
    for (int n = 360; n <= 830; ++n) {
      if (n == 550) {
        lambda.insert(lambda.end(), {549.99, 550.0, 550.01});
        value.insert(value.end(), {1.0, peak, 1.0});
        continue;
      }
      lambda.push_back(n);
      value.push_back(1.0);
    }
    const auto s = expectSamplerExact(makeTabulatedSpd(lambda, value), "0.01 nm line, peak " + std::to_string(int(std::log10(peak))) + " dec");
    EXPECT_EQ(s.zero, 0u);
  }
}

TEST(SamplerExactness, HundredThousandPointTable) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> magnitude(-3.0, 3.0);
  std::vector<double> lambda(100'000), value(100'000);
  for (size_t i = 0; i < lambda.size(); ++i) {
    lambda[i] = 360.0 + 470.0 * double(i) / double(lambda.size() - 1);
    value[i] = (1.5 + std::sin(lambda[i] * 0.05)) * std::pow(10.0, magnitude(rng));
  }
  const auto s = expectSamplerExact(makeTabulatedSpd(lambda, value), "100k nodes");
  EXPECT_EQ(s.checked, lambda.size() - 1);
}

TEST(SamplerExactness, LongZeroGaps) {
  // Leading and trailing zeros (trimmed), a 300 nm gap given by two nodes, a
  // gap of 2000 zero nodes, and single positive spikes between them.
  std::vector<double> lambda, value;
  auto add = [&](double l, double v) { lambda.push_back(l); value.push_back(v); };
  for (int i = 0; i < 20; ++i) add(300.0 + i, 0.0);
  add(330.0, 1e-6);
  add(331.0, 0.0);
  add(631.0, 0.0);   // 300 nm gap
  add(632.0, 5.0);
  add(633.0, 0.0);
  for (int i = 1; i <= 2000; ++i) add(633.0 + 0.05 * i, 0.0);  // 100 nm of zero nodes
  add(800.0, 1e-20);
  add(800.5, 0.0);
  add(801.0, 0.0);
  add(802.0, 3.0);
  add(803.0, 3.0);
  for (int i = 1; i <= 50; ++i) add(803.0 + i, 0.0);
  const auto s = expectSamplerExact(makeTabulatedSpd(lambda, value), "zero gaps");
  EXPECT_GT(s.zero, 2000u);
  EXPECT_GE(s.tinyPositive, 1u);  // the 1e-20 spike: share ~2e-21, must still be drawable
}

TEST(SamplerExactness, NonUniformSpacing) {
  // Spacings from 1e-4 nm to 50 nm (log-uniform), values spanning 6 decades.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> logGap(-4.0, std::log10(50.0)), magnitude(-3.0, 3.0);
  std::vector<double> lambda, value;
  double l = 360.0;
  while (l < 830.0) {
    lambda.push_back(l);
    value.push_back(std::pow(10.0, magnitude(rng)));
    l += std::pow(10.0, logGap(rng));
  }
  const auto s = expectSamplerExact(makeTabulatedSpd(lambda, value), "non-uniform spacing");
  EXPECT_GT(s.checked, 50u);
}

TEST(SamplerExactness, SpdsBeyondTheSpectrumRangeAreClipped) {
  // Probabilities are relative to the in-range power (reference clipped by
  // its own interpolation, not Spd::clipped).
  std::vector<double> lambda, value;
  for (double x = 203.0; x <= 1004.0; x += 7.0) {  // cut points 360, 830 fall inside intervals
    lambda.push_back(x);
    value.push_back(1.0 + 0.5 * std::sin(x * 0.03));
  }
  expectSamplerExact(makeTabulatedSpd(lambda, value), "7 nm grid 203..1002", true);
  expectSamplerExact(makeTabulatedSpd({800.0, 815.5, 1200.0}, {1.0, 7.0, 2.0}), "800..1200 (tail cut)", true);
  expectSamplerExact(makeTabulatedSpd({100.0, 361.0, 362.0}, {1e6, 1e6, 1.0}), "100..362 (head cut)", true);
  expectSamplerExact(*cieIlluminant("D65"), "D65 300..830", true);
  expectSamplerExact(makeBlackbodySpd(5800.0, 100.0, 3000.0), "blackbody 5800 K", true);
  expectSamplerExact(makeBlackbodySpd(1000.0, 100.0, 5000.0), "blackbody 1000 K", true);
}

TEST(SamplerExactness, EveryCieIlluminantAndYbar) {
  double worst = 0.0;
  for (const auto& name : cieIlluminantNames())
    worst = std::max(worst, expectSamplerExact(*cieIlluminant(name), "CIE " + name, true).worstRelative);
  const Spd ybar = ybarSpd();
  ASSERT_EQ(ybar.lambdaNm.size(), 471u);  // 360..830 nm: 470 1-nm intervals
  const auto s = expectSamplerExact(ybar, "CIE 1931 ybar");
  EXPECT_EQ(s.checked, 470u);
  std::printf("[ numerics ] worst over all CIE illuminants: %.3g; ybar: %.3g\n", worst, s.worstRelative);
}

// ---------------------------------------------------------------------------
// 2. Why integer CDFs: a naive float32 CDF of ybar over its 471 1 nm bins.

TEST(SamplerExactness, Float32CdfLosesYbarBinsIntegerCdfLosesNone) {
  const CsvTable& t = cie1931Table();
  const std::vector<double>& y = t.data[csvColumnIndex(t, "ybar")];
  ASSERT_EQ(y.size(), 471u);
  long double totalL = 0.0L;
  for (double v : y) totalL += v;
  const double total = double(totalL);

  // What a naive shader-side table would do: float cumulative sum, normalised.
  std::vector<float> cdf(y.size() + 1, 0.0f);
  for (size_t j = 0; j < y.size(); ++j) cdf[j + 1] = cdf[j] + float(y[j]);
  const float norm = cdf.back();
  for (float& c : cdf) c /= norm;
  size_t floatLost = 0, floatBad = 0;
  double floatWorst = 0.0;
  for (size_t j = 0; j < y.size(); ++j) {
    const float p = cdf[j + 1] - cdf[j];
    const double exact = y[j] / total;
    const double rel = std::abs(double(p) / exact - 1.0);
    floatWorst = std::max(floatWorst, rel);
    if (y[j] > 0.0 && p == 0.0f) ++floatLost;
    if (y[j] > 0.0 && (p == 0.0f || rel > kShareTolerance)) ++floatBad;
  }

  const auto lows = quantizeCdf(y);
  size_t intLost = 0, intBad = 0;
  double intWorst = 0.0;
  for (size_t j = 0; j < y.size(); ++j) {
    const double p = cdfProbability(lows, j);
    const double rel = std::abs(p / (y[j] / total) - 1.0);
    intWorst = std::max(intWorst, rel);
    if (y[j] > 0.0 && p == 0.0) ++intLost;
    if (y[j] > 0.0 && (p == 0.0 || rel > kShareTolerance)) ++intBad;
  }
  std::printf("[ numerics ] ybar over 471 bins: float32 CDF loses %zu bins (p == 0), %zu bins off by > 1e-6 "
              "(worst rel. error %.3g); integer CDF loses %zu, %zu off by > 1e-6 (worst %.3g)\n",
              floatLost, floatBad, floatWorst, intLost, intBad, intWorst);
  // The demonstration itself: the float CDF does lose the red tail (ybar
  // there is < half an ulp of the running sum).
  EXPECT_GT(floatLost, 0u);
  ASSERT_EQ(intLost, 0u);
  ASSERT_EQ(intBad, 0u);
  EXPECT_LE(intWorst, kShareTolerance);
  double smallest = 1.0;
  for (double v : y) smallest = std::min(smallest, v / total);
  EXPECT_LE(intWorst, quantisationBound(smallest, y.size()));
}

// ---------------------------------------------------------------------------
// 3. Endpoints of the position sampler and of drawWavelength.

// P(t' <= t) of the linear density within an interval, in double.
double linearCdf(double slope, double t) {
  const double a = 1.0 - slope, b = 1.0 + slope;
  return (a * t + 0.5 * (b - a) * t * t) / (0.5 * (a + b));
}

TEST(SamplerEndpoints, RngUniformRange) {
  EXPECT_EQ(uniformFloat(0u), 0.0f);
  EXPECT_EQ(uniformFloat(0xFFFFFFFFu), kMaxUniform);
  device::TraceConstants c{};
  std::vector<device::LightRecord> l(1);
  std::vector<device::SpectralInterval> iv(1);
  BeamKernel k(c, l, iv, {});
  EXPECT_EQ(k.uniformFromWord(0xFFFFFFFFu), kMaxUniform);
  EXPECT_EQ(k.uniformFromWord(0u), 0.0f);
}

TEST(SamplerEndpoints, LinearSamplerAtBothEndsOfTheUniformRange) {
  device::TraceConstants c{};
  std::vector<device::LightRecord> l(1);
  std::vector<device::SpectralInterval> iv(1);
  BeamKernel k(c, l, iv, {});
  const float slopes[] = {-1.0f, -1.0f + 1e-7f, -0.5f, 0.0f, 0.5f, 1.0f - 1e-7f, 1.0f};
  double worst = 0.0, worstRelT = 0.0;
  for (float slope : slopes) {
    const float t0 = k.sampleLinearInInterval(0.0f, slope);
    EXPECT_EQ(t0, 0.0f) << "slope " << slope;  // u = 0 is the interval's lower end, exactly
    for (float u : {0.0f, 1.0f / 16777216.0f, 2.0f / 16777216.0f, 1e-3f, 0.5f, 1.0f - 2.0f / 16777216.0f, kMaxUniform}) {
      const float t = k.sampleLinearInInterval(u, slope);
      ASSERT_FALSE(std::isnan(t)) << "slope " << slope << " u " << u;
      ASSERT_GE(t, 0.0f) << "slope " << slope << " u " << u;
      ASSERT_LE(t, 1.0f) << "slope " << slope << " u " << u;
      // Inverse of the CDF: t comes out of ~6 float operations of values in
      // [0, 4] (a few ulps of 1, ~2.4e-7 in t) and the density is at most
      // 2, so the CDF at t is within ~5e-7 of u.
      const double err = std::abs(linearCdf(slope, t) - double(u));
      worst = std::max(worst, err);
      EXPECT_LE(err, 1e-6) << "slope " << slope << " u " << u << " t " << t;
      // Relative to the exact inverse (the same cancellation-free closed
      // form in double, a and b being exact in float for these slopes):
      // about 5 roundings of 2^-24 each, with no cancellation to amplify
      // them, even for the smallest nonzero u.
      const double da = 1.0 - double(slope), db = 1.0 + double(slope);
      const double exact = std::min(2.0 * u / (da + std::sqrt((1.0 - u) * da * da + u * db * db)), 1.0);
      if (exact > 0.0) {
        const double relT = std::abs(double(t) / exact - 1.0);
        worstRelT = std::max(worstRelT, relT);
        EXPECT_LE(relT, 5.0 / 16777216.0) << "slope " << slope << " u " << u << " t " << t;
      }
    }
    const float tMax = k.sampleLinearInInterval(kMaxUniform, slope);
    // The largest uniform ends strictly below the upper end only where the
    // density there is not zero-ish; it must at least come within the
    // float-quantised remainder of it: 1 - t <= sqrt(2^-24 / ...) for slope -1.
    EXPECT_GT(tMax, 0.999f) << "slope " << slope;
  }
  std::printf("[ numerics ] sampleLinearInInterval: worst |F(t) - u| %.3g, worst rel. error of t %.3g\n", worst,
              worstRelT);
}

TEST(SamplerEndpoints, DrawWavelengthStaysInsideEachIntervalAndTheSupport) {
  // Intervals of slope 1, -1, 0, ~-1+1e-7 and ~1-1e-7, with zero gaps
  // between them and zeros trimmed at both ends.
  const Spd spd = makeTabulatedSpd(
      {380, 400, 410, 420, 450, 460, 470, 480, 490, 500, 600, 610, 620, 700},
      {0, 0, 1, 0, 0, 1, 5e-8, 1, 1, 0, 0, 2, 0, 0});
  const SpectralTable table = buildSpectralTable(spd);
  const auto& iv = table.intervals;
  const auto lows = lowsOf(table);
  bool sawSteep = false;
  for (const auto& i : iv) sawSteep |= (i.slope > -1.0f && i.slope < -0.9999f) || (i.slope < 1.0f && i.slope > 0.9999f);
  EXPECT_TRUE(sawSteep) << "the table should contain slopes within 1e-6 of +-1";

  device::TraceConstants c{};
  const AliasTable alias = expectAliasDrawsExactly(lows, "steep slopes");
  std::vector<device::LightRecord> l(1);
  l[0].spectralCount = uint32_t(iv.size());
  l[0].spectralAliasBits = alias.bits;
  BeamKernel k(c, l, iv, alias.columns);
  const float supportLo = iv.front().lambda0, supportHi = iv.back().lambda0 + iv.back().width;
  EXPECT_EQ(supportLo, 400.0f);
  EXPECT_EQ(supportHi, 620.0f);

  auto check = [&](uint64_t interval, float u, int64_t expectIndex) {
    const uint32_t found = k.aliasLookup(0, alias.bits, interval);
    const float lambda = k.drawWavelength(l[0], interval, u);
    ASSERT_FALSE(std::isnan(lambda)) << interval << " " << u;
    ASSERT_GE(lambda, supportLo) << interval << " " << u;
    ASSERT_LE(lambda, supportHi) << interval << " " << u;
    ASSERT_GT(cdfProbability(lows, found), 0.0) << "a zero-power interval was drawn";
    if (expectIndex >= 0) {
      ASSERT_EQ(found, uint32_t(expectIndex));
    }
    const float lo = iv[found].lambda0, hi = iv[found].lambda0 + iv[found].width;
    ASSERT_GE(lambda, lo);
    ASSERT_LE(lambda, hi);
    if (u == 0.0f) {
      ASSERT_EQ(lambda, lo);  // the lower end is reached exactly
    }
  };
  for (uint64_t interval : {uint64_t(0), ~uint64_t(0)})
    for (float u : {0.0f, kMaxUniform}) check(interval, u, -1);
  // Both ends of every alias column's 64-bit range, both position ends.
  for (uint32_t col = 0; col < alias.columns.size(); ++col) {
    const u128 base = u128(col) << (64 - alias.bits);
    for (u128 interval : {base, base + (u128(1) << (64 - alias.bits)) - 1})
      for (float u : {0.0f, kMaxUniform}) check(uint64_t(interval), u, -1);
  }
  // And a 0.01 nm line in a 1 nm table: the line's samples stay within it.
  const Spd narrow = makeTabulatedSpd({549.0, 549.99, 550.0, 550.01, 551.0}, {0.0, 0.0, 1e9, 0.0, 0.0});
  const SpectralTable nt = buildSpectralTable(narrow);
  const AliasTable narrowAlias = expectAliasDrawsExactly(lowsOf(nt), "narrow line");
  std::vector<device::LightRecord> nl(1);
  nl[0].spectralCount = uint32_t(nt.intervals.size());
  nl[0].spectralAliasBits = narrowAlias.bits;
  BeamKernel nk(c, nl, nt.intervals, narrowAlias.columns);
  for (uint64_t interval : {uint64_t(0), uint64_t(1) << 63, ~uint64_t(0)})
    for (float u : {0.0f, 0.5f, kMaxUniform}) {
      const float lambda = nk.drawWavelength(nl[0], interval, u);
      ASSERT_GE(lambda, float(549.99));
      ASSERT_LE(lambda, float(550.01));
    }
}

// ---------------------------------------------------------------------------
// 4. Light selection over wildly different powers.

void expectLightSelectionExact(const std::vector<double>& powers, const std::string& label, uint64_t seed) {
  const auto lows = quantizeCdf(powers);
  long double totalL = 0.0L;
  for (double p : powers) totalL += p;
  const size_t n = powers.size();
  const size_t widest = widestEntry(lows);
  std::vector<double> pmf(n);
  double worst = 0.0, smallestChecked = 1.0;
  size_t checked = 0;
  for (size_t j = 0; j < n; ++j) {
    pmf[j] = cdfProbability(lows, j);
    const double share = double(powers[j] / totalL);
    ASSERT_GT(pmf[j], 0.0) << label << ": light " << j << " of power " << powers[j] << " W is never selected";
    if (share < kCheckedShare) continue;
    const double rel = std::abs(pmf[j] / share - 1.0);
    worst = std::max(worst, rel);
    smallestChecked = std::min(smallestChecked, share);
    ++checked;
    EXPECT_LE(rel, kShareTolerance) << label << ": light " << j << " share " << share << " p " << pmf[j];
    EXPECT_LE(rel, quantisationBound(share, j == widest ? n : 0)) << label << ": light " << j << " share " << share;
  }

  // The kernel draws exactly these shares through the alias table.
  const AliasTable alias = expectAliasDrawsExactly(lows, label);
  std::vector<device::LightRecord> lights(n);
  device::TraceConstants c{};
  std::vector<device::SpectralInterval> iv(1);
  BeamKernel k(c, lights, iv, alias.columns);
  // Chi-square of the kernel's draws against the exact pmf; p > 0.01 with a
  // fixed seed (deterministic; a correct sampler fails 1% of seeds).
  constexpr uint64_t kDraws = 2'000'000;
  std::vector<uint64_t> counts(n, 0);
  for (uint64_t i = 0; i < kDraws; ++i) {
    const auto w = philoxWords(seed, i, 0);
    ++counts[k.aliasLookup(0, alias.bits, joinWords(w[0], w[1]))];
  }
  const auto result = testing::chiSquareTest(counts, pmf);
  EXPECT_FALSE(result.impossibleHit) << label;
  EXPECT_GT(result.pValue, 0.01) << label << ": chi2 " << result.statistic << " dof " << result.degreesOfFreedom;
  std::printf("[ numerics ] lights %-22s n=%zu: %zu checked (share >= %.3g), worst rel. error %.3g; "
              "chi2 %.1f dof %d p %.3f\n",
              label.c_str(), n, checked, smallestChecked, worst, result.statistic, result.degreesOfFreedom,
              result.pValue);
}

TEST(LightSelection, FourLightsFrom1eMinus9To1e9Watts) {
  expectLightSelectionExact({1e-9, 1e9, 1.0, 1e-9}, "{1e-9,1e9,1,1e-9} W", 11);
}

TEST(LightSelection, TenThousandLightsOver18Decades) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> exponent(-9.0, 9.0);
  std::vector<double> powers(10'000);
  for (double& p : powers) p = std::pow(10.0, exponent(rng));
  expectLightSelectionExact(powers, "10^U(-9,9) W", 12);
}

}  // namespace
}  // namespace spectrace

namespace spectrace {
namespace {

// Extreme magnitudes that used to overflow or underflow the interval weights
// stay drawable with the right shares (weights are scaled by 1/max).
TEST(SamplerExactness, HugeAndSubnormalValuesStayFiniteAndDrawable) {
  const Spd huge = makeTabulatedSpd({400, 500, 600, 700}, {1e306, 1.7e308, 1e306, 0});
  const SpectralTable hugeTable = buildSpectralTable(huge);
  ASSERT_EQ(hugeTable.intervals.size(), 3u);
  std::vector<uint64_t> lows;
  for (const auto& iv : hugeTable.intervals) lows.push_back(iv.cdfLow);
  // Shares (in units of 1e306, so the reference itself cannot overflow):
  // 171 : 171 : 1 of 343.
  EXPECT_NEAR(cdfProbability(lows, 0) / (171.0 / 343.0), 1.0, 1e-12);
  EXPECT_NEAR(cdfProbability(lows, 2) / (1.0 / 343.0), 1.0, 1e-12);

  const Spd tiny = makeTabulatedSpd({400, 400.5, 401, 500}, {5e-324, 0, 1, 1});
  const SpectralTable tinyTable = buildSpectralTable(tiny);
  ASSERT_EQ(tinyTable.intervals.size(), 3u);
  lows.clear();
  for (const auto& iv : tinyTable.intervals) lows.push_back(iv.cdfLow);
  EXPECT_GT(cdfProbability(lows, 0), 0.0) << "a subnormal but positive interval must stay drawable";
  EXPECT_EQ(cdfProbability(lows, 1) > 0.0, true) << "interval 400.5-401 rises from 0 to 1";
}

}  // namespace
}  // namespace spectrace
