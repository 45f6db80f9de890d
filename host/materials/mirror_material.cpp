// Mirror: specular reflection with a given reflectance, perfect (1) when
// the scene gives none.
#include "materials/material_shared.h"

namespace spectrace {

namespace {

namespace jf = json_fields;

void parse(const jf::Source& c, const jf::Json& v, const std::string& ptr, const SpectrumFieldReader& spectra,
           SurfaceMaterial& material) {
  jf::checkObject(c, v, ptr, {"type", "reflectance"}, "a mirror material");
  const double perfect = 1.0;
  parseReflectance(c, v, ptr, spectra, &perfect, material);
}

void validate(const SurfaceMaterial& material, double, double, const MaterialFieldCheck& check) {
  validateReflectance(material, check);
}

}  // namespace

const MaterialTypeUnit& mirrorMaterialUnit() {
  static const MaterialTypeUnit unit{
      .type = MaterialType::Mirror,
      .name = "mirror",
      .keys = {"reflectance"},
      .redirectsBeams = true,
      .needsClosedShape = false,
      .connectsToCamera = false,
      .parse = parse,
      .validate = validate,
      .pack = packReflectance,
      .variesWithWavelength = reflectanceVaries,
  };
  return unit;
}

}  // namespace spectrace
