#include "spectrum/glass.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <system_error>

#include <fmt/format.h>

#include "embedded_glass.h"
#include "json/json_fields.h"
#include "spectrum/cie_data.h"

namespace spectrace {
namespace {

// Parses "name,b1,b2,b3,c1_um2,c2_um2,c3_um2" rows after one header line.
// The table is compiled in, so a malformed row is a build mistake: it throws
// (at first use) rather than being skipped, so a test catches it.
std::vector<SellmeierGlass> parseCatalogue(std::string_view text) {
  constexpr std::string_view kSource = "embedded data/glass/sellmeier.csv";
  std::vector<SellmeierGlass> glasses;
  bool sawHeader = false;
  int lineNo = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    std::string_view line = text.substr(pos, nl - pos);
    pos = nl + 1;
    ++lineNo;
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    line = trimWhitespace(line);
    if (line.empty()) continue;
    if (!sawHeader) {
      sawHeader = true;
      continue;
    }
    std::vector<std::string_view> fields;
    for (size_t start = 0;;) {
      const size_t comma = line.find(',', start);
      const size_t length = comma == std::string_view::npos ? std::string_view::npos : comma - start;
      fields.push_back(trimWhitespace(line.substr(start, length)));
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (fields.size() != 7 || fields[0].empty())
      throw std::runtime_error(fmt::format("{}:{}: expected a name and 6 coefficients", kSource, lineNo));
    SellmeierGlass g;
    g.name = std::string(fields[0]);
    for (size_t i = 0; i < 6; ++i) {
      const std::string_view f = fields[i + 1];
      double v = 0.0;
      const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
      if (ec != std::errc() || ptr != f.data() + f.size() || !std::isfinite(v))
        throw std::runtime_error(fmt::format("{}:{}: '{}' is not a finite number", kSource, lineNo, f));
      (i < 3 ? g.b[i] : g.cUm2[i - 3]) = v;
    }
    glasses.push_back(std::move(g));
  }
  return glasses;
}

const std::vector<SellmeierGlass>& catalogue() {
  static const std::vector<SellmeierGlass> glasses = [] {
    const auto bytes = embedded::glass_sellmeier();
    return parseCatalogue(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  }();
  return glasses;
}

}  // namespace

const SellmeierGlass* glassNamed(std::string_view name) {
  for (const SellmeierGlass& g : catalogue())
    if (g.name == name) return &g;
  return nullptr;
}

std::vector<std::string> glassNames() {
  std::vector<std::string> names;
  for (const SellmeierGlass& g : catalogue()) names.push_back(g.name);
  return names;
}

double sellmeierIndex(const std::array<double, 3>& b, const std::array<double, 3>& cUm2, double lambdaNm) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const double lambdaUm = lambdaNm / 1000.0;  // exact for whole-um wavelengths, so poles are hit
  const double l2 = lambdaUm * lambdaUm;
  double n2 = 1.0;
  for (size_t i = 0; i < 3; ++i) {
    const double denom = l2 - cUm2[i];
    if (denom == 0.0) return kNaN;
    n2 += b[i] * l2 / denom;
  }
  // !(n2 > 0) also catches NaN inputs and inf/inf near a pole.
  if (!(n2 > 0.0) || !std::isfinite(n2)) return kNaN;
  return std::sqrt(n2);
}

// With b, c >= 0 every term b l^2 / (l^2 - c) falls as l grows between
// poles (its derivative in l^2 is -b c / (l^2 - c)^2), so without a pole
// inside the range n is finite there and least at maxNm: checking that end
// checks the whole range.
std::string sellmeierRangeProblem(const std::array<double, 3>& b, const std::array<double, 3>& cUm2,
                                  const std::string& label, double minNm, double maxNm) {
  namespace jf = json_fields;
  for (size_t i = 0; i < 3; ++i) {
    const double poleNm = 1000.0 * std::sqrt(cUm2[i]);
    if (b[i] != 0.0 && poleNm >= minNm && poleNm <= maxNm)
      return fmt::format("the refractive index of {} has a pole at {} nm (C{} = {} um^2), inside the scene's "
                         "spectrum range {}-{} nm",
                         label, jf::fmtNum(poleNm), i + 1, jf::fmtNum(cUm2[i]), jf::fmtNum(minNm), jf::fmtNum(maxNm));
  }
  for (double nm : {maxNm, minNm}) {
    const double n = sellmeierIndex(b, cUm2, nm);
    if (!(std::isfinite(n) && n >= 1.0))
      return fmt::format("the refractive index of {} must be finite and >= 1 over the scene's spectrum range {}-{} "
                         "nm, but at {} nm it is {}",
                         label, jf::fmtNum(minNm), jf::fmtNum(maxNm), jf::fmtNum(nm),
                         std::isnan(n) ? std::string("not a real number (n^2 <= 0)") : jf::fmtNum(n));
  }
  return "";
}

// b follows from nd for any c: b = (nd^2 - 1) (d^2 - c) / d^2. nF - nC
// grows from 0 (c = 0) without bound as c nears F^2 (the pole reaches the
// F line), so one c in between gives vd; bisection finds it to the last
// bit in double.
std::optional<SellmeierGlass> modelGlass(double nd, double vd) {
  if (!(std::isfinite(nd) && std::isfinite(vd) && nd > 1.0 && vd > 0.0)) return std::nullopt;
  const double d2 = (kLineDNm / 1000.0) * (kLineDNm / 1000.0);
  const double f2 = (kLineFNm / 1000.0) * (kLineFNm / 1000.0);
  const double target = (nd - 1.0) / vd;
  const auto glassWith = [&](double c) {
    SellmeierGlass g;
    g.name = "model glass";
    g.b = {(nd * nd - 1.0) * (d2 - c) / d2, 0.0, 0.0};
    g.cUm2 = {c, 0.0, 0.0};
    return g;
  };
  const auto dispersion = [&](double c) {
    const SellmeierGlass g = glassWith(c);
    return sellmeierIndex(g.b, g.cUm2, kLineFNm) - sellmeierIndex(g.b, g.cUm2, kLineCNm);
  };
  double lo = 0.0, hi = f2;
  for (int i = 0; i < 200 && lo < hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    const double x = dispersion(mid);
    if (std::isfinite(x) && x < target) lo = mid;
    else hi = mid;
  }
  return glassWith(lo);
}

}  // namespace spectrace
