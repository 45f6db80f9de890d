#include "lights/trace_plan.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "camera/camera_frame.h"
#include "kernel/beam_kernel.h"
#include "colour/colour.h"
#include "spectrum/wavelength_sampler.h"

namespace spectrace {
namespace {

glm::vec3 toFloat(const glm::dvec3& v) { return glm::vec3(v); }

// Any unit vector perpendicular to `n` (Duff et al. 2017, branchless ONB).
glm::dvec3 perpendicular(const glm::dvec3& n) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  return {1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x};
}

// Why a light (in the camera frame) can never put a beam on the sensor, or
// "" when it might. Counted beams start beyond the plane z = D (the sensor,
// or the aperture of a pinhole camera) and travel towards -z; the test is
// conservative: it only rejects what provably contributes nothing.
std::string unreachableBecause(const Light& light, const glm::dvec3& position, const glm::dvec3& axis,
                               const glm::dvec3& tangent, const glm::dvec3& bitangent, const Camera& camera) {
  const double planeZ = camera.pinhole ? camera.pinhole->distanceM : 0.0;
  const char* plane = camera.pinhole ? "the pinhole's aperture plane" : "the sensor plane";
  // Largest z any emission point reaches.
  double extent = 0.0;
  switch (light.type) {
    case LightType::Disk:
    case LightType::Laser: extent = light.radiusM * std::sqrt(std::max(0.0, 1.0 - axis.z * axis.z)); break;
    case LightType::Rect: extent = 0.5 * (light.sizeM.x * std::abs(tangent.z) + light.sizeM.y * std::abs(bitangent.z)); break;
    default: break;
  }
  if (!(position.z + extent > planeZ)) return fmt::format("it lies behind {}", plane);
  switch (light.type) {
    case LightType::Spot: {
      // Some direction in the cone points towards -z iff the angle between
      // the axis and -z is below 90 degrees plus the half angle.
      const double angle = std::acos(std::clamp(-axis.z, -1.0, 1.0));
      if (!(angle < M_PI / 2 + light.coneHalfAngleDeg * M_PI / 180.0)) return "its cone points away from the camera";
      break;
    }
    case LightType::Disk:
    case LightType::Rect:
      if (!(axis.z < 1.0)) return "it faces away from the camera";
      break;
    case LightType::Laser: {
      if (!(axis.z < 0.0)) return "its beam points away from the camera";
      // The beam's footprint in the plane z = planeZ: the disk's centre moved
      // along the axis, inside a circle of radius R / |axis.z| (the
      // ellipse's semi-major axis).
      const double t = (position.z - planeZ) / -axis.z;
      const glm::dvec2 centre(position.x + t * axis.x, position.y + t * axis.y);
      const double reach = light.radiusM / -axis.z;
      if (camera.pinhole) {
        if (!(glm::length(centre) < reach + camera.pinhole->radiusM)) return "its beam misses the pinhole";
      } else {
        const glm::dvec2 half(0.5 * camera.sensorWidthM, 0.5 * camera.sensorHeightM);
        const glm::dvec2 outside = glm::max(glm::abs(centre) - half, glm::dvec2(0.0));
        if (!(glm::length(outside) < reach)) return "its beam misses the sensor";
      }
      break;
    }
    case LightType::Point: break;
  }
  return "";
}

// Aimed sampling. Every counted beam passes through the target sphere: the
// pinhole's disk, or the bare sensor (its half diagonal). A light whose
// beams can be drawn only towards that sphere gets aimed = 1 and these
// parameters; each beam's weight is then (emission density) / (sampling
// density), and the light's largest weight w_max is folded into its
// selection probability (power x w_max), so the shader's weight ratio,
// weight / w_max, lies in [0, 1]:
// - point: uniform in the cone of half angle a holding the sphere, with
//   h = 1 - cos a: weight = (1 / 4 pi) / (1 / 2 pi h) = h / 2, for every beam;
// - spot (cone h_s = param0), when h < h_s: weight h / h_s inside the spot's
//   cone, 0 outside;
// - laser: origins uniform over the disk of radius rho around the target's
//   projection along the beam, when rho < R: weight rho^2 / R^2 inside the
//   laser's cross-section, 0 outside;
// - disk, rect: per origin, uniform in the cone holding the sphere (h from
//   that origin) when 2h < 1: weight cos(theta) / pi / (1 / 2 pi h) =
//   2 h cos(theta); w_max bounds 2h over the emitter from its closest point.
// Cones are widened by SPECTRACE_AIM_SLACK (beam_math.h) so float rounding
// cannot leave a countable direction outside them, and the values the shader
// samples with are the float values the weights are computed from.
struct AimTarget {
  glm::dvec3 centre;
  double radius;
};

AimTarget aimTarget(const Camera& camera) {
  if (camera.pinhole) return {{0.0, 0.0, camera.pinhole->distanceM}, camera.pinhole->radiusM};
  return {{0.0, 0.0, 0.0}, 0.5 * std::hypot(camera.sensorWidthM, camera.sensorHeightM)};
}

// 1 - cos(a) from sin(a) = s <= 1, without cancellation.
double oneMinusCosFromSin(double s) { return s * s / (1.0 + std::sqrt(std::max(0.0, 1.0 - s * s))); }

// The float nearest above x (the shader must sample a cone at least this wide).
float floatAtLeast(double x) {
  float f = float(x);
  return double(f) < x ? std::nextafter(f, INFINITY) : f;
}

// Fills the record's aim fields for an aimable light and returns its largest
// weight w_max; returns 1 (and leaves aimed = 0) when aiming would not help.
double aimLight(const Light& light, const glm::dvec3& position, const glm::dvec3& axis, const glm::dvec3& tangent,
                const glm::dvec3& bitangent, const AimTarget& target, device::LightRecord& record) {
  constexpr double kSlack = double(SPECTRACE_AIM_SLACK);
  const glm::dvec3 toCentre = target.centre - position;
  const double distance = glm::length(toCentre);
  switch (light.type) {
    case LightType::Point:
    case LightType::Spot: {
      const double s = target.radius / distance + kSlack;
      if (!(s < 1.0)) return 1.0;  // inside or at the sphere: nothing to gain
      const float h = floatAtLeast(oneMinusCosFromSin(s));
      const double emissionSpread = light.type == LightType::Point ? 2.0 : double(record.param0);
      if (!(double(h) < emissionSpread)) return 1.0;
      const glm::dvec3 coneAxis = toCentre / distance;
      const glm::dvec3 coneTangent = perpendicular(coneAxis);
      record.aimed = 1;
      record.aimSpread = h;
      record.aimAxis = toFloat(coneAxis);
      record.aimTangent = toFloat(coneTangent);
      record.aimBitangent = toFloat(glm::cross(coneAxis, coneTangent));
      // Spot: sin^2 of the half angle the analog path samples (1 - cos = param0).
      const double hs = double(record.param0);
      record.aimAccept = float(hs * (2.0 - hs));
      return double(h) / emissionSpread;
    }
    case LightType::Laser: {
      // The beam runs along the axis, so only origins within the sphere's
      // radius of its centre's projection onto the laser's plane can reach
      // it; the slack covers the float rounding of origins and hit points.
      const double slack = 1e-6 * (target.radius + glm::length(position) + glm::length(target.centre) + light.radiusM);
      const float rho = floatAtLeast(target.radius + slack);
      const double radius = double(record.param0);
      if (!(double(rho) < radius)) return 1.0;
      record.aimed = 1;
      record.aimSpread = rho;
      record.aimAxis = glm::vec3(float(glm::dot(toCentre, tangent)), float(glm::dot(toCentre, bitangent)), 0.0f);
      record.aimAccept = float(radius * radius);
      return (double(rho) * double(rho)) / (radius * radius);
    }
    case LightType::Disk:
    case LightType::Rect: {
      // The closest point of the emitter to the sphere's centre gives the
      // widest cone, so the largest 2h.
      const double normal = glm::dot(toCentre, axis);
      const double u = glm::dot(toCentre, tangent), v = glm::dot(toCentre, bitangent);
      double outside2 = 0.0;
      if (light.type == LightType::Disk) {
        const double beyond = std::max(0.0, std::hypot(u, v) - light.radiusM);
        outside2 = beyond * beyond;
      } else {
        const double bu = std::max(0.0, std::abs(u) - 0.5 * light.sizeM.x);
        const double bv = std::max(0.0, std::abs(v) - 0.5 * light.sizeM.y);
        outside2 = bu * bu + bv * bv;
      }
      const double closest = std::sqrt(normal * normal + outside2);
      const double s = target.radius / closest + kSlack;
      if (!(s * s < 0.5)) return 1.0;  // some origins see a wide cone: leave it analog
      // The shader evaluates 2h in float; 1e-4 covers that rounding.
      const double largest = std::min(1.0, 2.0 * oneMinusCosFromSin(s) * (1.0 + 1e-4));
      record.aimed = 1;
      record.aimWeightScale = float(1.0 / largest);
      return 1.0 / double(record.aimWeightScale);  // exactly the scale the shader uses
    }
  }
  return 1.0;
}

// Where a traced light can put beams on the sensor, conservatively: its
// emission points (corners of a convex region holding them, in the camera
// frame), and for a laser its beam.
struct LightReach {
  std::vector<glm::dvec3> corners;
  bool laser = false;
  glm::dvec3 centre{0.0}, axis{0.0};
  double radius = 0.0;
};

LightReach lightReach(const Light& light, const glm::dvec3& position, const glm::dvec3& axis, const glm::dvec3& tangent,
                      const glm::dvec3& bitangent) {
  LightReach reach;
  reach.laser = light.type == LightType::Laser;
  reach.centre = position;
  reach.axis = axis;
  reach.radius = light.radiusM;
  double u = 0.0, v = 0.0;  // half extents along tangent, bitangent
  if (light.type == LightType::Disk || light.type == LightType::Laser) u = v = light.radiusM;  // the disk's square
  if (light.type == LightType::Rect) {
    u = 0.5 * light.sizeM.x;
    v = 0.5 * light.sizeM.y;
  }
  for (double su : {-1.0, 1.0})
    for (double sv : {-1.0, 1.0}) reach.corners.push_back(position + tangent * (su * u) + bitangent * (sv * v));
  return reach;
}

// Narrows the stored window (the whole sensor on entry) to the
// pixels any counted beam can land on, plus a pixel of margin for float
// rounding; leaves it whole when that cannot be bounded.
// - Pinhole at distance D, radius r: a beam from P (height h = P.z - D > 0)
//   through the aperture point A hits H = A (1 + D/h) - P_xy D/h, inside the
//   disk about -P_xy D/h of radius r (1 + D/h). Over a convex emitter with
//   h > 0 throughout, -P_xy D/h stays in the hull of its corners' images
//   (a perspective map keeps segments straight), and 1 + D/h <= 1 + D/h_min.
// - Bare sensor: only lasers are bounded: the beam's footprint lies within
//   R / |a.z| of where its axis meets the sensor.
void narrowPixelWindow(const Camera& camera, const std::vector<LightReach>& lights, PixelWindow& window) {
  const double halfW = 0.5 * camera.sensorWidthM, halfH = 0.5 * camera.sensorHeightM;
  glm::dvec2 lo(INFINITY), hi(-INFINITY);  // sensor-plane bounds of every hit
  for (const LightReach& light : lights) {
    if (camera.pinhole) {
      const double d = camera.pinhole->distanceM, r = camera.pinhole->radiusM;
      double hMin = INFINITY;
      for (const glm::dvec3& p : light.corners) {
        const double h = p.z - d;
        if (!(h > 0.0)) return;  // part of the emitter at or behind the aperture plane
        hMin = std::min(hMin, h);
        const glm::dvec2 centre = -glm::dvec2(p.x, p.y) * (d / h);
        lo = glm::min(lo, centre);
        hi = glm::max(hi, centre);
      }
      const double blur = r * (1.0 + d / hMin);
      lo -= blur;
      hi += blur;
    } else {
      if (!light.laser || !(light.axis.z < 0.0)) return;
      const double t = light.centre.z / -light.axis.z;
      const glm::dvec2 centre(light.centre.x + t * light.axis.x, light.centre.y + t * light.axis.y);
      const double extent = light.radius / -light.axis.z;
      lo = glm::min(lo, centre - extent);
      hi = glm::max(hi, centre + extent);
    }
  }
  if (!(std::isfinite(lo.x) && std::isfinite(lo.y) && std::isfinite(hi.x) && std::isfinite(hi.y))) return;
  // Sensor coordinates to pixel columns and rows (hitSensor: a pinhole image
  // is flipped upright), widened by a pixel for rounding.
  const double ppmX = camera.pixelsX / camera.sensorWidthM, ppmY = camera.pixelsY / camera.sensorHeightM;
  double colLo, colHi, rowLo, rowHi;
  if (camera.pinhole) {
    colLo = (halfW - hi.x) * ppmX;
    colHi = (halfW - lo.x) * ppmX;
    rowLo = (lo.y + halfH) * ppmY;
    rowHi = (hi.y + halfH) * ppmY;
  } else {
    colLo = (lo.x + halfW) * ppmX;
    colHi = (hi.x + halfW) * ppmX;
    rowLo = (halfH - hi.y) * ppmY;
    rowHi = (halfH - lo.y) * ppmY;
  }
  const double maxCol = camera.pixelsX - 1, maxRow = camera.pixelsY - 1;
  const double c0 = std::clamp(std::floor(colLo) - 1.0, 0.0, maxCol), c1 = std::clamp(std::floor(colHi) + 1.0, 0.0, maxCol);
  const double r0 = std::clamp(std::floor(rowLo) - 1.0, 0.0, maxRow), r1 = std::clamp(std::floor(rowHi) + 1.0, 0.0, maxRow);
  window = {uint32_t(c0), uint32_t(r0), uint32_t(c1 - c0) + 1, uint32_t(r1 - r0) + 1};
}

std::string sceneName(const Scene& scene) {
  return scene.sourcePath.empty() ? std::string("<scene>") : scene.sourcePath.string();
}

}  // namespace

