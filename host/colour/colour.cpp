#include "colour/colour.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <glm/matrix.hpp>

#include "spectrum/cie_data.h"
#include "spectrum/wavelength_sampler.h"

namespace spectrace {
namespace {

Observer observerFromTable(std::string_view name, const CsvTable& t) {
  if (t.data.size() != 3) throw SpdError(fmt::format("{}: expected 3 CMF columns, got {}", t.source, t.data.size()));
  Observer o{name, t.lambdaNm, t.data[0], t.data[1], t.data[2]};
  for (const auto* col : {&o.xbar, &o.ybar, &o.zbar})
    for (size_t i = 0; i < col->size(); ++i)
      if (!std::isfinite((*col)[i]) || (*col)[i] < 0.0)
        throw SpdError(fmt::format("{}:{}: bad CMF value {}", t.source, t.line[i], (*col)[i]));
  return o;
}

// Index i of the segment [x[i], x[i+1]] holding l (x.front() <= l <= x.back()).
size_t segmentOf(const std::vector<double>& x, double l) {
  const size_t i = size_t(std::upper_bound(x.begin(), x.end(), l) - x.begin());
  return std::clamp<size_t>(i, 1, x.size() - 1) - 1;
}

double lerpAt(const std::vector<double>& x, const std::vector<double>& y, size_t i, double l) {
  const double t = (l - x[i]) / (x[i + 1] - x[i]);
  return y[i] + t * (y[i + 1] - y[i]);
}

}  // namespace

const Observer& cie1931Observer() {
  static const Observer o = observerFromTable("CIE1931_2", cie1931Table());
  return o;
}

const Observer& cie1964Observer() {
  static const Observer o = observerFromTable("CIE1964_10", cie1964Table());
  return o;
}

const Observer& observerByName(std::string_view name) {
  if (name == "CIE1931_2") return cie1931Observer();
  if (name == "CIE1964_10") return cie1964Observer();
  throw std::invalid_argument(
      fmt::format("unknown observer '{}'; known observers are: CIE1931_2, CIE1964_10", name));
}

std::array<double, 3> cmfAt(const Observer& obs, double l) {
  const auto& x = obs.lambdaNm;
  if (x.size() < 2 || !(l >= x.front()) || l > x.back()) return {0.0, 0.0, 0.0};
  const size_t i = segmentOf(x, l);
  return {lerpAt(x, obs.xbar, i, l), lerpAt(x, obs.ybar, i, l), lerpAt(x, obs.zbar, i, l)};
}

std::vector<std::array<double, 3>> binAveragedCmf(const Observer& obs, double minNm, double maxNm, int bins) {
  if (bins <= 0) throw std::invalid_argument(fmt::format("binAveragedCmf: bins must be positive, got {}", bins));
  if (!std::isfinite(minNm) || !std::isfinite(maxNm) || !(minNm < maxNm))
    throw std::invalid_argument(fmt::format("binAveragedCmf: need min < max, got [{}, {}] nm", minNm, maxNm));
  const auto& x = obs.lambdaNm;
  const std::array<const std::vector<double>*, 3> ys{&obs.xbar, &obs.ybar, &obs.zbar};
  std::vector<std::array<double, 3>> out(size_t(bins), {0.0, 0.0, 0.0});
  const double width = (maxNm - minNm) / double(bins);
  for (int b = 0; b < bins; ++b) {
    const double a = minNm + (maxNm - minNm) * double(b) / double(bins);
    const double e = b == bins - 1 ? maxNm : minNm + (maxNm - minNm) * double(b + 1) / double(bins);
    const double lo = std::max(a, x.front()), hi = std::min(e, x.back());
    if (!(lo < hi)) continue;  // the CMF is zero outside its table
    std::array<double, 3> sum{0.0, 0.0, 0.0};
    // Exact: the CMF is linear on each piece [max(lo, x_i), min(hi, x_{i+1})].
    for (size_t i = segmentOf(x, lo); i + 1 < x.size() && x[i] < hi; ++i) {
      const double u = std::max(lo, x[i]), v = std::min(hi, x[i + 1]);
      if (!(u < v)) continue;
      for (int c = 0; c < 3; ++c)
        sum[c] += 0.5 * (v - u) * (lerpAt(x, *ys[c], i, u) + lerpAt(x, *ys[c], i, v));
    }
    for (int c = 0; c < 3; ++c) out[size_t(b)][c] = sum[c] / width;
  }
  return out;
}

std::vector<std::array<double, 3>> sampledBinCmfMeans(std::span<const device::SpectralInterval> intervals,
                                                      const Observer& obs, double minNm, double maxNm, int bins) {
  std::vector<std::array<double, 3>> weighted(size_t(bins), {0.0, 0.0, 0.0});
  std::vector<double> mass(size_t(bins), 0.0);
  const double binsPerNm = double(bins) / (maxNm - minNm);
  auto binOf = [&](double lambda) {
    return size_t(std::clamp(std::floor((lambda - minNm) * binsPerNm), 0.0, double(bins - 1)));
  };
  std::vector<uint64_t> lows;
  for (const auto& iv : intervals) lows.push_back(iv.cdfLow);
  // Every bin edge and CMF node, sorted once.
  std::vector<double> edges(obs.lambdaNm.begin(), obs.lambdaNm.end());
  for (int e = 1; e < bins; ++e) edges.push_back(minNm + double(e) / binsPerNm);
  std::sort(edges.begin(), edges.end());
  for (size_t j = 0; j < intervals.size(); ++j) {
    const auto& iv = intervals[j];
    const double p = cdfProbability(lows, j);
    const double lambda0 = iv.lambda0, width = iv.width, slope = iv.slope;
    if (!(width > 0.0)) {  // a line
      const size_t b = binOf(lambda0);
      const auto c = cmfAt(obs, lambda0);
      mass[b] += p;
      for (int k = 0; k < 3; ++k) weighted[b][k] += p * c[k];
      continue;
    }
    // Pieces between the interval's ends and the bin edges and CMF nodes
    // inside it: on each the density and the CMF are linear, so Simpson's
    // rule is exact.
    std::vector<double> cuts{lambda0};
    for (auto it = std::upper_bound(edges.begin(), edges.end(), lambda0); it != edges.end() && *it < lambda0 + width; ++it)
      cuts.push_back(*it);
    cuts.push_back(lambda0 + width);
    auto density = [&](double lambda) { return p / width * (1.0 - slope + 2.0 * slope * (lambda - lambda0) / width); };
    for (size_t i = 0; i + 1 < cuts.size(); ++i) {
      const double u = cuts[i], v = cuts[i + 1];  // all inside [lambda0, lambda0 + width]
      if (!(u < v)) continue;
      const double m = 0.5 * (u + v);
      const size_t b = binOf(m);
      const double du = density(u), dm = density(m), dv = density(v);
      const auto cu = cmfAt(obs, u), cm = cmfAt(obs, m), cv = cmfAt(obs, v);
      mass[b] += (v - u) / 6.0 * (du + 4.0 * dm + dv);
      for (int k = 0; k < 3; ++k) weighted[b][k] += (v - u) / 6.0 * (du * cu[k] + 4.0 * dm * cm[k] + dv * cv[k]);
    }
  }
  std::vector<std::array<double, 3>> means = binAveragedCmf(obs, minNm, maxNm, bins);
  for (size_t b = 0; b < size_t(bins); ++b)
    if (mass[b] > 0.0)
      for (int k = 0; k < 3; ++k) means[b][k] = weighted[b][k] / mass[b];
  return means;
}

std::array<double, 3> spdToXyz(const Spd& spd, const Observer& obs) {
  if (spd.lambdaNm.empty()) return {0.0, 0.0, 0.0};
  if (spd.isLine()) {
    const auto c = cmfAt(obs, spd.lambdaNm[0]);
    return {spd.value[0] * c[0], spd.value[0] * c[1], spd.value[0] * c[2]};
  }
  const auto& sx = spd.lambdaNm;
  const auto& cx = obs.lambdaNm;
  const double lo = std::max(sx.front(), cx.front()), hi = std::min(sx.back(), cx.back());
  if (!(lo < hi)) return {0.0, 0.0, 0.0};
  // Merged nodes over the overlap; between consecutive ones both functions
  // are linear, so the product is quadratic and Simpson-like weights are
  // exact: ∫ f g = h/6 (2 f0 g0 + f0 g1 + f1 g0 + 2 f1 g1).
  std::vector<double> nodes;
  nodes.reserve(sx.size() + cx.size() + 2);
  nodes.push_back(lo);
  for (double l : sx)
    if (l > lo && l < hi) nodes.push_back(l);
  for (double l : cx)
    if (l > lo && l < hi) nodes.push_back(l);
  nodes.push_back(hi);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());

