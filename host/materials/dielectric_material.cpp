// Dielectric (glass): Fresnel reflection and Snell refraction with a
// Sellmeier index, from a catalogue glass, its coefficients or a constant
// "ior". It needs a closed shape, an inside to refract into.
#include <cmath>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "materials/material_shared.h"
#include "spectrum/glass.h"

namespace spectrace {

namespace {

namespace jf = json_fields;

// A constant refractive index ("ior"): above any transparent material's.
constexpr double kMaxIor = 5.0;

std::array<double, 3> getThree(const jf::Source& c, const jf::Json& v, const std::string& p, const char* names) {
  if (!v.is_array() || v.size() != 3)
    c.fail(p, fmt::format("must be an array of 3 finite numbers {} (got {})", names, jf::describe(v)));
  std::array<double, 3> out{};
  for (size_t i = 0; i < 3; ++i) out[i] = jf::getNumber(c, v[i], jf::child(p, i));
  return out;
}

void parseGlass(const jf::Source& c, const jf::Json& v, const std::string& p, const jf::Keys& glassKeys,
                SurfaceMaterial& m) {
  const std::string gp = jf::child(p, "glass");
  const std::string name = jf::getString(c, v.at("glass"), gp);
  const SellmeierGlass* glass = glassNamed(name);
  if (!glass)
    c.fail(gp, fmt::format("unknown glass {}{} (known: {})", jf::jsonQuoted(name), jf::suggestion(name, glassKeys),
                           jf::joinKeys(glassKeys)));
  m.sellmeierB = glass->b;
  m.sellmeierC = glass->cUm2;
  m.glassLabel = glass->name;
}

void parseSellmeier(const jf::Source& c, const jf::Json& v, const std::string& p, SurfaceMaterial& m) {
  const std::string sp = jf::child(p, "sellmeier");
  const jf::Json& s = v.at("sellmeier");
  jf::checkObject(c, s, sp, {"b", "c_um2"}, "sellmeier");
  m.sellmeierB = getThree(c, jf::require(c, s, sp, "b"), jf::child(sp, "b"), "[b1, b2, b3]");
  m.sellmeierC = getThree(c, jf::require(c, s, sp, "c_um2", " (in square micrometres)"), jf::child(sp, "c_um2"),
                          "[c1, c2, c3] in um^2");
  m.glassLabel = "sellmeier";
}

void parseIor(const jf::Source& c, const jf::Json& v, const std::string& p, SurfaceMaterial& m) {
  const std::string ip = jf::child(p, "ior");
  const double n = jf::getNumber(c, v.at("ior"), ip);
  if (!(n >= 1.0 && n <= kMaxIor))
    c.fail(ip, fmt::format("must be a refractive index, >= 1 and <= {} (got {})", jf::fmtNum(kMaxIor),
                           jf::describe(v.at("ior"))));
  m.sellmeierB = {n * n - 1.0, 0.0, 0.0};
  m.sellmeierC = {0.0, 0.0, 0.0};
  m.glassLabel = "ior " + jf::fmtNum(n);
}

void parse(const jf::Source& c, const jf::Json& v, const std::string& p, const SpectrumFieldReader&,
           SurfaceMaterial& m) {
  static const jf::Keys kForms = {"glass", "sellmeier", "ior"};
  jf::checkObject(c, v, p, {"type", "glass", "sellmeier", "ior"}, "a dielectric material");
  std::vector<std::string_view> present;
  for (auto f : kForms)
    if (jf::find(v, std::string(f))) present.push_back(f);
  const std::vector<std::string> glasses = glassNames();
  const jf::Keys glassKeys(glasses.begin(), glasses.end());
  if (present.empty())
    c.fail(p, fmt::format("a dielectric needs one of \"glass\" (one of: {}), \"sellmeier\" ({{\"b\": [b1, b2, b3], "
                          "\"c_um2\": [c1, c2, c3]}}) or \"ior\" (a constant refractive index)",
                          jf::joinKeys(glassKeys)));
  if (present.size() > 1)
    c.fail(p, fmt::format("ambiguous refractive index: has both {} and {}; use exactly one of {}",
                          jf::jsonQuoted(present[0]), jf::jsonQuoted(present[1]), jf::joinKeys(kForms)));
  if (present[0] == "glass") parseGlass(c, v, p, glassKeys, m);
  else if (present[0] == "sellmeier") parseSellmeier(c, v, p, m);
  else parseIor(c, v, p, m);
}

// The file's own key for the index ("glass", "sellmeier", "ior"), so
// messages name what was written; "" (the material) for a scene built in code.
std::string indexKey(const MaterialFieldCheck& check) {
  for (const char* key : {"glass", "sellmeier", "ior"})
    if (check.given(key)) return key;
  return "";
}

void validate(const SurfaceMaterial& m, double minNm, double maxNm, const MaterialFieldCheck& check) {
  for (auto [name, coefficients] : {std::pair{"b", &m.sellmeierB}, std::pair{"c_um2", &m.sellmeierC}})
    for (size_t i = 0; i < 3; ++i) {
      const std::string key = fmt::format("sellmeier/{}/{}", name, i);
      const double x = (*coefficients)[i];
      if (!(std::isfinite(x) && x >= 0.0))
        check.fail(key, fmt::format("must be a finite number >= 0 (got {})", check.got(key, x)));
    }
  const std::string label = m.glassLabel.empty() ? std::string("the dielectric") : m.glassLabel;
  const std::string problem = sellmeierRangeProblem(m.sellmeierB, m.sellmeierC, label, minNm, maxNm);
  if (!problem.empty()) check.fail(indexKey(check), problem);
}

void pack(const SurfaceMaterial& m, device::Material& record, SceneData& data) {
  packNoReflectance(record, data);
  record.sellmeierB = glm::vec3(float(m.sellmeierB[0]), float(m.sellmeierB[1]), float(m.sellmeierB[2]));
  record.sellmeierC = glm::vec3(float(m.sellmeierC[0]), float(m.sellmeierC[1]), float(m.sellmeierC[2]));
}

// A constant index (every C zero) does not disperse.
bool variesWithWavelength(const SurfaceMaterial& m) { return m.sellmeierC != std::array<double, 3>{0.0, 0.0, 0.0}; }

}  // namespace

double SurfaceMaterial::refractiveIndexAt(double lambdaNm) const {
  return sellmeierIndex(sellmeierB, sellmeierC, lambdaNm);
}

const MaterialTypeUnit& dielectricMaterialUnit() {
  static const MaterialTypeUnit unit{
      .type = MaterialType::Dielectric,
      .name = "dielectric",
      .keys = {"glass", "sellmeier", "ior"},
      .redirectsBeams = true,
      .needsClosedShape = true,
      .connectsToCamera = false,
      .parse = parse,
      .validate = validate,
      .pack = pack,
      .variesWithWavelength = variesWithWavelength,
  };
  return unit;
}

}  // namespace spectrace
