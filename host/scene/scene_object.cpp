#include "scene/scene_object.h"

#include <algorithm>

#include "spectrum/glass.h"

namespace spectrace {

const char* shapeTypeName(ShapeType type) {
  switch (type) {
    case ShapeType::Rect: return "rect";
    case ShapeType::Disk: return "disk";
    case ShapeType::Sphere: return "sphere";
    case ShapeType::Mesh: return "mesh";
  }
  return "unknown";
}

const char* materialTypeName(MaterialType type) {
  switch (type) {
    case MaterialType::Absorber: return "absorber";
    case MaterialType::Diffuse: return "diffuse";
    case MaterialType::Mirror: return "mirror";
    case MaterialType::Dielectric: return "dielectric";
  }
  return "unknown";
}

double SurfaceMaterial::reflectanceAt(double lambdaNm) const {
  const size_t n = std::min(reflectanceNm.size(), reflectance.size());
  if (n == 0) return 0.0;
  if (!(lambdaNm > reflectanceNm.front())) return reflectance.front();
  if (!(lambdaNm < reflectanceNm[n - 1])) return reflectance[n - 1];
  // First node above lambdaNm; the one before is at or below it.
  const size_t i = size_t(std::upper_bound(reflectanceNm.begin(), reflectanceNm.begin() + n, lambdaNm) -
                          reflectanceNm.begin());
  const double x0 = reflectanceNm[i - 1], x1 = reflectanceNm[i];
  const double t = (lambdaNm - x0) / (x1 - x0);
  return reflectance[i - 1] + t * (reflectance[i] - reflectance[i - 1]);
}

double SurfaceMaterial::refractiveIndexAt(double lambdaNm) const {
  return sellmeierIndex(sellmeierB, sellmeierC, lambdaNm);
}

}  // namespace spectrace