  std::array<double, 3> xyz{0.0, 0.0, 0.0};
  double f0 = spd.evaluate(nodes[0]);
  std::array<double, 3> g0 = cmfAt(obs, nodes[0]);
  for (size_t k = 1; k < nodes.size(); ++k) {
    const double h = nodes[k] - nodes[k - 1];
    const double f1 = spd.evaluate(nodes[k]);
    const std::array<double, 3> g1 = cmfAt(obs, nodes[k]);
    for (int c = 0; c < 3; ++c)
      xyz[c] += h / 6.0 * (2.0 * f0 * g0[c] + f0 * g1[c] + f1 * g0[c] + 2.0 * f1 * g1[c]);
    f0 = f1;
    g0 = g1;
  }
  return xyz;
}

std::array<double, 3> spdToXyzSummed(const Spd& spd, const Observer& obs) {
  // A line puts all its power in one 1 nm step: same as spdToXyz.
  if (spd.isLine()) return spdToXyz(spd, obs);
  std::array<double, 3> xyz{0.0, 0.0, 0.0};
  for (size_t i = 0; i < obs.lambdaNm.size(); ++i) {
    const double s = spd.evaluate(obs.lambdaNm[i]);
    xyz[0] += s * obs.xbar[i];
    xyz[1] += s * obs.ybar[i];
    xyz[2] += s * obs.zbar[i];
  }
  return xyz;
}

