#pragma once
// Inside the scene module: reading a light's "spd" field.
#include <string>

#include "json/json_fields.h"
#include "scene/scene.h"

namespace spectrace {

// Resolves the spd value `v` at `ptr` into light.spd and light.spdLabel.
void parseSpd(const json_fields::Source& c, const json_fields::Json& v, const std::string& ptr,
              const SpectrumRange& range, Light& light);

}  // namespace spectrace
