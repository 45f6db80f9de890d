#include "lights/photometric_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <iterator>
#include <numbers>

#include <fmt/format.h>

#include "json/input_file.h"

namespace spectrace {
namespace {

[[noreturn]] void fail(const std::string& name, size_t line, const std::string& what) {
  throw PhotometricFileError(fmt::format("{}:{}: {}", name, line, what));
}

struct Token {
  std::string_view text;
  size_t line;
};

// The numbers after the TILT line, with their lines: LM-63 lets them run
// over lines freely, separated by blanks (some writers use commas).
class NumberStream {
 public:
  NumberStream(std::string name, std::vector<Token> tokens, size_t lastLine)
      : name_(std::move(name)), tokens_(std::move(tokens)), lastLine_(lastLine) {}

  double next(const std::string& what) {
    if (at_ == tokens_.size()) fail(name_, lastLine_, fmt::format("the file ends where {} should be: truncated", what));
    const Token& t = tokens_[at_++];
    std::string_view s = t.text;
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    double v = 0.0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v))
      fail(name_, t.line, fmt::format("'{}' is not a number ({})", t.text, what));
    return v;
  }
  // A count: a whole number from `lo` up.
  size_t count(const std::string& what, double lo) {
    const size_t line = this->line();
    const double v = next(what);
    if (v != std::floor(v) || v < lo || v > 1e6)
      fail(name_, line, fmt::format("{} is {}: must be a whole number from {} to 1000000", what, v, lo));
    return size_t(v);
  }
  size_t line() const { return at_ < tokens_.size() ? tokens_[at_].line : lastLine_; }
  size_t left() const { return tokens_.size() - at_; }

 private:
  std::string name_;
  std::vector<Token> tokens_;
  size_t lastLine_;
  size_t at_ = 0;
};

// Neighbouring angles at least this far apart (degrees): far below any
// real table's steps, and far enough that the kernel's angles in turns
// (floats) stay distinct and a patch's sin(gamma) envelope stays well above
// its float slack.
constexpr double kMinAngleStepDeg = 1e-3;

// Angles in degrees, strictly ascending; `what` names them in messages.
std::vector<double> readAngles(NumberStream& in, size_t n, const std::string& what, const std::string& name) {
  std::vector<double> angles;
  for (size_t i = 0; i < n; ++i) {
    const size_t line = in.line();
    angles.push_back(in.next(fmt::format("{} angle {} of {}", what, i + 1, n)));
    if (i > 0 && !(angles[i] > angles[i - 1]))
      fail(name, line, fmt::format("{} angle {} of {} is {}, not above the one before ({}): angles must ascend", what,
                                   i + 1, n, angles[i], angles[i - 1]));
    if (i > 0 && angles[i] - angles[i - 1] < kMinAngleStepDeg)
      fail(name, line, fmt::format("{} angle {} of {} is {}, within {} degrees of the one before ({})", what, i + 1, n,
                                   angles[i], kMinAngleStepDeg, angles[i - 1]));
  }
  return angles;
}

// The horizontal angles' symmetry unfolded: every C in [0, 360] the file's
// angles give through their mirror images, with the column it copies (in
// no order, repeats included: setColumns sorts them out).
std::vector<std::pair<double, size_t>> unfoldSymmetry(const std::vector<double>& h, const std::string& name,
                                                      size_t line) {
  std::vector<std::pair<double, size_t>> images;
  auto add = [&](double c, size_t k) {
    if (c >= 0.0 && c <= 360.0) images.emplace_back(c, k);
  };
  const double first = h.front(), last = h.back();
  for (size_t k = 0; k < h.size(); ++k) {
    if (h.size() == 1 && first == 0.0) {  // rotationally symmetric
      add(0.0, k);
      add(360.0, k);
    } else if (first == 0.0 && last == 90.0) {  // symmetric in each quadrant
      add(h[k], k);
      add(180.0 - h[k], k);
      add(180.0 + h[k], k);
      add(360.0 - h[k], k);
    } else if (first == 0.0 && last == 180.0) {  // about the C0-C180 plane
      add(h[k], k);
      add(360.0 - h[k], k);
    } else if (first == 0.0 && last == 360.0) {  // no symmetry
      add(h[k], k);
    } else if (first == 90.0 && last == 270.0) {  // about the C90-C270 plane (LM-63-1995)
      add(h[k], k);
      add(180.0 - h[k], k);
      add(540.0 - h[k], k);
    } else {
      fail(name, line,
           fmt::format("horizontal angles run from {} to {}; Type C photometry has one angle (0), or runs 0-90, "
                       "0-180, 0-360 or 90-270",
                       first, last));
    }
  }
  return images;
}

