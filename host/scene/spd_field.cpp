// The "spd" field of a light: a CIE illuminant name, or one of the object
// forms (blackbody, CSV file, inline table, line). The spectrum is resolved
// here, over the scene's spectrum range; whether it emits inside that range
// is validateScene's rule. Surfaces' reflectances take the same forms
// (object_field.cpp).
#include "scene/spd_field.h"

#include <cmath>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "colour/colour.h"
#include "json/input_file.h"
#include "scene/scene_limits.h"

namespace spectrace {

namespace fs = std::filesystem;
namespace jf = json_fields;
using jf::Json;
using jf::Keys;
using jf::checkObject;
using jf::child;
using jf::describe;
using jf::find;
using jf::fmtNum;
using jf::getNumber;
using jf::getNumberArray;
using jf::getPositive;
using jf::getString;
using jf::joinKeys;
using jf::jsonQuoted;
using jf::require;
using jf::suggestion;

namespace {

// Wraps a call into spd.h: SpdError (and anything else it throws) becomes a
// SceneError at `ptr`.
template <class F>
Spd callSpd(const jf::Source& c, const std::string& ptr, F&& f) {
  try {
    return f();
  } catch (const SpdError& e) {
    c.fail(ptr, e.what());
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    c.fail(ptr, fmt::format("cannot build the spectrum: {}", e.what()));
  }
}

// ∫ȳ·S / ∫S of a table that holds the whole emission (spdToXyz integrates
// the product of the two piecewise-linear functions exactly; a line: ȳ at
// its wavelength).
double tableLuminousFraction(const Spd& spd) {
  return spd.fullIntegral > 0.0 ? spdToXyz(spd, cie1931Observer())[1] / spd.fullIntegral : 0.0;
}

}  // namespace

double luminousFraction(const Spd& spd, std::optional<double> blackbodyK) {
  if (!blackbodyK) return tableLuminousFraction(spd);
  // A table over the whole of ȳ's range instead (to < 1e-6, as every
  // blackbody table), over the exact total σT⁴/π. 0 when the radiance
  // underflows there (a body too cold to glow).
  const Observer& v = cie1931Observer();
  try {
    return tableLuminousFraction(makeBlackbodySpd(*blackbodyK, v.lambdaNm.front(), v.lambdaNm.back()));
  } catch (const SpdError&) {
    return 0.0;
  }
}

ResolvedSpd resolveSpd(const jf::Source& c, const Json& v, const std::string& p, const SpectrumRange& range) {
  ResolvedSpd out;
  static const Keys kForms = {"blackbody_k", "csv", "table", "lambda_nm", "line_nm"};
  static const char* kFormsHelp =
      "a CIE illuminant name such as \"D65\", or an object with one of: {\"blackbody_k\": K}, {\"csv\": \"file.csv\"}, "
      "{\"table\": [[nm, value], ...]}, {\"lambda_nm\": [...], \"value\": [...]}, {\"line_nm\": nm}";
  if (v.is_string()) {
    std::string name = v.get<std::string>();
    auto spd = callSpd(c, p, [&]() -> Spd {
      auto s = cieIlluminant(name);
      if (!s) {
        auto names = cieIlluminantNames();
        std::vector<std::string_view> views(names.begin(), names.end());
        std::string hint = suggestion(name, views);  // case-insensitive: "d65" suggests "D65"
        std::string list;
        for (auto& n : names) list += (list.empty() ? "" : ", ") + n;
        c.fail(p, fmt::format("unknown CIE illuminant {}{} (known: {})", jsonQuoted(name), hint, list));
      }
      return *s;
    });
    out.spd = std::move(spd);
    out.label = name;
  } else if (v.is_object()) {
    std::vector<std::string_view> present;
    for (auto f : kForms)
      if (find(v, std::string(f))) present.push_back(f);
    if (present.empty() && find(v, "value")) present.push_back("lambda_nm");
    if (present.empty()) {
      // Unknown keys first: {"blackbdy_k": ...} should name the typo.
      Keys all = {"blackbody_k", "csv", "column", "table", "lambda_nm", "value", "line_nm", "fwhm_nm"};
      checkObject(c, v, p, all, "spd");
      c.fail(p, fmt::format("must be {} (got an object with none of these)", kFormsHelp));
    }
    if (present.size() > 1)
      c.fail(p, fmt::format("ambiguous spectrum: has both {} and {}; use exactly one of {}", jsonQuoted(present[0]),
                            jsonQuoted(present[1]), joinKeys(kForms)));
    std::string_view form = present[0];
    if (form == "blackbody_k") {
      checkObject(c, v, p, {"blackbody_k"}, "a blackbody spd");
      std::string kp = child(p, "blackbody_k");
      double kelvin = getPositive(c, v.at("blackbody_k"), kp);
      if (kelvin > kMaxKelvin)
        c.fail(kp, fmt::format("must be a temperature in kelvin, > 0 and <= {:g} (got {})", kMaxKelvin,
                               describe(v.at("blackbody_k"))));
      out.spd = callSpd(c, kp, [&] { return makeBlackbodySpd(kelvin, range.minNm, range.maxNm); });
      out.label = fmt::format("blackbody {} K", fmtNum(kelvin));
      out.blackbodyK = kelvin;
    } else if (form == "csv") {
      checkObject(c, v, p, {"csv", "column"}, "a csv spd");
      std::string cp = child(p, "csv");
      std::string rel = getString(c, v.at("csv"), cp);
      std::optional<std::string> column;
      if (auto* x = find(v, "column")) column = getString(c, *x, child(p, "column"));
      fs::path path(rel);
      fs::path resolved = c.resolve(path);
      std::error_code ec;
      // A scene developed from a state reads its CSVs from the state, not the disk.
      const bool onDisk = !BundledInputFiles::active();
      if (onDisk && !fs::exists(resolved, ec))
        c.fail(cp, fmt::format("SPD file not found: {}{}", jsonQuoted(rel),
                               path.is_absolute() ? std::string()
                                                  : fmt::format(" (looked for {}, relative to the scene file's folder)",
                                                                jsonQuoted(fs::absolute(resolved, ec).string()))));
      if (onDisk && !fs::is_regular_file(resolved, ec)) c.fail(cp, fmt::format("{} is not a regular file", jsonQuoted(resolved.string())));
      out.spd = callSpd(c, cp, [&] { return loadCsvSpd(resolved, column); });
      out.label = "csv " + rel + (column ? " column " + *column : "");
      out.file = resolved;
    } else if (form == "table") {
      checkObject(c, v, p, {"table"}, "a table spd");
      std::string tp = child(p, "table");
      const Json& t = v.at("table");
      if (!t.is_array() || t.empty())
        c.fail(tp, fmt::format("must be a non-empty array of [wavelength_nm, value] pairs (got {})", describe(t)));
      if (t.size() > kMaxSpdPoints)
        c.fail(tp, fmt::format("has {} points; a spectrum has at most {}", t.size(), kMaxSpdPoints));
      std::vector<double> lambda, value;
      for (size_t i = 0; i < t.size(); ++i) {
        std::string rp = child(tp, i);
        if (!t[i].is_array() || t[i].size() != 2)
          c.fail(rp, fmt::format("must be a [wavelength_nm, value] pair (got {})", describe(t[i])));
        lambda.push_back(getNumber(c, t[i][0], child(rp, size_t(0))));
        value.push_back(getNumber(c, t[i][1], child(rp, size_t(1))));
      }
      out.spd = callSpd(c, tp, [&] { return makeTabulatedSpd(lambda, value); });
      out.label = fmt::format("inline table ({} points)", t.size());
    } else if (form == "lambda_nm") {
      checkObject(c, v, p, {"lambda_nm", "value"}, "a tabulated spd");
      std::vector<double> lambda = getNumberArray(c, require(c, v, p, "lambda_nm"), child(p, "lambda_nm"));
      std::vector<double> value = getNumberArray(c, require(c, v, p, "value"), child(p, "value"));
      if (lambda.size() != value.size())
        c.fail(child(p, "value"), fmt::format("has {} entries but lambda_nm has {}; they must be the same length",
                                              value.size(), lambda.size()));
      size_t n = lambda.size();
      out.spd = callSpd(c, p, [&] { return makeTabulatedSpd(std::move(lambda), std::move(value)); });
      out.label = fmt::format("inline table ({} points)", n);
    } else {  // line_nm
      checkObject(c, v, p, {"line_nm", "fwhm_nm"}, "a line spd");
      double center = getPositive(c, v.at("line_nm"), child(p, "line_nm"));
      std::optional<double> fwhm;
      if (auto* x = find(v, "fwhm_nm")) fwhm = getPositive(c, *x, child(p, "fwhm_nm"));
      out.spd = callSpd(c, p, [&] { return makeLineSpd(center, fwhm); });
      out.label = fmt::format("line {} nm", fmtNum(center));
      if (fwhm) out.label += fmt::format(" (FWHM {} nm)", fmtNum(*fwhm));
    }
  } else {
    c.fail(p, fmt::format("must be {} (got {})", kFormsHelp, describe(v)));
  }
  return out;
}

std::optional<double> parseSpd(const jf::Source& c, const Json& v, const std::string& p, const SpectrumRange& range,
                               Light& light) {
  ResolvedSpd resolved = resolveSpd(c, v, p, range);
  light.spd = std::move(resolved.spd);
  light.spdLabel = std::move(resolved.label);
  light.spdFile = std::move(resolved.file);
  return resolved.blackbodyK;
}

// The light's spd and its power: power_w (radiant flux, W) or power_lm
// (luminous flux, lm), one of them. Lumens become watts through the spd's
// luminous efficacy, 683 lm/W x ∫V·S / ∫S over the whole emission.
void parseLightPower(const jf::Source& c, const jf::Json& v, const std::string& p, const SpectrumRange& range,
                     Light& light) {
  // null stands for absent, so `--set /lights/0/power_w=null` can switch a
  // light from watts to lumens.
  const auto given = [&](const char* key) {
    const jf::Json* x = jf::find(v, key);
    return x && !x->is_null() ? x : nullptr;
  };
  const jf::Json* watts = given("power_w");
  const jf::Json* lumens = given("power_lm");
  if (watts && lumens)
    c.fail(jf::child(p, "power_lm"), "a light's power is power_w (watts) or power_lm (lumens), not both");
  // A luminaire file gives its flux in lumens when the scene gives neither.
  const bool fileLumens = !watts && !lumens && light.photometry;
  if (!lumens && !fileLumens)
    light.powerW = jf::getNonNegative(
        c, jf::require(c, v, p, "power_w", " (radiant flux in watts; or power_lm, luminous flux in lumens)"),
        jf::child(p, "power_w"));
  const std::optional<double> blackbodyK = parseSpd(c, jf::require(c, v, p, "spd"), jf::child(p, "spd"), range, light);
  if (!lumens && !fileLumens) return;
  const std::string lp = jf::child(p, lumens ? "power_lm" : "file");
  light.powerLm = lumens ? jf::getNonNegative(c, *lumens, lp) : light.photometry->tableLumens();
  light.powerW = 0.0;
  if (light.powerLm == 0.0) return;
  const double fraction = luminousFraction(light.spd, blackbodyK);
  if (!(fraction > 0.0))
    c.fail(lp, fmt::format("the spd ({}) has no power where the eye sees (V(λ) > 0, 360-830 nm), so lumens cannot set "
                           "its power; give power_w",
                           light.spdLabel));
  light.powerW = light.powerLm / (kLumensPerWatt * fraction);
  if (!std::isfinite(light.powerW))
    c.fail(lp, fmt::format("{:g} lm of this spd ({}, {:g} lm/W) is more watts than a double holds", light.powerLm,
                           light.spdLabel, kLumensPerWatt * fraction));
}

}  // namespace spectrace
