// Diffuse (Lambertian) surface of a given reflectance; camera connections
// start at its vertices.
#include "materials/material_shared.h"

namespace spectrace {

namespace {

namespace jf = json_fields;

void parse(const jf::Source& c, const jf::Json& v, const std::string& ptr, const SpectrumFieldReader& spectra,
           SurfaceMaterial& material) {
  jf::checkObject(c, v, ptr, {"type", "reflectance"}, "a diffuse material");
  parseReflectance(c, v, ptr, spectra, nullptr, material);
}

void validate(const SurfaceMaterial& material, double, double, const MaterialFieldCheck& check) {
  validateReflectance(material, check);
}

}  // namespace

const MaterialTypeUnit& diffuseMaterialUnit() {
  static const MaterialTypeUnit unit{
      .type = MaterialType::Diffuse,
      .name = "diffuse",
      .keys = {"reflectance"},
      .redirectsBeams = true,
      .needsClosedShape = false,
      .connectsToCamera = true,
      .parse = parse,
      .validate = validate,
      .pack = packReflectance,
      .variesWithWavelength = reflectanceVaries,
  };
  return unit;
}

}  // namespace spectrace