// Index i with v[i] <= x < v[i + 1] (clamped into the table), and the
// fraction of the way.
size_t intervalOf(const std::vector<double>& v, double x, double& fraction) {
  const auto upper = std::upper_bound(v.begin(), v.end(), x);
  size_t i = upper == v.begin() ? 0 : size_t(upper - v.begin()) - 1;
  i = std::min(i, v.size() - 2);
  fraction = (x - v[i]) / (v[i + 1] - v[i]);
  return i;
}

// The table's C angles and candela columns from (C, column of `values`)
// pairs: sorted by C, one column at each C (mirror images that land on
// one C copy equal columns by symmetry).
void setColumns(PhotometricTable& table, std::vector<std::pair<double, size_t>> images,
                const std::vector<double>& values, size_t perColumn) {
  std::sort(images.begin(), images.end());
  images.erase(std::unique(images.begin(), images.end(), [](auto& a, auto& b) { return a.first == b.first; }),
               images.end());
  for (const auto& [c, column] : images) {
    table.cDegrees.push_back(c);
    table.candela.insert(table.candela.end(), values.begin() + std::ptrdiff_t(column * perColumn),
                         values.begin() + std::ptrdiff_t((column + 1) * perColumn));
  }
  // The table is periodic in C: where the images miss C = 0 or 360 (a 90-270
  // file without 180), the column there lies between the last C and the
  // first C + 360, as the interpolation across 0 has it.
  const double low = table.cDegrees.front(), high = table.cDegrees.back();
  if (low > 0.0 || high < 360.0) {
    const double t = (360.0 - high) / (low + 360.0 - high);
    std::vector<double> wrapped(perColumn);
    const size_t last = table.candela.size() - perColumn;
    for (size_t g = 0; g < perColumn; ++g)
      wrapped[g] = table.candela[last + g] + t * (table.candela[g] - table.candela[last + g]);
    if (high < 360.0) {
      table.cDegrees.push_back(360.0);
      table.candela.insert(table.candela.end(), wrapped.begin(), wrapped.end());
    }
    if (low > 0.0) {
      table.cDegrees.insert(table.cDegrees.begin(), 0.0);
      table.candela.insert(table.candela.begin(), wrapped.begin(), wrapped.end());
    }
  }
}

double mod360(double c) {
  const double m = std::fmod(c, 360.0);
  return m < 0.0 ? m + 360.0 : m;
}

}  // namespace

double PhotometricTable::intensity(double cDeg, double gammaDeg) const {
  if (!(gammaDeg >= gammaDegrees.front() && gammaDeg <= gammaDegrees.back())) return 0.0;
  double s = 0.0, t = 0.0;
  const size_t i = intervalOf(cDegrees, mod360(cDeg), s);
  const size_t j = intervalOf(gammaDegrees, gammaDeg, t);
  return (1.0 - s) * ((1.0 - t) * at(i, j) + t * at(i, j + 1)) + s * ((1.0 - t) * at(i + 1, j) + t * at(i + 1, j + 1));
}

