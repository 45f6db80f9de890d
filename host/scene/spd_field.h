#pragma once
// Inside the scene module: reading a spectrum field (a light's "spd", an
// object's "reflectance").
#include <filesystem>
#include <string>

#include "json/json_fields.h"
#include "scene/scene.h"

namespace spectrace {

// A spectrum read from a field, before it is given to a light or a surface.
struct ResolvedSpd {
  Spd spd;
  std::string label;           // "D65", "blackbody 2700 K", "csv lamp.csv", ...
  std::filesystem::path file;  // the CSV file it was read from, else empty
  // ∫V·S / ∫S over the whole emission, V the CIE photopic curve (the 1931
  // ȳ, whichever observer the scene names: lumens are defined by it). Times
  // 683 lm/W it is the luminous efficacy of the radiation, which turns a
  // light's power_lm into watts. 0 when nothing lies where V > 0.
  double luminousFraction = 0.0;
};

// Resolves the spd value `v` at `ptr` (a CIE illuminant name or one of the
// object forms), tabulated over `range` where the form needs one (blackbody).
ResolvedSpd resolveSpd(const json_fields::Source& c, const json_fields::Json& v, const std::string& ptr,
                       const SpectrumRange& range);

// Resolves the spd value `v` at `ptr` into light.spd, light.spdLabel and
// light.spdFile; returns its luminousFraction.
double parseSpd(const json_fields::Source& c, const json_fields::Json& v, const std::string& ptr,
                const SpectrumRange& range, Light& light);

}  // namespace spectrace
