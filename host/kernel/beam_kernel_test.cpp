// Tests of the shared beam code as the CPU runs it: wavelength sampling
// (chi-square against the SPD), exact integer CDFs, the trig polynomials and
// the direction samplers. The GPU runs the same text; gpu tests compare the
// two beam for beam.
#include "kernel/beam_kernel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "rng/philox.h"
#include "spectrum/spd.h"
#include "spectrum/alias_table.h"
#include "spectrum/wavelength_sampler.h"
#include "support/statistics.h"

namespace spectrace {
namespace {

using device::BeamKernel;

// A kernel over one light's spectral table; only the spectral part is used.
struct SamplerFixture {
  SpectralTable table;
  AliasTable alias;
  device::TraceConstants constants{};
  std::vector<device::LightRecord> lights{1};
  mutable BeamKernel kernel;  // the shared functions are not const-qualified
  explicit SamplerFixture(const Spd& spd)
      : table(buildSpectralTable(spd)), alias(aliasOf(table)), kernel(constants, lights, table.intervals, alias.columns) {
    lights[0].spectralCount = uint32_t(table.intervals.size());
    lights[0].spectralAliasBits = alias.bits;
  }
  static AliasTable aliasOf(const SpectralTable& table) {
    std::vector<uint64_t> lows;
    for (const auto& iv : table.intervals) lows.push_back(iv.cdfLow);
    return buildAliasTable(lows);
  }
  float draw(uint64_t seed, uint64_t i) const {
    const auto w = philoxWords(seed, i, device::kRngBlockSpectral);
    return kernel.drawWavelength(lights[0], joinWords(w[0], w[1]), uniformFloat(w[2]));
  }
};

// Draws n wavelengths and chi-square tests them against the SPD's own
// integral over cells of `cellNm` between lo and hi. p > 0.01 (a fixed seed,
// so the test is deterministic; a correct sampler fails it 1% of seeds).
void expectMatchesSpd(const Spd& spd, double lo, double hi, double cellNm, uint64_t n, uint64_t seed) {
  SamplerFixture f(spd);
  const int cells = int(std::round((hi - lo) / cellNm));
  std::vector<uint64_t> observed(cells, 0);
  uint64_t outside = 0;
  for (uint64_t i = 0; i < n; ++i) {
    const double lambda = f.draw(seed, i);
    const int c = int(std::floor((lambda - lo) / cellNm));
    if (c < 0 || c >= cells) ++outside; else ++observed[c];
  }
  EXPECT_EQ(outside, 0u) << "samples outside the SPD's support";
  const double total = spd.integral();
  std::vector<double> probability(cells);
  for (int c = 0; c < cells; ++c) {
    const Spd part = spd.clipped(lo + c * cellNm, lo + (c + 1) * cellNm);
    probability[c] = part.lambdaNm.empty() ? 0.0 : part.integral() / total;
  }
  const auto result = testing::chiSquareTest(observed, probability);
  EXPECT_FALSE(result.impossibleHit) << "a sample fell where the SPD is zero";
  EXPECT_GT(result.pValue, 0.01) << "chi2 = " << result.statistic << " dof = " << result.degreesOfFreedom;
}

TEST(WavelengthSampler, ChiSquareD65) {
  const Spd d65 = cieIlluminant("D65")->clipped(360, 830);
  expectMatchesSpd(d65, 360, 830, 1.0, 2'000'000, 1);
}

TEST(WavelengthSampler, ChiSquareF11) {
  const Spd f11 = cieIlluminant("F11")->clipped(360, 830);
  expectMatchesSpd(f11, 380, 780, 1.0, 2'000'000, 2);
}

// A camera path's k wavelengths (shaders/wavelengths.h): with k = 1 the
// alias draw itself; with k = 4 each is a draw from the table (chi-square,
// p > 0.01 at a fixed seed, as a lone draw's), and wavelength j lies in the
// interval that holds u + j 2^64 / 4 by the table's integer CDF (equal
// steps of the CDF: stratified).
TEST(WavelengthSampler, PathWavelengthsAreEachDrawnFromTheTableAtEqualCdfSteps) {
  const Spd f11 = cieIlluminant("F11")->clipped(360, 830);
  SamplerFixture f(f11);
  const device::LightRecord& light = f.lights[0];
  for (uint64_t i = 0; i < 1000; ++i) {
    const auto w = philoxWords(5, i, device::kRngBlockSpectral);
    const auto one = f.kernel.drawPathWavelengths(light, joinWords(w[0], w[1]), uniformFloat(w[2]), 1);
    ASSERT_EQ(one.lambda[0], f.draw(5, i));
    ASSERT_EQ(one.share[0], 1.0f);
    ASSERT_EQ(one.share[1], 0.0f);
  }
  constexpr uint32_t k = 4;
  const double lo = 380, hi = 780, cellNm = 1.0;
  const int cells = int(std::round((hi - lo) / cellNm));
  std::vector<std::vector<uint64_t>> observed(k, std::vector<uint64_t>(cells, 0));
  const uint64_t n = 1'000'000;
  const auto& iv = f.table.intervals;
  for (uint64_t i = 0; i < n; ++i) {
    const auto w = philoxWords(6, i, device::kRngBlockSpectral);
    const uint64_t u = joinWords(w[0], w[1]);
    const auto path = f.kernel.drawPathWavelengths(light, u, uniformFloat(w[2]), k);
    for (uint32_t j = 0; j < k; ++j) {
      ASSERT_EQ(path.share[j], 0.25f);
      const int c = int(std::floor((path.lambda[j] - lo) / cellNm));
      ASSERT_TRUE(c >= 0 && c < cells) << path.lambda[j];
      ++observed[j][c];
      if (i < 10'000) {
        const uint64_t rotated = u + uint64_t(j) * (uint64_t(1) << 62);
        const uint32_t at = f.kernel.intervalOfUniform(light, rotated);
        ASSERT_LE(iv[at].cdfLow, rotated);
        if (at + 1 < iv.size()) {
          ASSERT_LT(rotated, iv[at + 1].cdfLow);
        }
        ASSERT_GE(path.lambda[j], iv[at].lambda0);
        ASSERT_LE(path.lambda[j], iv[at].lambda0 + iv[at].width);
      }
    }
  }
  const double total = f11.integral();
  std::vector<double> probability(cells);
  for (int c = 0; c < cells; ++c) {
    const Spd part = f11.clipped(lo + c * cellNm, lo + (c + 1) * cellNm);
    probability[c] = part.lambdaNm.empty() ? 0.0 : part.integral() / total;
  }
  for (uint32_t j = 0; j < k; ++j) {
    const auto result = testing::chiSquareTest(observed[j], probability);
    EXPECT_FALSE(result.impossibleHit) << "wavelength " << j;
    EXPECT_GT(result.pValue, 0.01) << "wavelength " << j << ": chi2 = " << result.statistic;
  }
}

TEST(WavelengthSampler, ChiSquareGaussianLaserLine) {
  const Spd line = makeLineSpd(532.0, 1.0);
  expectMatchesSpd(line, 529.0, 535.0, 0.05, 1'000'000, 3);
}

TEST(WavelengthSampler, DiracLineIsExact) {
  SamplerFixture f(makeLineSpd(532.0));
  for (uint64_t i = 0; i < 10000; ++i) ASSERT_EQ(f.draw(4, i), 532.0f);
}

TEST(WavelengthSampler, ChiSquareCsvWithZeroGapsAndNeverInsideThem) {
  const auto dir = std::filesystem::temp_directory_path() / ("spectrace_sampler_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto csv = dir / "gaps.csv";
  {
    std::ofstream out(csv);
    out << "wavelength_nm,value\n400,0\n410,1\n430,1\n440,0\n470,0\n475,0\n480,3\n481,0\n500,0\n"
           "520,0.5\n600,0.5\n610,0\n700,0\n";
  }
  const Spd spd = loadCsvSpd(csv);
  std::filesystem::remove_all(dir);
  expectMatchesSpd(spd, 400, 700, 0.5, 2'000'000, 5);
  SamplerFixture f(spd);
  for (uint64_t i = 0; i < 1'000'000; ++i) {
    const float l = f.draw(6, i);
    // Zero-power intervals (440-480, 481-520 and 610-700 are zero except at
    // their positive ends) are never drawn.
    ASSERT_FALSE(l > 440.0f && l < 475.0f) << l;
    ASSERT_FALSE(l > 481.0f && l < 500.0f) << l;
    ASSERT_FALSE(l > 610.0f) << l;
  }
}

TEST(IntegerCdf, ZeroWeightsNeverDrawnPositiveAlwaysDrawable) {
  const std::vector<double> weights = {1e-30, 0.0, 0.0, 5.0, 0.0, 1e30, 0.0, 1e-300, 2.0};
  const auto lows = quantizeCdf(weights);
  unsigned __int128 sum = 0;
  for (size_t j = 0; j < weights.size(); ++j) {
    const double p = cdfProbability(lows, j);
    if (weights[j] == 0.0) EXPECT_EQ(p, 0.0) << j;
    else EXPECT_GT(p, 0.0) << j;
    const unsigned __int128 high = j + 1 < lows.size() ? lows[j + 1] : (unsigned __int128)1 << 64;
    sum += high - lows[j];
  }
  // Widths sum to exactly 2^64: every 64-bit uniform selects some entry.
  EXPECT_TRUE(sum == (unsigned __int128)1 << 64);
  // The alias table the kernel draws through gives each entry exactly its
  // width, and its lookup never lands on a zero-width entry, at either end
  // of any column.
  const AliasTable alias = buildAliasTable(lows);
  const auto masses = aliasMasses(alias, alias.columns.size());
  for (size_t j = 0; j < masses.size(); ++j) {
    const unsigned __int128 high = j + 1 < lows.size() ? lows[j + 1] : (unsigned __int128)1 << 64;
    EXPECT_TRUE(masses[j] == (j < lows.size() ? high - lows[j] : 0)) << j;
  }
  std::vector<device::SpectralInterval> intervals(weights.size());
  device::TraceConstants c{};
  std::vector<device::LightRecord> l(1);
  BeamKernel k(c, l, intervals, alias.columns);
  const unsigned __int128 columnWidth = (unsigned __int128)1 << (64 - alias.bits);
  for (uint32_t col = 0; col < alias.columns.size(); ++col)
    for (unsigned __int128 u : {col * columnWidth, (col + 1) * columnWidth - 1})
      EXPECT_GT(weights[k.aliasLookup(0, alias.bits, uint64_t(u))], 0.0) << "column " << col;
}

TEST(IntegerCdf, SharesAreExactToTheWidthRounding) {
  std::vector<double> weights;
  for (int i = 0; i < 1000; ++i) weights.push_back(1.0 + (i % 7) * 0.37 + (i == 500 ? 1e6 : 0.0));
  const auto lows = quantizeCdf(weights);
  double total = 0.0;
  for (double w : weights) total += w;
  for (size_t j = 0; j < weights.size(); ++j) {
    // Rounding down loses < 1 in 2^64 * share (> 4e13 here); the largest
    // entry absorbs at most n units.
    EXPECT_NEAR(cdfProbability(lows, j) / (weights[j] / total), 1.0, 1e-12) << j;
  }
}

TEST(SharedMath, CosSin2PiMatchesLibmToAFewUlps) {
  SamplerFixture f(makeLineSpd(500.0));
  double worst = 0.0;
  for (uint32_t k = 0; k < (1u << 24); k += 97) {
    const float u = float(k) * (1.0f / 16777216.0f);
    const auto cs = f.kernel.cosSin2Pi(u);
    const double angle = 2.0 * M_PI * double(u);
    worst = std::max({worst, std::abs(cs.x - std::cos(angle)), std::abs(cs.y - std::sin(angle))});
  }
  // Float rounding of a Horner polynomial on [0, pi/4]: a few ulps of 1.
  EXPECT_LT(worst, 4e-7);
}

TEST(SharedMath, PolyAtan2MatchesLibmToAFewUlps) {
  SamplerFixture f(makeLineSpd(500.0));
  double worst = 0.0;
  // Every direction around the circle, at radii from 1e-20 to 1e20, plus the
  // axes and the diagonals exactly.
  for (int k = 0; k < 200000; ++k) {
    const double angle = 2.0 * M_PI * (k / 200000.0) - M_PI;
    const double radius = std::pow(10.0, -20.0 + 40.0 * ((k * 7919) % 200000) / 200000.0);
    const float y = float(radius * std::sin(angle)), x = float(radius * std::cos(angle));
    worst = std::max(worst, std::abs(double(f.kernel.polyAtan2(y, x)) - std::atan2(double(y), double(x))));
  }
  for (float y : {-1.0f, 0.0f, 1.0f})
    for (float x : {-1.0f, 0.0f, 1.0f})
      worst = std::max(worst, std::abs(double(f.kernel.polyAtan2(y, x)) - std::atan2(double(y), double(x))));
  // Float rounding of the reduction and the Horner polynomial, added to pi
  // at most: a few ulps of pi (2.4e-7 each).
  EXPECT_LT(worst, 8e-7);
  EXPECT_EQ(f.kernel.polyAtan2(0.0f, 0.0f), 0.0f);
}

TEST(SharedMath, LinearIntervalSamplerInvertsItsCdfAndStaysInside) {
  SamplerFixture f(makeLineSpd(500.0));
  for (float slope : {-1.0f, -0.999f, -0.3f, 0.0f, 0.5f, 1.0f}) {
    for (float u : {0.0f, 1e-7f, 0.25f, 0.5f, 0.9f, 1.0f - 1.0f / 16777216.0f}) {
      const float t = f.kernel.sampleLinearInInterval(u, slope);
      ASSERT_TRUE(std::isfinite(t));
      ASSERT_GE(t, 0.0f);
      ASSERT_LE(t, 1.0f);
      const double a = 1.0 - slope, b = 1.0 + slope;
      const double cdf = (a * t + 0.5 * (b - a) * double(t) * t) / (0.5 * (a + b));
      EXPECT_NEAR(cdf, u, 2e-6) << "slope " << slope << " u " << u;
    }
  }
}

TEST(SharedMath, DirectionSamplersAreUnitVectors) {
  SamplerFixture f(makeLineSpd(500.0));
  for (uint64_t i = 0; i < 100000; ++i) {
    const auto w = philoxWords(9, i, 0);
    const float u = uniformFloat(w[0]), v = uniformFloat(w[1]);
    for (auto d : {f.kernel.sampleSphere(u, v), f.kernel.sampleCosineHemisphere(u, v), f.kernel.sampleCone(u, v, 0.1f)}) {
      ASSERT_NEAR(glm::length(glm::dvec3(d)), 1.0, 1e-6);
    }
    ASSERT_GE(f.kernel.sampleCosineHemisphere(u, v).z, 0.0f);
    ASSERT_GE(f.kernel.sampleCone(u, v, 0.1f).z, 0.9f - 1e-6f);
  }
}

}  // namespace
}  // namespace spectrace

namespace spectrace {
namespace {

// The range argument of the exact-colour sums (device_shared.h): one hit
// adds less than 2^22 units, so 1e12 hits in one pixel cannot overflow 64
// bits; and the rounding is unbiased to well below a quantum.
TEST(ColourFixedPoint, RangeAndResolutionHoldForBothObservers) {
  SamplerFixture f(makeLineSpd(500.0));
  for (float v : {0.0f, 1e-6f, 0.5f, 1.0f, 1.7826f, 2.02f}) {
    for (float u : {0.0f, 0.5f, 1.0f - 1.0f / 16777216.0f}) {
      const uint64_t fixed = f.kernel.colourFixedPoint(v, u);
      EXPECT_LT(fixed, uint64_t(1) << 22);
      EXPECT_LE(std::abs(double(fixed) - double(v) * device::kColourFixedPointScale), 1.0);
    }
  }
  EXPECT_LT(1e12 * double(uint64_t(1) << 22), std::ldexp(1.0, 64));
  // Averaged over the rounding uniform, the sum is exact to the uniform's
  // resolution (here 2^-16 levels are used, so to 2^-16 of a quantum).
  const float value = 0.123456789f;
  double sum = 0.0;
  constexpr int kSteps = 1 << 16;
  for (int i = 0; i < kSteps; ++i)
    sum += double(f.kernel.colourFixedPoint(value, float(i) / kSteps));
  EXPECT_NEAR(sum / kSteps, double(value) * device::kColourFixedPointScale, 2.0 / kSteps + 1e-3);
}

}  // namespace
}  // namespace spectrace
