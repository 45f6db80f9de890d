#include "spectrum/wavelength_sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <fmt/format.h>

namespace spectrace {

std::vector<uint64_t> quantizeCdf(std::span<const double> weights) {
  if (weights.empty()) throw SpdError("a sampling table needs at least one entry");
  long double total = 0.0L;
  for (size_t j = 0; j < weights.size(); ++j) {
    if (!std::isfinite(weights[j]) || weights[j] < 0.0)
      throw SpdError(fmt::format("sampling weight {} is {} (must be finite and >= 0)", j, weights[j]));
    total += weights[j];
  }
  if (!(total > 0.0L)) throw SpdError("sampling weights are all zero: nothing can be drawn");
  if (!(weights.back() > 0.0)) throw SpdError("internal: trailing zero weight in a sampling table");

  // 80-bit long double keeps 64 significant bits, so floor() below is the
  // exact share rounded down for all practical weights.
  using u128 = unsigned __int128;
  const long double two64 = std::ldexp(1.0L, 64);
  const u128 full = u128(1) << 64;
  std::vector<u128> widths(weights.size(), 0);
  u128 sum = 0;
  size_t largest = 0;
  for (size_t j = 0; j < weights.size(); ++j) {
    if (weights[j] > 0.0) {
      const long double scaled = std::floor(static_cast<long double>(weights[j]) / total * two64);
      widths[j] = std::max<u128>(1, scaled >= two64 ? full : u128(scaled));
    }
    sum += widths[j];
    if (widths[j] > widths[largest]) largest = j;
  }
  // The remainder (a few units against >= 2^64 / n) goes to the largest.
  if (sum > full) {
    widths[largest] -= sum - full;
  } else {
    widths[largest] += full - sum;
  }
  std::vector<uint64_t> lows(weights.size());
  u128 running = 0;
  for (size_t j = 0; j < weights.size(); ++j) {
    lows[j] = uint64_t(running);
    running += widths[j];
  }
  return lows;
}

double cdfProbability(std::span<const uint64_t> lows, size_t j) {
  const unsigned __int128 high = j + 1 < lows.size() ? lows[j + 1] : (unsigned __int128)1 << 64;
  return std::ldexp(static_cast<double>(high - lows[j]), -64);
}

SpectralTable buildSpectralTable(const Spd& spd) {
  SpectralTable table;
  if (spd.lambdaNm.empty()) throw SpdError("the spectrum has no power inside the spectrum range");
  if (spd.isLine()) {
    if (!(spd.value[0] > 0.0)) throw SpdError("the spectral line has no power");
    table.intervals.push_back({0, float(spd.lambdaNm[0]), 0.0f, 0.0f, 0.0f});
    table.integral = spd.value[0];
    return table;
  }
  // Weights are formed from values scaled by 1/max, so neither huge values
  // (1e306 over a wide range) overflow nor subnormal ones underflow to a
  // zero weight; only the shares matter.
  double peak = 0.0;
  for (double v : spd.value) peak = std::max(peak, v);
  if (!(peak > 0.0) || !std::isfinite(peak)) throw SpdError("the spectrum has no finite power inside the spectrum range");
  const double scale = 1.0 / peak;
  auto value = [&](size_t j) { return spd.value[j] * scale; };
  // An interval of positive power keeps a positive weight even if it
  // underflows (a subnormal next to a large peak): it must stay drawable.
  auto intervalWeight = [&](size_t j) {
    if (!(spd.value[j] > 0.0 || spd.value[j + 1] > 0.0)) return 0.0;
    const double w = 0.5 * (value(j) + value(j + 1)) * (spd.lambdaNm[j + 1] - spd.lambdaNm[j]);
    return std::max(w, std::numeric_limits<double>::denorm_min());
  };
  std::vector<double> weights;
  size_t first = spd.lambdaNm.size(), last = 0;
  for (size_t j = 0; j + 1 < spd.lambdaNm.size(); ++j) {
    const double w = intervalWeight(j);
    if (w > 0.0) {
      first = std::min(first, j);
      last = j;
    }
  }
  if (first > last) throw SpdError("the spectrum has no power inside the spectrum range");
  for (size_t j = first; j <= last; ++j) {
    const double f0 = value(j), f1 = value(j + 1);
    const double width = spd.lambdaNm[j + 1] - spd.lambdaNm[j];
    const double w = intervalWeight(j);
    weights.push_back(w);
    table.integral += w * peak;
    const double slope = f0 + f1 > 0.0 ? (f1 - f0) / (f1 + f0) : 0.0;
    table.intervals.push_back({0, float(spd.lambdaNm[j]), float(width), float(slope), 0.0f});
  }
  const auto lows = quantizeCdf(weights);
  for (size_t j = 0; j < lows.size(); ++j) table.intervals[j].cdfLow = lows[j];
  return table;
}

namespace {
// P(t <= x) within one interval for the linear density of `slope`.
double linearCdf(double slope, double x) {
  x = std::clamp(x, 0.0, 1.0);
  const double a = 1.0 - slope, b = 1.0 + slope;
  return (a * x + 0.5 * (b - a) * x * x) / (0.5 * (a + b));
}
}  // namespace

double tableProbability(const SpectralTable& table, double aNm, double bNm) {
  const auto& iv = table.intervals;
  std::vector<uint64_t> lows(iv.size());
  for (size_t j = 0; j < iv.size(); ++j) lows[j] = iv[j].cdfLow;
  double p = 0.0;
  for (size_t j = 0; j < iv.size(); ++j) {
    const double pj = cdfProbability(lows, j);
    const double l0 = iv[j].lambda0, w = iv[j].width;
    if (w == 0.0) {
      if (l0 >= aNm && l0 < bNm) p += pj;
      continue;
    }
    const double lo = linearCdf(iv[j].slope, (aNm - l0) / w);
    const double hi = linearCdf(iv[j].slope, (bNm - l0) / w);
    p += pj * (hi - lo);
  }
  return p;
}

}  // namespace spectrace
