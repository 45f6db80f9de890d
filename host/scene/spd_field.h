#pragma once
// Inside the scene module: reading a spectrum field (a light's "spd", an
// object's "reflectance").
#include <filesystem>
#include <optional>
#include <string>

#include "json/json_fields.h"
#include "scene/scene.h"

namespace spectrace {

// A spectrum read from a field, before it is given to a light or a surface.
struct ResolvedSpd {
  Spd spd;
  std::string label;           // "D65", "blackbody 2700 K", "csv lamp.csv", ...
  std::filesystem::path file;  // the CSV file it was read from, else empty
  // A blackbody's temperature: its table is only a window onto the
  // emission (the scene's range), which luminousFraction must look past.
  std::optional<double> blackbodyK;
};

// Resolves the spd value `v` at `ptr` (a CIE illuminant name or one of the
// object forms), tabulated over `range` where the form needs one (blackbody).
ResolvedSpd resolveSpd(const json_fields::Source& c, const json_fields::Json& v, const std::string& ptr,
                       const SpectrumRange& range);

// Resolves the spd value `v` at `ptr` into light.spd, light.spdLabel and
// light.spdFile; returns its blackbodyK.
std::optional<double> parseSpd(const json_fields::Source& c, const json_fields::Json& v, const std::string& ptr,
                               const SpectrumRange& range, Light& light);

// Reads an emitter's spd and its power (a light, or an object's
// "emission", the object `v` at `p`): power_w (radiant flux, W) or power_lm
// (luminous flux, lm), one of them, or for a luminaire neither (its file's
// lumens). Lumens become watts through the spd's luminous efficacy.
void parseLightPower(const json_fields::Source& c, const json_fields::Json& v, const std::string& p,
                     const SpectrumRange& range, Light& light);

// ∫V·S / ∫S over the whole emission of `spd` (of the blackbody at
// blackbodyK, whose table covers only the scene's range), V the CIE
// photopic curve: the 1931 ȳ, whichever observer the scene names, since
// lumens are defined by it. Times 683 lm/W it is the luminous efficacy of
// the radiation, which turns a light's power_lm into watts. 0 when nothing
// lies where V > 0. Computed when asked: only power_lm needs it.
double luminousFraction(const Spd& spd, std::optional<double> blackbodyK);

}  // namespace spectrace
