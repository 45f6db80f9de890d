#include "spectrum/spd.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "json/input_file.h"
#include "spectrum/cie_data.h"

namespace spectrace {
namespace {

// CODATA 2018 exact SI constants.
constexpr double kPlanck = 6.62607015e-34;     // J·s
constexpr double kLightSpeed = 299792458.0;    // m/s
constexpr double kBoltzmann = 1.380649e-23;    // J/K

double trapezoid(const std::vector<double>& x, const std::vector<double>& y) {
  double s = 0.0;
  for (size_t i = 1; i < x.size(); ++i) s += 0.5 * (x[i] - x[i - 1]) * (y[i] + y[i - 1]);
  return s;
}

// Validates a table; `label(i)` names row i in messages (e.g. "row 3" or
// "file.csv:12"). Returns the SPD with fullIntegral = its own integral.
Spd validated(std::vector<double> lambdaNm, std::vector<double> value, const std::string& context,
              const std::function<std::string(size_t)>& label) {
  if (lambdaNm.size() != value.size())
    throw SpdError(fmt::format("{}{} wavelengths but {} values", context, lambdaNm.size(), value.size()));
  if (lambdaNm.size() < 2)
    throw SpdError(fmt::format("{}a tabulated SPD needs at least 2 points (got {})", context, lambdaNm.size()));
  if (lambdaNm.size() > kMaxSpdPoints)
    throw SpdError(fmt::format("{}a tabulated SPD has at most {} points (got {})", context, kMaxSpdPoints, lambdaNm.size()));
  for (size_t i = 0; i < lambdaNm.size(); ++i) {
    const double l = lambdaNm[i], v = value[i];
    if (!std::isfinite(l)) throw SpdError(fmt::format("{}: non-finite wavelength ({})", label(i), l));
    if (l <= 0.0) throw SpdError(fmt::format("{}: wavelength must be positive, got {} nm", label(i), l));
    if (i > 0 && !(l > lambdaNm[i - 1]))
      throw SpdError(fmt::format("{}: wavelengths must be strictly increasing: {} nm after {} nm", label(i), l,
                                 lambdaNm[i - 1]));
    if (!std::isfinite(v)) throw SpdError(fmt::format("{}: non-finite value ({}) at {} nm", label(i), v, l));
    if (v < 0.0) throw SpdError(fmt::format("{}: value at {} nm is negative ({})", label(i), l, v));
  }
  Spd s{std::move(lambdaNm), std::move(value), 0.0};
  s.fullIntegral = s.integral();
  if (std::isinf(s.fullIntegral)) {
    // Values near the double range overflow the integral. An SPD gives only
    // a shape (power_w sets the scale), so scale it by an exact power of two.
    const int shift = std::ilogb(*std::max_element(s.value.begin(), s.value.end()));
    for (double& v : s.value) v = std::ldexp(v, -shift);
    s.fullIntegral = s.integral();
  }
  if (!(s.fullIntegral > 0.0))
    throw SpdError(fmt::format("{}SPD has no power (all values are zero)", context));
  return s;
}

Spd spdFromColumn(const CsvTable& t, size_t col) {
  const std::string colName = t.columns.empty() ? std::string() : " column '" + t.columns[col] + "'";
  return validated(t.lambdaNm, t.data[col], fmt::format("{}{}: ", t.source, colName),
                   [&](size_t i) { return fmt::format("{}:{}{}", t.source, t.line[i], colName); });
}

struct IlluminantSet {
  std::vector<std::string> names;
  std::map<std::string, Spd, std::less<>> spds;
};

const IlluminantSet& illuminants() {
  static const IlluminantSet set = [] {
    IlluminantSet s;
    for (const CsvTable* t : cieIlluminantTables())
      for (size_t c = 0; c < t->columns.size(); ++c) {
        s.names.push_back(t->columns[c]);
        s.spds.emplace(t->columns[c], spdFromColumn(*t, c));
      }
    return s;
  }();
  return set;
}

}  // namespace

double Spd::integral() const {
  if (lambdaNm.empty()) return 0.0;
  if (isLine()) return value[0];
  return trapezoid(lambdaNm, value);
}

double Spd::evaluate(double l) const {
  if (lambdaNm.size() < 2 || !(l >= lambdaNm.front()) || l > lambdaNm.back()) return 0.0;
  // First node strictly greater than l; l == back() lands on the last segment.
  size_t i = size_t(std::upper_bound(lambdaNm.begin(), lambdaNm.end(), l) - lambdaNm.begin());
  if (i == lambdaNm.size()) return value.back();
  const double x0 = lambdaNm[i - 1], x1 = lambdaNm[i];
  const double t = (l - x0) / (x1 - x0);
  return value[i - 1] + t * (value[i] - value[i - 1]);
}

Spd Spd::clipped(double minNm, double maxNm) const {
  Spd out;
  out.fullIntegral = fullIntegral;
  if (lambdaNm.empty() || !(minNm <= maxNm)) return out;
  if (isLine()) {
    if (lambdaNm[0] >= minNm && lambdaNm[0] <= maxNm) out = *this;
    return out;
  }
  const double lo = std::max(minNm, lambdaNm.front());
  const double hi = std::min(maxNm, lambdaNm.back());
  // A zero-width overlap would leave one node, which would read as a line.
  if (!(lo < hi)) return out;
  out.lambdaNm.push_back(lo);
  out.value.push_back(evaluate(lo));
  for (size_t i = 0; i < lambdaNm.size(); ++i)
    if (lambdaNm[i] > lo && lambdaNm[i] < hi) {
      out.lambdaNm.push_back(lambdaNm[i]);
      out.value.push_back(value[i]);
    }
  out.lambdaNm.push_back(hi);
  out.value.push_back(evaluate(hi));
  return out;
}

Spd makeTabulatedSpd(std::vector<double> lambdaNm, std::vector<double> value) {
  return validated(std::move(lambdaNm), std::move(value), "",
                   [](size_t i) { return fmt::format("row {}", i + 1); });
}

Spd makeLineSpd(double centerNm, std::optional<double> fwhmNm) {
  if (!std::isfinite(centerNm) || centerNm <= 0.0)
    throw SpdError(fmt::format("line centre must be a positive finite wavelength, got {} nm", centerNm));
  if (!fwhmNm) return Spd{{centerNm}, {1.0}, 1.0};
  const double fwhm = *fwhmNm;
  if (!std::isfinite(fwhm) || fwhm <= 0.0)
    throw SpdError(fmt::format("line FWHM must be positive and finite, got {} nm", fwhm));
  const double sigma = fwhm / (2.0 * std::sqrt(2.0 * std::numbers::ln2));
  const double lo = centerNm - 6.0 * sigma, hi = centerNm + 6.0 * sigma;
  if (lo <= 0.0)
    throw SpdError(fmt::format("line at {} nm with FWHM {} nm reaches below 0 nm (±6σ = ±{} nm)", centerNm, fwhm,
                               6.0 * sigma));
  if ((hi - lo) / double(1200) <= centerNm * 1e-12)
    throw SpdError(fmt::format("line FWHM {} nm is too narrow to tabulate at {} nm; omit the FWHM for a sharp line",
                               fwhm, centerNm));
  // Unit-area Gaussian density, so a line has total power 1 either way.
  constexpr int kNodes = 1201;  // spacing σ/100
  Spd s;
  s.lambdaNm.resize(kNodes);
  s.value.resize(kNodes);
  const double norm = 1.0 / (sigma * std::sqrt(2.0 * std::numbers::pi));
  for (int i = 0; i < kNodes; ++i) {
    const double x = -6.0 + 12.0 * double(i) / double(kNodes - 1);  // in units of σ
    s.lambdaNm[i] = centerNm + x * sigma;
    s.value[i] = norm * std::exp(-0.5 * x * x);
  }
  // fullIntegral is the table's own integral (≈ 1 − 2e-9 for the cut tails,
  // minus the trapezoid bias of ~1e-5 relative), not exactly 1, so that a
  // line with no range clipping carries exactly its table's power.
  s.fullIntegral = s.integral();
  return s;
}

double planckRadiance(double lambdaNm, double kelvin) {
  if (!(lambdaNm > 0.0) || !std::isfinite(lambdaNm) || !(kelvin > 0.0) || !std::isfinite(kelvin))
    throw SpdError(fmt::format("planckRadiance needs positive finite λ and T, got {} nm, {} K", lambdaNm, kelvin));
  const double l = lambdaNm * 1e-9;  // m
  const double x = kPlanck * kLightSpeed / (l * kBoltzmann * kelvin);
  const double l5 = (l * l) * (l * l) * l;
  // W·sr⁻¹·m⁻²·m⁻¹, then per nm.
  return 2.0 * kPlanck * kLightSpeed * kLightSpeed / l5 / std::expm1(x) * 1e-9;
}

Spd makeBlackbodySpd(double kelvin, double minNm, double maxNm) {
  if (!std::isfinite(kelvin) || kelvin <= 0.0)
    throw SpdError(fmt::format("blackbody temperature must be positive and finite, got {} K", kelvin));
  if (!std::isfinite(minNm) || !std::isfinite(maxNm) || minNm <= 0.0 || !(minNm < maxNm))
    throw SpdError(fmt::format("blackbody range must satisfy 0 < min < max, got [{}, {}] nm", minNm, maxNm));
  const auto B = [kelvin](double l) { return planckRadiance(l, kelvin); };

  // Adaptive bisection: a segment [a, b] is accepted when its trapezoid
  // differs from Simpson's rule (whose error is O(h^5), so the difference
  // estimates the trapezoid's own error) by at most kRelTol of the segment's
  // integral. All values are > 0, so the table's total relative error is
  // bounded by the same kRelTol (≈2e-7, with margin under the promised 1e-6).
  constexpr double kRelTol = 2e-7;
  constexpr double kMaxStartStep = 2.0;  // nm; Planck is smooth and unimodal
  Spd s;
  const int n0 = std::max(1, int(std::ceil((maxNm - minNm) / kMaxStartStep)));
  const double minWidth = maxNm * 1e-12;
  s.lambdaNm.push_back(minNm);
  s.value.push_back(B(minNm));
  std::function<void(double, double, double, double, int)> refine = [&](double a, double fa, double b, double fb,
                                                                        int depth) {
    const double m = 0.5 * (a + b), fm = B(m);
    const double trap = 0.5 * (b - a) * (fa + fb);
    const double simpson = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
    if (depth >= 40 || (b - a) < minWidth || std::abs(trap - simpson) <= kRelTol * simpson) {
      s.lambdaNm.push_back(b);
      s.value.push_back(fb);
      return;
    }
    refine(a, fa, m, fm, depth + 1);
    refine(m, fm, b, fb, depth + 1);
  };
  for (int i = 0; i < n0; ++i) {
    const double a = s.lambdaNm.back();
    const double b = i == n0 - 1 ? maxNm : minNm + (maxNm - minNm) * double(i + 1) / double(n0);
    refine(a, s.value.back(), b, B(b), 0);
  }
  if (!(s.integral() > 0.0))
    throw SpdError(fmt::format("blackbody at {} K has no power in [{}, {}] nm (radiance underflows)", kelvin,
                               minNm, maxNm));
  // ∫B dλ over all λ = σT⁴/π, with σ = 2π⁵k⁴/(15h³c²) from the exact constants.
  constexpr double pi = std::numbers::pi;
  const double sigmaSB = 2.0 * std::pow(pi, 5) * std::pow(kBoltzmann, 4) /
                         (15.0 * std::pow(kPlanck, 3) * kLightSpeed * kLightSpeed);
  s.fullIntegral = sigmaSB * std::pow(kelvin, 4) / pi;  // W·sr⁻¹·m⁻², i.e. (W·sr⁻¹·m⁻²·nm⁻¹)·nm
  return s;
}

Spd loadCsvSpd(const std::filesystem::path& file, const std::optional<std::string>& column) {
  std::string text;
  try {
    text = readInputFile(file, "SPD file");
  } catch (const InputFileError& e) {
    throw SpdError(e.what());
  }
  const CsvTable t = parseCsvTable(text, file.string());
  size_t col = 0;
  if (column) {
    col = csvColumnIndex(t, *column);
  } else if (t.data.size() != 1) {
    std::string names;
    for (const auto& c : t.columns) names += (names.empty() ? "" : ", ") + c;
    throw SpdError(fmt::format("{}: the file has {} value columns; name the one to use{}", t.source,
                               t.data.size(), names.empty() ? " (and add a header line naming them)"
                                                            : " (columns are: " + names + ")"));
  }
  return spdFromColumn(t, col);
}

std::optional<Spd> cieIlluminant(std::string_view name) {
  const auto& set = illuminants();
  const auto it = set.spds.find(name);
  if (it == set.spds.end()) return std::nullopt;
  return it->second;
}

std::vector<std::string> cieIlluminantNames() { return illuminants().names; }

}  // namespace spectrace