double PhotometricTable::patchLumens(size_t c, size_t g) const {
  // Over a patch, I is linear in C at each gamma, so its C integral is the
  // width times the mean of the two edges; along gamma, with t = (gamma -
  // g0) / dg, the integrals of (1 - t) sin(gamma) and t sin(gamma) are
  // A - B / dg and B / dg, A = cos g0 - cos g1, B = sin g1 - sin g0 - dg cos g1.
  constexpr double kRad = std::numbers::pi / 180.0;
  const double g0 = gammaDegrees[g] * kRad, g1 = gammaDegrees[g + 1] * kRad, dg = g1 - g0;
  const double a = std::cos(g0) - std::cos(g1);
  const double b = std::sin(g1) - std::sin(g0) - dg * std::cos(g1);
  const double lower = a - b / dg, upper = b / dg;  // weights of the patch's gamma-edges g0 and g1
  const double dc = (cDegrees[c + 1] - cDegrees[c]) * kRad;
  return 0.5 * dc * (lower * (at(c, g) + at(c + 1, g)) + upper * (at(c, g + 1) + at(c + 1, g + 1)));
}

double PhotometricTable::tableLumens() const {
  double flux = 0.0;
  for (size_t c = 0; c + 1 < cDegrees.size(); ++c)
    for (size_t g = 0; g + 1 < gammaDegrees.size(); ++g) flux += patchLumens(c, g);
  return flux;
}

PhotometricTable parseIes(std::string_view text, const std::string& name) {
  // The header: an optional format line, keyword lines, then TILT=.
  size_t line = 0, pos = 0;
  std::optional<size_t> tiltLine;
  while (pos < text.size() && !tiltLine) {
    const size_t end = std::min(text.find('\n', pos), text.size());
    std::string_view l = text.substr(pos, end - pos);
    pos = end + 1;
    ++line;
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    if (l.substr(0, 5) != "TILT=") continue;
    std::string_view tilt = l.substr(5);
    while (!tilt.empty() && (tilt.back() == ' ' || tilt.back() == '\t')) tilt.remove_suffix(1);
    if (tilt != "NONE")
      fail(name, line, fmt::format("TILT={}: only TILT=NONE is supported (a lamp whose output does not depend on "
                                   "its tilt)",
                                   tilt));
    tiltLine = line;
  }
  if (!tiltLine) fail(name, line, "no TILT= line: not an IES LM-63 photometric file");

  std::vector<Token> tokens;
  while (pos < text.size()) {
    const size_t end = std::min(text.find('\n', pos), text.size());
    const std::string_view l = text.substr(pos, end - pos);
    ++line;
    size_t k = 0;
    while (k < l.size()) {
      while (k < l.size() && (l[k] == ' ' || l[k] == '\t' || l[k] == ',' || l[k] == '\r')) ++k;
      const size_t start = k;
      while (k < l.size() && !(l[k] == ' ' || l[k] == '\t' || l[k] == ',' || l[k] == '\r')) ++k;
      if (k > start) tokens.push_back({l.substr(start, k - start), line});
    }
    pos = end + 1;
  }
  NumberStream in(name, std::move(tokens), line);

  PhotometricTable table;
  const size_t lamps = in.count("the number of lamps", 1);
  const size_t lumensLine = in.line();
  const double lumensPerLamp = in.next("the lumens per lamp");
  const size_t multiplierLine = in.line();
  const double multiplier = in.next("the candela multiplier");
  const size_t verticalCount = in.count("the number of vertical angles", 2);
  const size_t horizontalCount = in.count("the number of horizontal angles", 1);
  const size_t typeLine = in.line();
  const double photometricType = in.next("the photometric type");
  in.next("the units type");
  in.next("the width");
  in.next("the length");
  in.next("the height");
  const size_t ballastLine = in.line();
  const double ballast = in.next("the ballast factor");
  const double ballastLamp = in.next("the ballast-lamp photometric factor");  // "future use" (1) since 2002
  table.inputWatts = in.next("the input watts");

  if (lumensPerLamp != -1.0 && !(lumensPerLamp > 0.0))
    fail(name, lumensLine, fmt::format("lumens per lamp is {}: must be positive, or -1 for absolute photometry",
                                       lumensPerLamp));
  if (!(multiplier > 0.0))
    fail(name, multiplierLine, fmt::format("candela multiplier is {}: must be positive", multiplier));
  if (photometricType != 1.0)
    fail(name, typeLine, fmt::format("photometric type is {}: only Type C (1) is supported", photometricType));
  if (!(ballast > 0.0) || !(ballastLamp > 0.0))
    fail(name, ballastLine, fmt::format("ballast factor {} and ballast-lamp factor {}: both must be positive", ballast,
                                        ballastLamp));
  if (lumensPerLamp > 0.0) table.ratedLumens = double(lamps) * lumensPerLamp;

  const size_t verticalLine = in.line();
  const std::vector<double> vertical = readAngles(in, verticalCount, "vertical", name);
  if (!((vertical.front() == 0.0 || vertical.front() == 90.0) && (vertical.back() == 90.0 || vertical.back() == 180.0)))
    fail(name, verticalLine,
         fmt::format("vertical angles run from {} to {}; Type C photometry runs 0-90, 0-180 or 90-180",
                     vertical.front(), vertical.back()));
  const size_t horizontalLine = in.line();
  const std::vector<double> horizontal = readAngles(in, horizontalCount, "horizontal", name);
  auto images = unfoldSymmetry(horizontal, name, horizontalLine);

  std::vector<double> values;
  const double factor = multiplier * ballast * ballastLamp;
  for (size_t h = 0; h < horizontalCount; ++h) {
    for (size_t v = 0; v < verticalCount; ++v) {
      const size_t valueLine = in.line();
      const double cd = in.next(fmt::format("the candela value at horizontal angle {} ({} of {}), vertical angle {}",
                                            horizontal[h], h + 1, horizontalCount, vertical[v]));
      if (cd < 0.0)
        fail(name, valueLine, fmt::format("candela value {} at horizontal angle {}, vertical angle {} is negative", cd,
                                          horizontal[h], vertical[v]));
      values.push_back(cd * factor);
    }
  }
  if (in.left() > 0)
    fail(name, in.line(),
         fmt::format("{} more numbers after the {} x {} candela values the header announces", in.left(),
                     horizontalCount, verticalCount));

  table.gammaDegrees = vertical;
  setColumns(table, std::move(images), values, verticalCount);
  return table;
}

