#include "lights/trace_plan.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "camera/camera_frame.h"
#include "kernel/beam_kernel.h"
#include "lights/light_shared.h"
#include "colour/colour.h"
#include "spectrum/wavelength_sampler.h"

namespace spectrace {
namespace {

// The sphere every counted beam passes through: the pinhole's disk, or the
// bare sensor (its half diagonal).
AimTarget aimTarget(const Camera& camera) {
  const double slack = double(SPECTRACE_AIM_SLACK);
  if (camera.pinhole) return {{0.0, 0.0, camera.pinhole->distanceM}, camera.pinhole->radiusM, slack};
  return {{0.0, 0.0, 0.0}, 0.5 * std::hypot(camera.sensorWidthM, camera.sensorHeightM), slack};
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
      if (!light.collimated || !(light.axis.z < 0.0)) return;
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
    const LightTypeUnit& unit = lightTypeUnit(light.type);
    summary.label = fmt::format("{} ({}, {})", light.label, unit.name, light.spdLabel);
    summary.powerW = light.powerW;
    const Spd clipped = light.spd.clipped(range.minNm, range.maxNm);
    const double inRange = clipped.lambdaNm.empty() ? 0.0 : clipped.integral();
    summary.inRangeShare = light.spd.fullIntegral > 0.0 ? std::min(1.0, inRange / light.spd.fullIntegral) : 0.0;
    summary.tracedPowerW = light.powerW * summary.inRangeShare;
    const glm::dvec3 axis = glm::normalize(frame.directionToLocal(light.direction));
    glm::dvec3 tangent = unit.tangentFromUAxis ? frame.directionToLocal(light.uAxis) : perpendicular(axis);
    tangent = glm::normalize(tangent - axis * glm::dot(tangent, axis));
    const glm::dvec3 bitangent = glm::cross(axis, tangent);
    const glm::dvec3 position = frame.pointToLocal(light.position);
    const LightFrame local{position, axis, tangent, bitangent};
    if (!(summary.tracedPowerW > 0.0)) {
      summary.notTracedBecause = light.powerW > 0.0 ? "it has no power inside the spectrum range" : "its power is zero";
    } else if (options.skipUnreachableLights) {
      summary.notTracedBecause = unit.unreachableBecause(light, local, camera);
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
      unit.pack(light, record);
      if (options.aim) summary.largestWeight = unit.aim(light, local, target, record);
      summary.aimed = record.aimed != 0;
      plan.lights.push_back(record);
      reaches.push_back(unit.reach(light, local));
      // Selection in proportion to power x largest weight: each light's
      // weight ratios are then <= 1 and its beams share one scale.
      selectWeights.push_back(summary.tracedPowerW * summary.largestWeight);
      plan.tracedPowerW += summary.tracedPowerW;
      plan.sampledPowerW += summary.tracedPowerW * summary.largestWeight;
      if (record.aimed && unit.aimedWeightsVary)
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
