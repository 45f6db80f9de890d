#pragma once
// A surface's material as a scene describes it. What each kind means,
// reads and packs is in its unit (materials/material_type.h).
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "device_shared.h"

namespace spectrace {

// MaterialType is defined in device_shared.h, numbered as the kernel
// numbers it.

// "absorber", "diffuse", ... (the unit's name).
const char* materialTypeName(MaterialType type);

struct SurfaceMaterial {
  MaterialType type = MaterialType::Absorber;
  // diffuse, mirror: reflectance in [0, 1], linear between the nodes and
  // holding its end values outside them (a constant is one node).
  std::vector<double> reflectanceNm;
  std::vector<double> reflectance;
  std::string reflectanceLabel;  // "0.8", "dark_skin", "paint.csv", ...
  std::filesystem::path reflectanceFile;  // the CSV it was read from (an input: never an output); else empty
  // dielectric: n^2 = 1 + sum B_i l^2 / (l^2 - C_i), l in micrometres; a
  // constant ior n is B = {n^2 - 1, 0, 0}, C = {0, 0, 0}.
  std::array<double, 3> sellmeierB{};
  std::array<double, 3> sellmeierC{};
  std::string glassLabel;  // "N-BK7", "sellmeier", "ior 1.5"

  // The reflectance at a wavelength (diffuse, mirror), as the kernel
  // evaluates its table: linear, held constant outside the nodes.
  double reflectanceAt(double lambdaNm) const;
  // The refractive index at a wavelength (dielectric).
  double refractiveIndexAt(double lambdaNm) const;
};

}  // namespace spectrace