TracePlan buildTracePlan(const Scene& scene, uint64_t seed, const TracePlanOptions& options) {
  validateScene(scene);  // scenes built in code get the loader's guarantees too
  TracePlan plan;
  const SpectrumRange& range = scene.spectrum;
  const Camera& camera = scene.camera;
  const CameraFrame frame = CameraFrame::fromCamera(camera);
  const AimTarget target = aimTarget(camera);
  plan.film.weightUnits = 1;
  plan.film.pixelsX = uint32_t(camera.pixelsX);
  plan.film.pixelsY = uint32_t(camera.pixelsY);
  plan.film.bins = uint32_t(range.bins);
  plan.film.lambdaMinNm = range.minNm;
  plan.film.lambdaMaxNm = range.maxNm;
  plan.film.pixelAreaM2 = (camera.sensorWidthM / camera.pixelsX) * (camera.sensorHeightM / camera.pixelsY);

  std::vector<double> selectWeights;
  std::vector<LightReach> reaches;
  for (const Light& light : scene.lights) {
    LightSummary summary;
    summary.label = fmt::format("{} ({}, {})", light.label, lightTypeName(light.type), light.spdLabel);
    summary.powerW = light.powerW;
    const Spd clipped = light.spd.clipped(range.minNm, range.maxNm);
    const double inRange = clipped.lambdaNm.empty() ? 0.0 : clipped.integral();
    summary.inRangeShare = light.spd.fullIntegral > 0.0 ? std::min(1.0, inRange / light.spd.fullIntegral) : 0.0;
    summary.tracedPowerW = light.powerW * summary.inRangeShare;
    const glm::dvec3 axis = glm::normalize(frame.directionToLocal(light.direction));
    glm::dvec3 tangent = light.type == LightType::Rect ? frame.directionToLocal(light.uAxis) : perpendicular(axis);
    tangent = glm::normalize(tangent - axis * glm::dot(tangent, axis));
    const glm::dvec3 bitangent = glm::cross(axis, tangent);
    const glm::dvec3 position = frame.pointToLocal(light.position);
    if (!(summary.tracedPowerW > 0.0)) {
      summary.notTracedBecause = light.powerW > 0.0 ? "it has no power inside the spectrum range" : "its power is zero";
    } else if (options.skipUnreachableLights) {
      summary.notTracedBecause = unreachableBecause(light, position, axis, tangent, bitangent, camera);
    }
    if (summary.notTracedBecause.empty()) {
      summary.traced = true;
      SpectralTable table = buildSpectralTable(clipped);
      device::LightRecord record{};
      record.type = uint32_t(light.type);
      record.spectralFirst = uint32_t(plan.intervals.size());
      record.spectralCount = uint32_t(table.intervals.size());
      plan.intervals.insert(plan.intervals.end(), table.intervals.begin(), table.intervals.end());

      record.position = toFloat(position);
      record.axis = toFloat(axis);
      record.tangent = toFloat(tangent);
      record.bitangent = toFloat(bitangent);
      switch (light.type) {
        case LightType::Spot: {
          // 1 - cos(a) = 2 sin^2(a/2): no cancellation for narrow cones.
          const double half = light.coneHalfAngleDeg * M_PI / 180.0;
          const double s = std::sin(0.5 * half);
          record.param0 = float(2.0 * s * s);
          break;
        }
        case LightType::Disk:
        case LightType::Laser: record.param0 = float(light.radiusM); break;
        case LightType::Rect:
          record.param0 = float(light.sizeM.x);
          record.param1 = float(light.sizeM.y);
          break;
        case LightType::Point: break;
      }
      if (options.aim) summary.largestWeight = aimLight(light, position, axis, tangent, bitangent, target, record);
      summary.aimed = record.aimed != 0;
      plan.lights.push_back(record);
      reaches.push_back(lightReach(light, position, axis, tangent, bitangent));
      // Selection in proportion to power x largest weight: each light's
      // weight ratios are then <= 1 and its beams share one scale.
      selectWeights.push_back(summary.tracedPowerW * summary.largestWeight);
      plan.tracedPowerW += summary.tracedPowerW;
      plan.sampledPowerW += summary.tracedPowerW * summary.largestWeight;
      if (record.aimed && (light.type == LightType::Disk || light.type == LightType::Rect))
        plan.film.weightUnits = device::kWeightUnitsFractional;
    }
    if (!summary.traced) summary.tracedPowerW = 0.0;
    plan.summaries.push_back(summary);
  }
  if (plan.lights.empty()) {
    std::string why;
    for (const auto& s : plan.summaries) why += fmt::format("\n  {}: {}", s.label, s.notTracedBecause);
    throw SceneError(fmt::format("{}: /lights: no light can put a beam on the sensor:{}", sceneName(scene), why));
  }
  const auto lows = quantizeCdf(selectWeights);
  for (size_t i = 0; i < lows.size(); ++i) plan.lights[i].selectCdfLow = lows[i];

  device::TraceConstants& c = plan.constants;
  c.sensorHalfSize = glm::vec2(float(0.5 * camera.sensorWidthM), float(0.5 * camera.sensorHeightM));
  c.pixelsPerMetre = glm::vec2(float(camera.pixelsX / camera.sensorWidthM), float(camera.pixelsY / camera.sensorHeightM));
  c.pixelsX = plan.film.pixelsX;
  c.pixelsY = plan.film.pixelsY;
  c.bins = plan.film.bins;
  c.lightCount = uint32_t(plan.lights.size());
  c.lambdaMin = float(range.minNm);
  c.binsPerNm = float(range.bins / (range.maxNm - range.minNm));
  if (camera.pinhole) {
    c.apertureDistance = float(camera.pinhole->distanceM);
    c.apertureRadiusSq = float(camera.pinhole->radiusM * camera.pinhole->radiusM);
  }
  c.pixelsPerChunk = uint32_t(plan.film.pixelCount());
  FilmLayout& film = plan.film;
  film.exactColour = options.exactColour;
  film.firstStoredBin = 0;
  film.storedBins = film.bins;
  const Observer& observer = observerByName(scene.observer);
  for (size_t i = 0; i < observer.lambdaNm.size(); ++i)
    plan.cmfTable.emplace_back(float(observer.xbar[i]), float(observer.ybar[i]), float(observer.zbar[i]));
  c.cmfCount = uint32_t(observer.lambdaNm.size());
  c.cmfLambdaMin = float(observer.lambdaNm.front());
  c.cmfNodesPerNm = float((observer.lambdaNm.size() - 1) / (observer.lambdaNm.back() - observer.lambdaNm.front()));
  c.seed = seed;
  c.aimCentre = toFloat(target.centre);
  c.aimRadius = floatAtLeast(target.radius);
  if (options.trimSpectrum) {
    // The lowest and highest bin any sample can fall in, from the very float
    // operations of the shader (beam_trace.h): an interval's wavelengths run
    // from lambda0 + width * 0 to lambda0 + width * 1, monotonically in t.
    device::BeamKernel kernel(c, plan.lights, plan.intervals);
    uint32_t first = plan.film.bins, last = 0;
    for (const auto& iv : plan.intervals) {
      const float lowest = iv.lambda0 + iv.width * 0.0f;
      const float highest = iv.lambda0 + iv.width * 1.0f;
      first = std::min(first, kernel.binOfWavelength(lowest, c.lambdaMin, c.binsPerNm, plan.film.bins));
      last = std::max(last, kernel.binOfWavelength(highest, c.lambdaMin, c.binsPerNm, plan.film.bins));
    }
    film.firstStoredBin = first;
    film.storedBins = last - first + 1;
  }
  film.window = {0, 0, film.pixelsX, film.pixelsY};
  if (options.trimPixels) narrowPixelWindow(camera, reaches, film.window);
  // The kernel's copy of the film's shape.
  c.exactColour = film.exactColour ? 1u : 0u;
  c.totalBins = film.bins;
  c.binOffset = film.firstStoredBin;
  c.bins = film.storedBins;
  c.countersPerPixel = film.countersPerPixel();
  c.weightUnits = film.weightUnits;
  c.windowX0 = film.window.x0;
  c.windowY0 = film.window.y0;
  c.windowWidth = film.window.width;
  c.windowHeight = film.window.height;
  return plan;
}

}  // namespace spectrace
