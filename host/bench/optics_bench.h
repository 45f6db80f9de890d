#pragma once
// The bench's "Optics" section: scenes with objects (the prism, the
// ColorChecker, a mesh of a million triangles), the camera connection
// against analog transport, the BVH against brute force; and the O(1)
// draws: emitting spheres of one primitive, 1k and 1M triangles, and a
// photometric light of a small and a large table.
//
// Their error has no closed form, so it is measured from two renders with
// different seeds, A and B: for an unbiased estimator E[(A - B)^2] is twice
// one render's variance, so
//   relMSE = sum over pixels (A - B)^2 / 2  /  sum over pixels R^2,
// with R a reference image of the same scene (one denominator for every
// variant of a scene, so FOM ratios are ratios of squared error x time).
// The two scenes matched with pbrt-v4 (scenes/bench/fom_emitter.json, a D65
// Lambertian square seen through a 25 um pinhole, and fom_lit_grey.json,
// a grey diffuse square lit by a spot) use Y instead of irradiance, over
// the square's interior only, with R the mean of A and B.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "backend/device.h"
#include "scene/scene.h"

namespace spectrace {

struct OpticsRow {
  std::string scene;    // "prism", "colorchecker", "mesh 1M"
  std::string variant;  // "connect", "analog", "bvh", "brute force"
  DeviceKind device = DeviceKind::Cpu;
  bool reference = false;  // the CPU reference (the other devices' ratios are to it)
  std::string deviceName;
  uint64_t primitives = 0;
  uint64_t beams = 0, counted = 0;
  double traceSeconds = 0.0;  // the trace loop's wall time, least of the two renders
  double relMse = 0.0;
  double fom = 0.0;           // 1 / (relMSE x traceSeconds)
  bool sameImageAsFirst = false;  // a second variant: its image equals the first's bit for bit
  double beamsPerSecond() const { return double(beams) / traceSeconds; }
};

// A sphere of about `triangles` triangles (a latitude-longitude mesh),
// closed, faces outwards.
Shape tessellatedSphere(const glm::dvec3& centre, double radius, uint64_t triangles);

// The mesh scene: a grey sphere of about `triangles` triangles (radius
// 0.3 m, 1 m before the camera) lit by a spot that just covers it, seen
// through a pinhole.
Scene opticsMeshScene(uint64_t triangles);

// An emitting sphere (radius 0.06 m, 1 W at 550 nm) 0.2 m above a 0.6 m
// bare sensor: the analytic sphere (triangles 0) or a mesh of about
// `triangles` triangles.
Scene emittingSphereScene(uint64_t triangles);
// A photometric light (an asymmetric 0-360 table in steps of cStepDeg and
// gammaStepDeg) 0.25 m above the same sensor.
Scene photometricScene(double cStepDeg, double gammaStepDeg);

struct OpticsBenchOptions {
  std::filesystem::path scenesDir;  // holds prism.json and colorchecker.json
  const std::atomic<bool>* cancel = nullptr;
  bool objects = true;  // the prism, ColorChecker and mesh rows
  bool matched = true;  // the scenes matched with pbrt-v4 (scenes/bench/fom_*)
  std::function<void(const OpticsRow&)> onRow;
};
std::vector<OpticsRow> runOpticsBench(const std::vector<DeviceSpec>& devices, const OpticsBenchOptions& options);

}  // namespace spectrace
