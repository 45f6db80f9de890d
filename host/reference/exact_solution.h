#pragma once
// Exact per-pixel answers for simple scenes, computed independently of the
// renderer: closed forms, or deterministic Gauss–Legendre quadrature of
// closed-form point irradiances, in double precision. The renderer's
// histogram converges to these as the beam count grows, so they turn a
// render into a statistical test (see scenes/reference/README.md).
//
// Coordinates are the camera frame's (host/camera/camera_frame.h): x = image
// right, y = image up, z = viewing direction, sensor centred at the origin
// in the plane z = 0. Lengths in metres, irradiance in W/m², Y in lux.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "colour/colour.h"
#include "scene/scene.h"

namespace spectrace {

struct ExactImage {
  int width = 0, height = 0;  // pixels: columns, rows; index row * width + column, row 0 at the top
  // Mean irradiance of each pixel, summed over the spectrum range (W/m²),
  // as the renderer's `irradiance.E`.
  std::vector<double> irradiance;
  // CIE XYZ (Y in lux): 683 · E · ∫S·cmf / ∫S over the range, the CMF taken
  // at each wavelength (what the exact-colour resolve converges to).
  std::vector<std::array<double, 3>> xyz;
  // The same light through the renderer's bin-averaged CMFs
  // (binAveragedCmf): 683 · Σ_b E_b · w̄_b, E_b the irradiance in bin b.
  std::vector<std::array<double, 3>> xyzBinned;
  // 1 where the value is exact; 0 where no closed form applies (pinhole
  // pixels within one pixel of the blurred edge of a rect's image). There
  // the value is still a quadrature estimate (within ~1e-6 of the image's
  // peak), fine for hit fractions and pictures, not for tests.
  std::vector<uint8_t> valid;
  double tracedPowerW = 0.0;  // Σ power_w × in-range share, as CompiledScene::tracedPowerW
  // Expected share of all emitted beams that are counted:
  // Σ_pixels E · A_pixel / tracedPowerW (uses the estimates where !valid).
  double hitFraction = 0.0;
  std::string configuration;  // what was recognised, e.g. "disk light over a bare sensor"

  size_t pixelCount() const { return size_t(width) * size_t(height); }
  size_t validCount() const;
};

struct ExactOptions {
  // Gauss–Legendre nodes per pixel side where a pixel mean needs quadrature
  // (disk and rect lights, pinhole). 16 is converged to < 1e-12 relative
  // for the reference scenes; the tests compare 16 with 32.
  int quadratureNodes = 16;
};

// The exact image of `scene`, or nullopt when some light (with power in the
// spectrum range) is not in a recognised configuration. Recognised:
//  bare sensor:  point lights in front of the sensor; disk and rect lights
//                parallel to the sensor and facing it; lasers travelling
//                along -z (any footprint, exact partial pixels);
//                photometric lights; emitting objects: a rect or disk
//                parallel to the sensor and facing it, a flat emitter of
//                rects or triangles at any tilt above the sensor's plane
//                with the sensor before one face, a sphere above it;
//  pinhole:      rect lights, and emitting objects of one rect, parallel to
//                the sensor, facing it, beyond the aperture.
// Lights with no power in range, or that can never reach the sensor (behind
// it, facing away), contribute zero. Several lights add.
std::optional<ExactImage> exactSolution(const Scene& scene, const ExactOptions& options = {});

// ------------------------------------------------------------------ building blocks

// A pixel's rectangle [x1, x2] x [y1, y2] in the sensor plane (camera frame).
// Bare sensor: column along +x, rows down from +y. Pinhole: the image is
// flipped upright, so column c covers x from w/2 - (c+1)·pw to w/2 - c·pw and
// row r covers y from -h/2 + r·ph to -h/2 + (r+1)·ph.
struct SensorRect {
  double x1, x2, y1, y2;
  double area() const { return (x2 - x1) * (y2 - y1); }
};
SensorRect pixelRect(const Camera& camera, int column, int row);

// Solid angle of the rectangle [x1,x2] x [y1,y2] in the plane z = 0, seen
// from (x0, y0, d), d > 0: Σ corners ± atan(a b / (d sqrt(a² + b² + d²))).
double rectangleSolidAngle(double x1, double x2, double y1, double y2, double x0, double y0, double d);

// View factor F = E / (π L) from a point to a parallel disk of radius R at
// height h whose axis passes at distance rho from the point (the point's
// surface faces the disk):
//   F = ½ (1 − (h² + ρ² − R²) / sqrt((h² + ρ² + R²)² − 4 ρ² R²)),
// on axis R² / (h² + R²). Evaluated without cancellation.
double parallelDiskViewFactor(double h, double radius, double rho);
// 1 − F for the same geometry, without cancellation: the furnace shortfall.
// A disk of radiance L filling most of the hemisphere gives E = πL (1 − s);
// on axis s = h² / (h² + R²) exactly.
double furnaceShortfall(double h, double radius, double rho = 0.0);

// View factor from a point to a parallel rectangle [x1,x2] x [y1,y2] at
// height h (coordinates relative to the point, in the rectangle's axes):
// Σ corners ± (1/2π)[a/√(a²+h²) atan(b/√(a²+h²)) + b/√(b²+h²) atan(a/√(b²+h²))].
double parallelRectViewFactor(double x1, double x2, double y1, double y2, double h);

// Area of the intersection of the disk (cx, cy, r) and the rectangle
// [x1,x2] x [y1,y2], in closed form.
double diskRectangleOverlap(double cx, double cy, double r, double x1, double x2, double y1, double y2);

// ∫ over a convex polygon ∩ disk of h² / (x² + y² + h²)² dx dy, the point
// (0, 0, -h) looking at the plane: by Green's theorem the boundary integral
// ½ ∮ (x dy − y dx) / (x² + y² + h²), with Gauss–Legendre on each edge piece
// and arc piece (machine precision). The polygon's vertices may be in
// either order. Divided by π it is the view factor of that region.
double polygonDiskKernelIntegral(const std::vector<std::array<double, 2>>& polygon, double diskX, double diskY,
                                 double diskRadius, double h);

// Gauss–Legendre nodes and weights on [-1, 1] (Newton on P_n; cached).
struct GaussLegendreRule {
  std::vector<double> node, weight;
};
const GaussLegendreRule& gaussLegendre(int n);

// Traced power of one light: power_w × in-range share (as compile/compile_scene.cpp).
double tracedPower(const Light& light, const SpectrumRange& range);
// 683 · ∫S·cmf / ∫S over the range (XYZ per W/m²), CMF at each wavelength;
// zeros when the light has nothing in range.
std::array<double, 3> luminousXyzPerWatt(const Spd& spd, const SpectrumRange& range, const Observer& observer);
// The same with the bin-averaged CMFs of the range's bins.
std::array<double, 3> binnedXyzPerWatt(const Spd& spd, const SpectrumRange& range, const Observer& observer);

}  // namespace spectrace
