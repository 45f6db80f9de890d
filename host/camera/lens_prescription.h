#pragma once
// A lens system's prescription (the lens camera model,
// camera/lens_system_camera.cpp): surfaces on one axis from the object side
// to the sensor, each with its curvature radius, the distance to the next
// surface (the last: to the sensor), its semi-aperture and the medium
// behind it. Its paraxial optics in double: the system matrix, the focal
// length, and the lens-to-sensor distance that focuses a given distance.
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace spectrace {

// What lies behind a surface: air (index 1) or a glass by its Sellmeier
// coefficients (b, c in um^2; a constant index n is b = {n^2 - 1, 0, 0},
// c = 0).
struct LensMedium {
  std::string label = "air";  // "air", a catalogue name, "nd 1.5168, vd 64.17", "index 1.67"
  std::array<double, 3> b{0.0, 0.0, 0.0};
  std::array<double, 3> cUm2{0.0, 0.0, 0.0};

  bool isAir() const { return b == std::array<double, 3>{0.0, 0.0, 0.0}; }
  bool disperses() const { return cUm2 != std::array<double, 3>{0.0, 0.0, 0.0}; }
  double indexAt(double lambdaNm) const;
};

struct LensSurface {
  double radiusM = 0.0;  // signed: > 0 when the centre of curvature lies towards the sensor; 0: flat
  double thicknessM = 0.0;
  double semiApertureM = 0.0;
  LensMedium medium;
  bool stop = false;
  // Its sag at height r: how far the surface lies behind its vertex
  // (towards the sensor; negative when it curves towards the object).
  double sagAt(double r) const;
};

struct LensPrescription {
  std::vector<LensSurface> surfaces;
  // Each surface's vertex in the camera frame (the sensor at z = 0, the
  // object side at z > 0).
  std::vector<double> vertexZ() const;
  // The foremost point of the first surface (its vertex, or its rim when it
  // curves towards the object): where the barrel opens.
  double frontZ() const;
  double widestSemiApertureM() const;
  bool disperses() const;
};

// The paraxial system matrix from the first surface to the last, at
// lambdaNm, on (height, index x angle): refraction [1 0; -P 1] with
// P = (n' - n) / R, transfer [1 t/n; 0 1].
struct ParaxialMatrix {
  double a = 1.0, b = 0.0, c = 0.0, d = 1.0;
};
ParaxialMatrix paraxialMatrix(const LensPrescription& lens, double lambdaNm);
// The same from the first surface through surface `last` (its refraction
// included, not the gap after it).
ParaxialMatrix paraxialMatrixThrough(const LensPrescription& lens, double lambdaNm, size_t last);

// Its effective focal length, -1 / c (nullopt for an afocal system), and
// where its principal planes lie, each from the vertex of its own end
// surface along the axis towards the sensor.
struct ParaxialCardinal {
  double focalLengthM;
  double frontPrincipalM;  // from the first vertex
  double backPrincipalM;   // from the last vertex
};
std::optional<ParaxialCardinal> paraxialCardinal(const LensPrescription& lens, double lambdaNm);

// The last surface's distance to the sensor that puts an object at
// `focusDistanceM` from the sensor in paraxial focus at lambdaNm (the
// nearer of the two solutions: the sensor near the back focal plane);
// nullopt when no real image can be focused at that distance (the object
// at or inside four focal lengths, the least object-to-image distance, or
// a diverging system).
std::optional<double> focusedBackThicknessM(const LensPrescription& lens, double focusDistanceM, double lambdaNm);

// The working f-number for an object at infinity, f / (2 x the entrance
// pupil's radius): a ray parallel to the axis at height y meets the stop at
// height a y (a of the matrix through the stop), so the entrance pupil's
// radius is the stop's semi-aperture over |a|. nullopt without one stop, a
// positive focal length, or with a = 0.
std::optional<double> fNumber(const LensPrescription& lens, double lambdaNm);

}  // namespace spectrace