namespace {

// Through readInputFile: bounded, regular files only, and from a render
// state's bundle when a scene is developed from one.
std::string readText(const std::filesystem::path& path) {
  try {
    return readInputFile(path, "photometric file");
  } catch (const InputFileError& e) {
    throw PhotometricFileError(e.what());
  }
}

// EULUMDAT's lines, one field each, numbered from 1.
class LdtLines {
 public:
  LdtLines(std::string_view text, std::string name) : name_(std::move(name)) {
    size_t pos = 0;
    while (pos < text.size()) {
      const size_t end = std::min(text.find('\n', pos), text.size());
      std::string_view l = text.substr(pos, end - pos);
      while (!l.empty() && (l.back() == '\r' || l.back() == ' ' || l.back() == '\t')) l.remove_suffix(1);
      while (!l.empty() && (l.front() == ' ' || l.front() == '\t')) l.remove_prefix(1);
      lines_.push_back(l);
      pos = end + 1;
    }
  }
  size_t line() const { return at_ + 1; }
  std::string_view text(const std::string& what) {
    if (at_ == lines_.size())
      fail(name_, lines_.size(), fmt::format("the file ends where {} should be: truncated", what));
    return lines_[at_++];
  }
  // A decimal comma ("0,85"), as files written in comma locales have it, is
  // read as a point: with one field a line it cannot separate fields (and
  // EULUMDAT has no thousands separators: "1,000" is 1).
  double number(const std::string& what) {
    const size_t line = this->line();
    const std::string_view t = text(what);
    std::string point(t);
    if (std::count(point.begin(), point.end(), ',') == 1 && point.find('.') == std::string::npos)
      point[point.find(',')] = '.';
    double v = 0.0;
    const auto [end, ec] = std::from_chars(point.data(), point.data() + point.size(), v);
    if (t.empty() || ec != std::errc() || end != point.data() + point.size() || !std::isfinite(v))
      fail(name_, line, fmt::format("'{}' is not a number ({})", t, what));
    return v;
  }
  size_t count(const std::string& what, double lo, double hi) {
    const size_t line = this->line();
    const double v = number(what);
    if (v != std::floor(v) || v < lo || v > hi)
      fail(name_, line, fmt::format("{} is {}: must be a whole number from {} to {}", what, v, lo, hi));
    return size_t(v);
  }
  size_t left() const { return lines_.size() - at_; }
  // Blank lines at the end are no data.
  size_t leftWithText() const {
    size_t n = 0;
    for (size_t k = at_; k < lines_.size(); ++k) n += lines_[k].empty() ? 0 : 1;
    return n;
  }

