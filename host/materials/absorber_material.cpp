// Absorber: takes every beam that meets it (the kernel ends the beam at it).
#include "materials/material_shared.h"

namespace spectrace {

namespace {

namespace jf = json_fields;

void parse(const jf::Source& c, const jf::Json& v, const std::string& ptr, const SpectrumFieldReader&,
           SurfaceMaterial&) {
  jf::checkObject(c, v, ptr, {"type"}, "an absorber material");
}

void validate(const SurfaceMaterial&, double, double, const MaterialFieldCheck&) {}

void pack(const SurfaceMaterial&, device::Material& record, SceneData& data) { packNoReflectance(record, data); }

bool variesWithWavelength(const SurfaceMaterial&) { return false; }

}  // namespace

const MaterialTypeUnit& absorberMaterialUnit() {
  static const MaterialTypeUnit unit{
      .type = MaterialType::Absorber,
      .name = "absorber",
      .keys = {},
      .redirectsBeams = false,
      .needsClosedShape = false,
      .connectsToCamera = false,
      .parse = parse,
      .validate = validate,
      .pack = pack,
      .variesWithWavelength = variesWithWavelength,
  };
  return unit;
}

}  // namespace spectrace
