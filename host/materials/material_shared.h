#pragma once
// What more than one material unit shares: the reflectance (diffuse,
// mirror) read, checked and packed as a table, and the record of a kind
// with no table.
#include <string>
#include <vector>

#include "materials/material_type.h"

namespace spectrace {

// Reads the "reflectance" of the material `v` at `ptr`; absent, a mirror
// takes `fallback` (a perfect one) where a diffuse material, with no
// fallback, refuses it.
void parseReflectance(const json_fields::Source& c, const json_fields::Json& v, const std::string& ptr,
                      const SpectrumFieldReader& spectra, const double* fallback, SurfaceMaterial& material);
void validateReflectance(const SurfaceMaterial& material, const MaterialFieldCheck& check);
// Appends the reflectance table to the scene data and points the record at it.
void packReflectance(const SurfaceMaterial& material, device::Material& record, SceneData& data);
// Whether the reflectance differs between some of its nodes.
bool reflectanceVaries(const SurfaceMaterial& material);
// A kind without a table still points its record at one word (0), so every
// record's table offset is a word of the scene data.
void packNoReflectance(device::Material& record, SceneData& data);

// The reflectance table the kernel interpolates (Material's fields): nodes
// on a uniform grid over the given nodes, fine enough that the grid holds
// every node when the nodes are evenly spaced (tabulated data usually is).
struct ReflectanceTable {
  float lambda0 = 0.0f;
  float nodesPerNm = 0.0f;
  std::vector<float> values;
};
ReflectanceTable reflectanceTable(const SurfaceMaterial& material);

}  // namespace spectrace
