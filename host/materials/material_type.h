#pragma once
// One unit per material kind: everything the host knows about a kind (its
// JSON keys, checks, device record, what it does to the shortcuts) lives in
// its own file, materials/<kind>_material.cpp, beside the kernel of the
// same stem in shaders/materials/. They are listed once, in
// host/materials/CMakeLists.txt (spectrace_unit_table), from which
// material_types.cpp builds the table.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "device_data/scene_data.h"
#include "device_shared.h"
#include "json/json_fields.h"
#include "materials/material.h"
#include "spectrum/spd.h"

namespace spectrace {

// A spectrum-valued key (a reflectance), read in every form a light's spd
// takes. The scene loader provides it: the forms and their files are its.
struct FieldSpectrum {
  Spd spd;
  std::string label;           // "D65", "csv paint.csv", ...
  std::filesystem::path file;  // the CSV file it was read from, else empty
};
class SpectrumFieldReader {
 public:
  virtual ~SpectrumFieldReader() = default;
  virtual FieldSpectrum read(const json_fields::Json& v, const std::string& ptr) const = 0;
};

// How a unit's `validate` reports a problem: throws SceneError naming the
// material's field (`key` relative to the material, e.g. "reflectance";
// "" names the material itself).
class MaterialFieldCheck {
 public:
  virtual ~MaterialFieldCheck() = default;
  [[noreturn]] virtual void fail(const std::string& key, const std::string& what) const = 0;
  // For "(got ...)": the value as the scene file wrote it when the scene came
  // from a file that has `key`, else `fallback`.
  virtual std::string got(const std::string& key, double fallback) const = 0;
  // Whether the scene file has `key` (so messages name what was written).
  virtual bool given(const std::string& key) const = 0;
};

struct MaterialTypeUnit {
  MaterialType type;
  const char* name;  // "absorber", "diffuse", ... (the JSON "type")
  // The kind's own JSON keys, besides "type".
  json_fields::Keys keys;
  // It can send a beam somewhere a straight line from its light would not
  // go; false for a kind that only takes beams away (the absorber), with
  // which every "straight from the light" shortcut stays exact.
  bool redirectsBeams;
  // It refracts into the shape, so the shape must have an inside.
  bool needsClosedShape;
  // Camera connections start at its vertices (TraceConstants::connect).
  bool connectsToCamera;

  // Reads the material object `v` at `ptr` into `material`, and refuses
  // keys that are not the kind's (types only: value ranges are `validate`'s).
  void (*parse)(const json_fields::Source& c, const json_fields::Json& v, const std::string& ptr,
                const SpectrumFieldReader& spectra, SurfaceMaterial& material);
  // The kind's semantic checks over the scene's spectrum range.
  void (*validate)(const SurfaceMaterial& material, double minNm, double maxNm, const MaterialFieldCheck& check);
  // Fills the record's parameters, appending its tables to the scene data
  // (reflectanceFirst and friends); `record.type` is set already.
  void (*pack)(const SurfaceMaterial& material, device::Material& record, SceneData& data);
  // Whether what it does to a beam depends on the beam's wavelength (colour
  // from the bins assumes it does not).
  bool (*variesWithWavelength)(const SurfaceMaterial& material);
};

const MaterialTypeUnit& materialTypeUnit(MaterialType type);
// nullptr for an unknown name.
const MaterialTypeUnit* materialTypeUnitNamed(std::string_view name);
// Every unit, in MaterialType order.
const std::vector<const MaterialTypeUnit*>& materialTypeUnits();

}  // namespace spectrace