std::array<double, 2> chromaticity(const std::array<double, 3>& xyz) {
  const double sum = xyz[0] + xyz[1] + xyz[2];
  if (sum == 0.0) return {0.0, 0.0};  // black has no chromaticity
  return {xyz[0] / sum, xyz[1] / sum};
}

glm::dmat3 xyzToRgbFromPrimaries(std::array<double, 2> r, std::array<double, 2> g, std::array<double, 2> b,
                                 std::array<double, 2> white) {
  const auto toXyz = [](std::array<double, 2> xy, const char* what) {
    if (!std::isfinite(xy[0]) || !std::isfinite(xy[1]) || !(xy[1] > 0.0))
      throw std::invalid_argument(fmt::format("{} chromaticity ({}, {}) needs a finite y > 0", what, xy[0], xy[1]));
    return glm::dvec3(xy[0] / xy[1], 1.0, (1.0 - xy[0] - xy[1]) / xy[1]);
  };
  // Columns: XYZ of each primary at Y = 1 (glm is column-major).
  const glm::dmat3 p(toXyz(r, "red primary"), toXyz(g, "green primary"), toXyz(b, "blue primary"));
  const double det = glm::determinant(p);
  if (!(std::abs(det) > 1e-12)) throw std::invalid_argument("primaries are collinear (singular matrix)");
  // Scale each primary so that RGB (1, 1, 1) is the white point at Y = 1.
  const glm::dvec3 s = glm::inverse(p) * toXyz(white, "white point");
  glm::dmat3 rgbToXyz = p;
  for (int c = 0; c < 3; ++c) rgbToXyz[c] *= s[c];
  return glm::inverse(rgbToXyz);
}

glm::dmat3 xyzToLinearSrgb() {
  return xyzToRgbFromPrimaries({0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, {0.3127, 0.3290});
}

}  // namespace spectrace