 private:
  std::string name_;
  std::vector<std::string_view> lines_;
  size_t at_ = 0;
};

}  // namespace

PhotometricTable parseEulumdat(std::string_view text, const std::string& name) {
  LdtLines in(text, name);
  in.text("the company identification");
  in.count("the type indicator Ityp", 0, 3);
  const size_t symmetryLine = in.line();
  const size_t symmetry = in.count("the symmetry indicator Isym", 0, 4);
  const size_t planeCount = in.count("the number of C planes Mc", 1, 3600);
  in.number("the distance between C planes Dc");
  const size_t gammaCount = in.count("the number of intensities per C plane Ng", 2, 3600);
  in.number("the distance between intensities Dg");
  for (const char* field : {"the measurement report number", "the luminaire name", "the luminaire number",
                            "the file name", "the date and user"})
    in.text(field);
  for (const char* field : {"the luminaire's length or diameter", "the luminaire's width", "the luminaire's height",
                            "the luminous area's length or diameter", "the luminous area's width",
                            "the luminous area's height at C0", "at C90", "at C180", "at C270",
                            "the downward flux fraction", "the light output ratio"})
    in.number(field);
  const size_t factorLine = in.line();
  const double factor = in.number("the conversion factor for luminous intensities");
  if (!(factor > 0.0)) fail(name, factorLine, fmt::format("the conversion factor is {}: must be positive", factor));
  in.number("the tilt during measurement");
  const size_t sets = in.count("the number of sets of lamps n", 1, 20);
  std::vector<double> flux(sets), watts(sets);
  std::vector<size_t> fluxLines(sets);
  for (size_t k = 0; k < sets; ++k) in.text(fmt::format("the number of lamps of set {}", k + 1));
  for (size_t k = 0; k < sets; ++k) in.text(fmt::format("the type of lamps of set {}", k + 1));
  for (size_t k = 0; k < sets; ++k) {
    fluxLines[k] = in.line();
    flux[k] = in.number(fmt::format("the total luminous flux of set {}", k + 1));
  }
  for (size_t k = 0; k < sets; ++k) in.text(fmt::format("the colour temperature of set {}", k + 1));
  for (size_t k = 0; k < sets; ++k) in.text(fmt::format("the colour rendering of set {}", k + 1));
  for (size_t k = 0; k < sets; ++k) watts[k] = in.number(fmt::format("the wattage of set {}", k + 1));
  if (!(flux[0] > 0.0))
    fail(name, fluxLines[0], fmt::format("the lamps' total luminous flux is {}: must be positive", flux[0]));
  for (size_t k = 0; k < 10; ++k) in.number(fmt::format("direct ratio {} of 10", k + 1));

  const size_t cLine = in.line();
  std::vector<double> cAngles;
  for (size_t k = 0; k < planeCount; ++k) {
    const size_t line = in.line();
    cAngles.push_back(in.number(fmt::format("C angle {} of {}", k + 1, planeCount)));
    if (!(cAngles[k] >= 0.0 && cAngles[k] < 360.0) || (k > 0 && !(cAngles[k] >= cAngles[k - 1] + kMinAngleStepDeg)))
      fail(name, line,
           fmt::format("C angle {} of {} is {}: C angles must ascend from 0 below 360, at least {} degrees apart", k + 1,
                       planeCount, cAngles[k], kMinAngleStepDeg));
  }
  if (cAngles.front() != 0.0) fail(name, cLine, fmt::format("the first C angle is {}, not 0", cAngles.front()));
  std::vector<double> gammas;
  for (size_t k = 0; k < gammaCount; ++k) {
    const size_t line = in.line();
    gammas.push_back(in.number(fmt::format("gamma angle {} of {}", k + 1, gammaCount)));
    if (!(gammas[k] >= 0.0 && gammas[k] <= 180.0) || (k > 0 && !(gammas[k] >= gammas[k - 1] + kMinAngleStepDeg)))
      fail(name, line,
           fmt::format("gamma angle {} of {} is {}: gamma angles must ascend within 0 to 180, at least {} degrees apart",
                       k + 1, gammaCount, gammas[k], kMinAngleStepDeg));
  }

  // The planes the file holds (EULUMDAT's Mc1 to Mc2), and where each
  // symmetry mirrors them.
  auto planeAt = [&](double c) {
    const auto it = std::find(cAngles.begin(), cAngles.end(), c);
    if (it == cAngles.end())
      fail(name, symmetryLine, fmt::format("symmetry {} needs a C plane at {} degrees, which the C angles (line {}) "
                                           "lack",
                                           symmetry, c, cLine));
    return size_t(it - cAngles.begin());
  };
  std::vector<size_t> given;  // plane indices, in the file's order
  if (symmetry == 1) given = {0};
  else if (symmetry == 2) for (size_t k = 0; k <= planeAt(180.0); ++k) given.push_back(k);
  else if (symmetry == 4) for (size_t k = 0; k <= planeAt(90.0); ++k) given.push_back(k);
  else if (symmetry == 3) {
    for (size_t k = planeAt(270.0); k < planeCount; ++k) given.push_back(k);
    for (size_t k = 0; k <= planeAt(90.0); ++k) given.push_back(k);
  } else {
    for (size_t k = 0; k < planeCount; ++k) given.push_back(k);
  }
  std::vector<double> values;
  for (size_t k : given) {
    for (size_t g = 0; g < gammaCount; ++g) {
      const size_t line = in.line();
      const double v = in.number(fmt::format("the intensity at C {}, gamma {}", cAngles[k], gammas[g]));
      if (v < 0.0)
        fail(name, line, fmt::format("intensity {} at C {}, gamma {} is negative", v, cAngles[k], gammas[g]));
      values.push_back(v * factor * flux[0] / 1000.0);  // cd per 1000 lm of the lamps
    }
  }
  if (in.leftWithText() > 0)
    fail(name, in.line(), fmt::format("{} more lines after the {} x {} intensities the header announces",
                                      in.leftWithText(), given.size(), gammaCount));

  std::vector<std::pair<double, size_t>> images;  // (C, column of `values`)
  for (size_t col = 0; col < given.size(); ++col) {
    const double c = cAngles[given[col]];
    std::vector<double> mirrors = {c};
    if (symmetry == 1) mirrors = {0.0, 360.0};
    if (symmetry == 2) mirrors.push_back(360.0 - c);
    if (symmetry == 3) mirrors.push_back(mod360(180.0 - c));
    if (symmetry == 4) mirrors.insert(mirrors.end(), {180.0 - c, 180.0 + c, 360.0 - c});
    for (double m : mirrors) {
      images.emplace_back(m, col);
      if (m == 0.0) images.emplace_back(360.0, col);  // the table closes the circle
    }
  }

  PhotometricTable table;
  table.gammaDegrees = gammas;
  table.ratedLumens = flux[0];
  table.inputWatts = watts[0];
  setColumns(table, std::move(images), values, gammaCount);
  return table;
}

PhotometricTable readIesFile(const std::filesystem::path& path) { return parseIes(readText(path), path.string()); }

PhotometricTable readEulumdatFile(const std::filesystem::path& path) {
  return parseEulumdat(readText(path), path.string());
}

PhotometricTable readPhotometricFile(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& ch : extension) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  if (extension == ".ies") return readIesFile(path);
  if (extension == ".ldt") return readEulumdatFile(path);
  throw PhotometricFileError(
      fmt::format("{}: a photometric file is IES LM-63 (.ies) or EULUMDAT (.ldt), by its extension", path.string()));
}

}  // namespace spectrace
