// Reflectances: every form a light's spd takes, plus a number and the
// ColorChecker patch names.
#include "materials/material_shared.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <span>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "spectrum/cie_data.h"

namespace spectrace {

namespace jf = json_fields;

namespace {

// A constant reflectance is one node; where it sits does not matter.
constexpr double kConstantNodeNm = 550.0;

const jf::Keys kSpdForms = {"blackbody_k", "csv", "table", "lambda_nm", "value"};

const char* kReflectanceHelp =
    "a number in [0, 1], a ColorChecker patch name such as \"dark_skin\", or a spectrum of values in [0, 1]: "
    "{\"csv\": \"file.csv\"}, {\"table\": [[nm, value], ...]}, {\"lambda_nm\": [...], \"value\": [...]}";

jf::Keys patchNames() {
  const CsvTable& t = colorCheckerTable();
  return jf::Keys(t.columns.begin(), t.columns.end());
}

void setConstant(double r, SurfaceMaterial& m) {
  m.reflectanceNm = {kConstantNodeNm};
  m.reflectance = {r};
  m.reflectanceLabel = jf::fmtNum(r);
}

// A patch name; false for a name that is not one (a CIE illuminant name is a
// spectrum too, read by the caller); fails on any other name.
bool parsePatch(const jf::Source& c, const std::string& name, const std::string& p, SurfaceMaterial& m) {
  const CsvTable& patches = colorCheckerTable();
  if (auto it = std::find(patches.columns.begin(), patches.columns.end(), name); it != patches.columns.end()) {
    m.reflectanceNm = patches.lambdaNm;
    m.reflectance = patches.data[size_t(it - patches.columns.begin())];
    m.reflectanceLabel = name;
    return true;
  }
  if (!cieIlluminant(name)) {
    const jf::Keys names = patchNames();
    c.fail(p, fmt::format("unknown reflectance {}{} (ColorChecker patches: {})", jf::jsonQuoted(name),
                          jf::suggestion(name, names), jf::joinKeys(names)));
  }
  // validateReflectance refuses an illuminant's values above 1.
  return false;
}

void parseReflectanceValue(const jf::Source& c, const jf::Json& v, const std::string& p,
                           const SpectrumFieldReader& spectra, SurfaceMaterial& m) {
  if (v.is_number()) {
    setConstant(jf::getNumber(c, v, p), m);  // [0, 1] is validateReflectance's rule
    return;
  }
  if (v.is_string()) {
    if (parsePatch(c, v.get<std::string>(), p, m)) return;
  } else if (v.is_object()) {
    if (jf::find(v, "line_nm"))
      c.fail(jf::child(p, "line_nm"),
             "a spectral line is light, not a reflectance: a reflectance gives a value in [0, 1] at every "
             "wavelength (a number for a constant one, or a table)");
    if (std::none_of(kSpdForms.begin(), kSpdForms.end(),
                     [&](std::string_view k) { return jf::find(v, std::string(k)); })) {
      jf::checkObject(c, v, p, {"blackbody_k", "csv", "column", "table", "lambda_nm", "value"}, "a reflectance");
      c.fail(p, fmt::format("must be {} (got an object with none of these)", kReflectanceHelp));
    }
  } else {
    c.fail(p, fmt::format("must be {} (got {})", kReflectanceHelp, jf::describe(v)));
  }
  FieldSpectrum resolved = spectra.read(v, p);
  if (resolved.spd.isLine())
    c.fail(p, "a single spectral line is not a reflectance: give a number for a constant reflectance, or a table");
  m.reflectanceNm = std::move(resolved.spd.lambdaNm);
  m.reflectance = std::move(resolved.spd.value);
  m.reflectanceLabel = std::move(resolved.label);
  m.reflectanceFile = std::move(resolved.file);
}

}  // namespace

void parseReflectance(const jf::Source& c, const jf::Json& v, const std::string& p, const SpectrumFieldReader& spectra,
                      const double* fallback, SurfaceMaterial& m) {
  if (const jf::Json* r = jf::find(v, "reflectance")) {
    parseReflectanceValue(c, *r, jf::child(p, "reflectance"), spectra, m);
  } else if (fallback) {
    setConstant(*fallback, m);
  } else {
    jf::require(c, v, p, "reflectance", fmt::format(" ({})", kReflectanceHelp));
  }
}

void validateReflectance(const SurfaceMaterial& m, const MaterialFieldCheck& check) {
  const std::string key = "reflectance";
  const auto& nm = m.reflectanceNm;
  const auto& r = m.reflectance;
  if (nm.empty() || nm.size() != r.size())
    check.fail(key, fmt::format("needs as many wavelengths as values, at least one (got {} and {})", nm.size(),
                                r.size()));
  for (size_t i = 0; i < nm.size(); ++i)
    if (!(std::isfinite(nm[i]) && nm[i] > 0.0) || (i > 0 && !(nm[i] > nm[i - 1])))
      check.fail(key, fmt::format("wavelengths must be finite, > 0 and strictly increasing (node {} is at {} nm)", i,
                                  jf::fmtNum(nm[i])));
  // The node furthest outside [0, 1] (NaN first).
  size_t worst = 0;
  double worstBy = 0.0;
  for (size_t i = 0; i < r.size(); ++i) {
    const double by = std::isnan(r[i]) ? INFINITY : std::max(-r[i], r[i] - 1.0);
    if (by > worstBy) worst = i, worstBy = by;
  }
  if (worstBy > 0.0) {
    if (r.size() == 1) check.fail(key, fmt::format("must be a reflectance in [0, 1] (got {})", check.got(key, r[0])));
    check.fail(key, fmt::format("must lie in [0, 1] at every wavelength, but {} is {} at {} nm",
                                m.reflectanceLabel.empty() ? "the reflectance" : m.reflectanceLabel,
                                jf::fmtNum(r[worst]), jf::fmtNum(nm[worst])));
  }
}

void packReflectance(const SurfaceMaterial& material, device::Material& record, SceneData& data) {
  const ReflectanceTable table = reflectanceTable(material);
  record.reflectanceCount = uint32_t(table.values.size());
  record.reflectanceLambda0 = table.lambda0;
  record.reflectanceNodesPerNm = table.nodesPerNm;
  record.reflectanceFirst = data.append(std::span<const float>(table.values));
}

bool reflectanceVaries(const SurfaceMaterial& m) {
  return std::adjacent_find(m.reflectance.begin(), m.reflectance.end(), std::not_equal_to<>()) != m.reflectance.end();
}

void packNoReflectance(device::Material& record, SceneData& data) {
  record.reflectanceCount = 1;
  const float none = 0.0f;
  record.reflectanceFirst = data.append(std::span<const float>(&none, 1));
}

double SurfaceMaterial::reflectanceAt(double lambdaNm) const {
  const size_t n = std::min(reflectanceNm.size(), reflectance.size());
  if (n == 0) return 0.0;
  if (!(lambdaNm > reflectanceNm.front())) return reflectance.front();
  if (!(lambdaNm < reflectanceNm[n - 1])) return reflectance[n - 1];
  // First node above lambdaNm; the one before is at or below it.
  const size_t i = size_t(std::upper_bound(reflectanceNm.begin(), reflectanceNm.begin() + n, lambdaNm) -
                          reflectanceNm.begin());
  const double x0 = reflectanceNm[i - 1], x1 = reflectanceNm[i];
  const double t = (lambdaNm - x0) / (x1 - x0);
  return reflectance[i - 1] + t * (reflectance[i] - reflectance[i - 1]);
}

ReflectanceTable reflectanceTable(const SurfaceMaterial& material) {
  ReflectanceTable table;
  const std::vector<double>& nm = material.reflectanceNm;
  if (nm.size() < 2) {
    table.lambda0 = nm.empty() ? 0.0f : float(nm.front());
    table.nodesPerNm = 1.0f;
    table.values.push_back(float(material.reflectance.empty() ? 0.0 : material.reflectance.front()));
    return table;
  }
  // The grid step: evenly spaced nodes (tabulated data usually are) are the
  // grid, exactly; otherwise 1 nm or the smallest spacing if finer, which
  // holds every node to within that step. At most 100k nodes either way.
  constexpr double kMaxNodes = 100000;
  double smallest = nm[1] - nm[0], largest = smallest;
  for (size_t i = 1; i < nm.size(); ++i) {
    smallest = std::min(smallest, nm[i] - nm[i - 1]);
    largest = std::max(largest, nm[i] - nm[i - 1]);
  }
  double step = largest - smallest <= 1e-9 * largest ? smallest : std::min(1.0, smallest);
  const double span = nm.back() - nm.front();
  step = std::max(step, span / (kMaxNodes - 1));
  const size_t count = size_t(std::ceil(span / step - 1e-9)) + 1;
  step = span / double(count - 1);
  table.lambda0 = float(nm.front());
  table.nodesPerNm = float(1.0 / step);
  for (size_t i = 0; i < count; ++i) table.values.push_back(float(material.reflectanceAt(nm.front() + double(i) * step)));
  return table;
}

}  // namespace spectrace
