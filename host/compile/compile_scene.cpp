#include "compile/compile_scene.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "camera/camera_frame.h"
#include "colour/colour.h"
#include "compile/compile_objects.h"
#include "compile/estimators.h"
#include "compile/shortcuts.h"
#include "film/pixel_window.h"
#include "kernel/beam_kernel.h"
#include "lights/light_shared.h"
#include "spectrum/alias_table.h"
#include "spectrum/wavelength_sampler.h"

namespace spectrace {
namespace {

// The sphere every counted beam passes through (the camera model's
// entrance), widened by the kernel's slack.
AimTarget aimTarget(const Camera& camera) {
  const EntranceSphere entrance = camera.model->entranceSphere(camera);
  return {entrance.centre, entrance.radius, double(SPECTRACE_AIM_SLACK)};
}

std::string sceneName(const Scene& scene) {
  return scene.sourcePath.empty() ? std::string("<scene>") : scene.sourcePath.string();
}

// Refuses a light that sees the camera's entrance under less than the
// smallest angle its model resolves (CameraModel::smallestEntranceSine).
void checkEntranceResolved(const Scene& scene, const Light& light, const LightReach& reach, const AimTarget& target) {
  const double smallest = scene.camera.model->smallestEntranceSine();
  if (reach.collimated || !(smallest > 0.0)) return;  // a laser's beams run along its axis: no angle to resolve
  double farthest = glm::length(reach.centre - target.centre);
  for (const glm::dvec3& corner : reach.corners) farthest = std::max(farthest, glm::length(corner - target.centre));
  if (!(farthest > 0.0) || target.radius / farthest >= smallest) return;
  throw SceneError(fmt::format(
      "{}: /camera: the camera's entrance ({:g} m across) seen from {} ({:g} m away) subtends {:.2g} rad, below the "
      "{:g} rad float positions and directions resolve; the image would be decided by rounding. Use an entrance of "
      "at least {:.2g} m radius, or bring the light closer",
      sceneName(scene), 2.0 * target.radius, light.label, farthest, target.radius / farthest, smallest,
      smallest * farthest));
}

// The whole sensor and spectrum, before any trimming.
FilmLayout sensorFilm(const Scene& scene, bool exactColour) {
  const Camera& camera = scene.camera;
  FilmLayout film;
  film.pixelsX = uint32_t(camera.pixelsX);
  film.pixelsY = uint32_t(camera.pixelsY);
  film.bins = uint32_t(scene.spectrum.bins);
  film.lambdaMinNm = scene.spectrum.minNm;
  film.lambdaMaxNm = scene.spectrum.maxNm;
  film.pixelAreaM2 = (camera.sensorWidthM / camera.pixelsX) * (camera.sensorHeightM / camera.pixelsY);
  film.window = {0, 0, film.pixelsX, film.pixelsY};
  film.firstStoredBin = 0;
  film.storedBins = film.bins;
  film.exactColour = exactColour;
  film.weightUnits = 1;
  return film;
}

// The light's placement in the camera frame, with the frame its type uses.
LightFrame lightFrame(const Light& light, const LightTypeUnit& unit, const CameraFrame& frame) {
  const glm::dvec3 axis = glm::normalize(frame.directionToLocal(light.direction));
  glm::dvec3 tangent = unit.tangentFromUAxis ? frame.directionToLocal(light.uAxis) : perpendicular(axis);
  tangent = glm::normalize(tangent - axis * glm::dot(tangent, axis));
  return {frame.pointToLocal(light.position), axis, tangent, glm::cross(axis, tangent)};
}

// Where `table` already lies in `intervals` as the whole table of an
// earlier light (bit for bit, so the draws are the same), or the end of
// `intervals` when it does not. Lights of one SPD (a row of lasers or
// lamps) then share one table and its alias columns instead of one copy
// per light (41 copies of D65 on the prism scene), so the tables stay small
// enough for a device's uniform buffers (backend/uniform_tables.cpp).
uint32_t sharedSpectralFirst(const std::vector<device::SpectralInterval>& intervals,
                             std::span<const device::LightRecord> lights, const SpectralTable& table) {
  for (const device::LightRecord& earlier : lights) {
    if (sameSpectralTable(std::span(intervals).subspan(earlier.spectralFirst, earlier.spectralCount), table.intervals))
      return earlier.spectralFirst;
  }
  return uint32_t(intervals.size());
}

// Light records, spectral tables and summaries, through each light type's
// unit; the skip and aim passes act per light. Returns each traced light's
// reach and its selection weight (power x largest weight).
void compileLights(const Scene& scene, const CompileOptions& options, CompiledScene& compiled,
                   std::vector<LightReach>& reaches, std::vector<double>& selectWeights) {
  const SpectrumRange& range = scene.spectrum;
  const CameraFrame frame = CameraFrame::fromCamera(scene.camera);
  const AimTarget target = aimTarget(scene.camera);
  const bool skip = shortcutApplies(Shortcut::SkipUnreachableLights, options.skipUnreachableLights, scene);
  const bool aim = shortcutApplies(Shortcut::AimAtCamera, options.aim, scene);
  DeviceScene& device = compiled.device;
  for (const Light& light : scene.lights) {
    LightSummary summary;
    const LightTypeUnit& unit = lightTypeUnit(light.type);
    summary.label = light.name.empty()
                        ? fmt::format("{} ({}, {})", light.label, unit.name, light.spdLabel)
                        : fmt::format("light {} ({}, {}, {})", json_fields::jsonQuoted(light.name), light.label,
                                      unit.name, light.spdLabel);
    summary.powerW = light.powerW;
    summary.powerLm = light.powerLm;
    const Spd clipped = light.spd.clipped(range.minNm, range.maxNm);
    const double inRange = clipped.lambdaNm.empty() ? 0.0 : clipped.integral();
    summary.inRangeShare = light.spd.fullIntegral > 0.0 ? std::min(1.0, inRange / light.spd.fullIntegral) : 0.0;
    summary.tracedPowerW = light.powerW * summary.inRangeShare;
    const LightFrame local = lightFrame(light, unit, frame);
    // Whether the light could shine on the camera with nothing in the way:
    // without objects a light that cannot is never sampled; with objects it
    // is, for what it lights, and the render says so before tracing.
    summary.cannotShineOnCameraBecause = unit.unreachableBecause(light, local, scene.camera);
    if (!(summary.tracedPowerW > 0.0)) {
      summary.notTracedBecause = light.powerW > 0.0 ? "it has no power inside the spectrum range" : "its power is zero";
    } else if (skip) {
      summary.notTracedBecause = summary.cannotShineOnCameraBecause;
    }
    if (summary.notTracedBecause.empty()) {
      summary.traced = true;
      SpectralTable table = buildSpectralTable(clipped);
      device::LightRecord record{};
      record.type = uint32_t(light.type);
      record.spectralFirst = sharedSpectralFirst(device.intervals, device.lights, table);
      record.spectralCount = uint32_t(table.intervals.size());
      if (record.spectralFirst == device.intervals.size())
        device.intervals.insert(device.intervals.end(), table.intervals.begin(), table.intervals.end());
      record.position = toFloat(local.position);
      record.axis = toFloat(local.axis);
      record.tangent = toFloat(local.tangent);
      record.bitangent = toFloat(local.bitangent);
      unit.pack(light, frame, record, compiled.device.data);
      if (aim) summary.largestWeight = unit.aim(light, local, target, record);
      summary.aimed = record.aimed != 0;
      device.lights.push_back(record);
      reaches.push_back(unit.reach(light, local));
      checkEntranceResolved(scene, light, reaches.back(), target);
      // Selection in proportion to power x largest weight: each light's
      // weight ratios are then <= 1 and its beams share one scale.
      selectWeights.push_back(summary.tracedPowerW * summary.largestWeight);
      compiled.tracedPowerW += summary.tracedPowerW;
      compiled.sampledPowerW += summary.tracedPowerW * summary.largestWeight;
      if (record.aimed && unit.aimedWeightsVary) compiled.film.weightUnits = device::kWeightUnitsFractional;
    }
    if (!summary.traced) summary.tracedPowerW = 0.0;
    compiled.summaries.push_back(summary);
  }
  if (device.lights.empty()) {
    std::string why;
    for (const auto& s : compiled.summaries) why += fmt::format("\n  {}: {}", s.label, s.notTracedBecause);
    throw SceneError(fmt::format("{}: /lights: no light can put a beam on the sensor:{}", sceneName(scene), why));
  }
}

// The traced light that carries the most power: the one to name when the
// scene's scale is out of range.
struct NamedLight {
  const Light& light;
  std::string pointer;  // e.g. "/lights/2"
};
// "power_w: 10 W", or "power_lm: 800 lm (11.7 W)": the field the file gave.
std::string powerField(const Light& light) {
  if (light.powerLm >= 0.0) return fmt::format("power_lm: {:g} lm ({:g} W)", light.powerLm, light.powerW);
  return fmt::format("power_w: {:g} W", light.powerW);
}

NamedLight strongestLight(const Scene& scene, const CompiledScene& compiled) {
  size_t strongest = 0;
  for (size_t i = 1; i < compiled.summaries.size(); ++i)
    if (compiled.summaries[i].tracedPowerW > compiled.summaries[strongest].tracedPowerW) strongest = i;
  const Light& light = scene.lights[strongest];
  return {light, light.label.empty() ? fmt::format("/lights/{}", strongest) : light.label};
}

// The image is float: the brightest a pixel can be (every beam in it,
// sampledPowerW / pixel area, times 683 lm/W and a CMF value up to 2.1 in
// XYZ) must stay far inside float range, and a pixel's area must not
// underflow. Checked before tracing, naming the field to change.
constexpr double kSmallestPixelAreaM2 = 1e-30;   // pixels of 1e-15 m (a femtometre)
constexpr double kBrightestImageValue = 1e30;    // float's 3.4e38, with room for sums and scales
void checkImageRange(const Scene& scene, const CompiledScene& compiled) {
  const Camera& camera = scene.camera;
  const double area = compiled.film.pixelAreaM2;
  if (!std::isnormal(area) || area < kSmallestPixelAreaM2)
    throw SceneError(fmt::format(
        "{}: /camera/sensor: pixels of {:g} x {:g} m have an area of {:g} m², below {:g} m²: irradiance per "
        "pixel would overflow or lose all precision; use a larger sensor or fewer pixels",
        sceneName(scene), camera.sensorWidthM / camera.pixelsX, camera.sensorHeightM / camera.pixelsY, area,
        kSmallestPixelAreaM2));
  const double brightest = compiled.sampledPowerW / area * kLumensPerWatt * 2.1;
  if (std::isfinite(brightest) && brightest < kBrightestImageValue) return;
  const auto [light, pointer] = strongestLight(scene, compiled);
  throw SceneError(fmt::format(
      "{}: {}/{} over pixels of {:g} m² can reach {:g} in XYZ, beyond the range of the image's float "
      "channels (at most {:g}); use a smaller power or larger pixels",
      sceneName(scene), pointer, powerField(light), area, brightest, kBrightestImageValue));
}

// Camera, spectrum, observer and seed constants of the kernel.
void cameraConstants(const Scene& scene, uint64_t seed, DeviceScene& device) {
  const Camera& camera = scene.camera;
  const SpectrumRange& range = scene.spectrum;
  device::TraceConstants& c = device.constants;
  c.sensorHalfSize = glm::vec2(float(0.5 * camera.sensorWidthM), float(0.5 * camera.sensorHeightM));
  c.pixelsPerMetre = glm::vec2(float(camera.pixelsX / camera.sensorWidthM), float(camera.pixelsY / camera.sensorHeightM));
  c.pixelsX = uint32_t(camera.pixelsX);
  c.pixelsY = uint32_t(camera.pixelsY);
  c.lightCount = uint32_t(device.lights.size());
  c.lambdaMin = float(range.minNm);
  c.binsPerNm = float(range.bins / (range.maxNm - range.minNm));
  camera.model->pack(c, device.data);
  const Observer& observer = observerByName(scene.observer);
  for (size_t i = 0; i < observer.lambdaNm.size(); ++i)
    device.cmfTable.emplace_back(float(observer.xbar[i]), float(observer.ybar[i]), float(observer.zbar[i]));
  c.cmfCount = uint32_t(observer.lambdaNm.size());
  c.cmfLambdaMin = float(observer.lambdaNm.front());
  c.cmfNodesPerNm = float((observer.lambdaNm.size() - 1) / (observer.lambdaNm.back() - observer.lambdaNm.front()));
  c.seed = seed;
  const AimTarget target = aimTarget(camera);
  c.aimCentre = toFloat(target.centre);
  c.aimRadius = floatAtLeast(target.radius);
}

// Trim-spectrum pass: the lowest and highest bin any sample can fall in,
// from the very float operations of the kernel (emit.h): an interval's
// wavelengths run from lambda0 + width * 0 to lambda0 + width * 1,
// monotonically in t.
void trimSpectrum(const DeviceScene& device, FilmLayout& film) {
  const device::TraceConstants& c = device.constants;
  device::BeamKernel kernel(c, device.lights, device.intervals, device.aliasColumns);
  uint32_t first = film.bins, last = 0;
  for (const auto& iv : device.intervals) {
    const float lowest = iv.lambda0 + iv.width * 0.0f;
    const float highest = iv.lambda0 + iv.width * 1.0f;
    first = std::min(first, kernel.binOfWavelength(lowest, c.lambdaMin, c.binsPerNm, film.bins));
    last = std::max(last, kernel.binOfWavelength(highest, c.lambdaMin, c.binsPerNm, film.bins));
  }
  film.firstStoredBin = first;
  film.storedBins = last - first + 1;
}

// The alias columns the kernel draws through (host/spectrum/alias_table.h):
// the light choice's from column 0, then each light's spectral table's,
// each built from the integer CDF it replaces; lights that share a
// spectral table share its columns.
void buildAliasColumns(DeviceScene& device) {
  std::vector<uint64_t> lows;
  for (const auto& light : device.lights) lows.push_back(light.selectCdfLow);
  AliasTable table = buildAliasTable(lows);
  device.constants.lightAliasBits = table.bits;
  device.aliasColumns = std::move(table.columns);
  for (size_t l = 0; l < device.lights.size(); ++l) {
    auto& light = device.lights[l];
    const auto sharer = std::find_if(device.lights.begin(), device.lights.begin() + l,
                                     [&](const auto& earlier) { return earlier.spectralFirst == light.spectralFirst; });
    if (sharer != device.lights.begin() + l) {
      light.spectralAliasFirst = sharer->spectralAliasFirst;
      light.spectralAliasBits = sharer->spectralAliasBits;
      continue;
    }
    lows.clear();
    for (uint32_t i = 0; i < light.spectralCount; ++i) lows.push_back(device.intervals[light.spectralFirst + i].cdfLow);
    table = buildAliasTable(lows);
    light.spectralAliasFirst = uint32_t(device.aliasColumns.size());
    light.spectralAliasBits = table.bits;
    device.aliasColumns.insert(device.aliasColumns.end(), table.columns.begin(), table.columns.end());
  }
}

// Colour-from-bins pass: no per-beam colour counters; the film's colour is
// developed from its bins with the shared table's mean CMF per bin.
void developColourFromBins(const Scene& scene, CompiledScene& compiled) {
  const DeviceScene& device = compiled.device;
  const auto& light = device.lights.front();
  const std::span<const device::SpectralInterval> table(device.intervals.data() + light.spectralFirst,
                                                        light.spectralCount);
  compiled.colourBinMeans = sampledBinCmfMeans(table, observerByName(scene.observer), compiled.film.lambdaMinNm,
                                               compiled.film.lambdaMaxNm, int(compiled.film.bins));
  compiled.film.exactColour = false;
  compiled.film.colourFromBins = true;
}

// The kernel's copy of the film's shape.
void filmConstants(const FilmLayout& film, device::TraceConstants& c) {
  c.exactColour = film.exactColour ? 1u : 0u;
  c.totalBins = film.bins;
  c.binOffset = film.firstStoredBin;
  c.bins = film.storedBins;
  c.countersPerPixel = film.countersPerPixel();
  c.weighted = film.weighted() ? 1u : 0u;
  c.windowX0 = film.window.x0;
  c.windowY0 = film.window.y0;
  c.windowWidth = film.window.width;
  c.windowHeight = film.window.height;
}

}  // namespace

void checkBeamScale(const Scene& scene, const CompiledScene& compiled, uint64_t beams) {
  const double perCount = compiled.irradiancePerCount(beams);
  // The smallest value a pixel can hold, one count, in the float image.
  if (beams == 0 || (std::isfinite(perCount) && float(perCount) > 0.0f)) return;
  const auto [light, pointer] = strongestLight(scene, compiled);
  throw SceneError(fmt::format(
      "{}: {}/{} spread over {} beams gives {:g} W/m² per count, below the smallest float the image "
      "can hold; use a larger power or fewer beams",
      sceneName(scene), pointer, powerField(light), beams, perCount));
}

CompiledScene compileScene(const Scene& scene, uint64_t seed, const CompileOptions& options) {
  validateScene(scene);  // scenes built in code get the loader's guarantees too
  CompiledScene compiled;
  compiled.film = sensorFilm(scene, options.exactColour);
  std::vector<LightReach> reaches;
  std::vector<double> selectWeights;
  compileLights(scene, options, compiled, reaches, selectWeights);
  checkImageRange(scene, compiled);
  const auto lows = quantizeCdf(selectWeights);
  for (size_t i = 0; i < lows.size(); ++i) compiled.device.lights[i].selectCdfLow = lows[i];
  buildAliasColumns(compiled.device);
  cameraConstants(scene, seed, compiled.device);
  // Each emitting object's light: 1 + its index among the traced lights.
  std::vector<uint32_t> emitterOf(scene.objects.size(), 0u);
  uint32_t traced = 0;
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    if (!compiled.summaries[i].traced) continue;
    const auto& surface = scene.lights[i].surface;
    if (surface && surface->objectIndex < emitterOf.size()) emitterOf[surface->objectIndex] = traced + 1;
    ++traced;
  }
  compileObjects(scene, options, compiled.device, emitterOf);
  const std::string cameraPathsUseless = cameraPathsUselessBecause(scene, compiled.device);
  if (!options.lightPaths && !options.cameraPaths)
    throw SceneError(fmt::format("{}: no estimator: light paths and camera paths are both off", sceneName(scene)));
  if (!options.lightPaths && !cameraPathsUseless.empty())
    throw SceneError(fmt::format("{}: camera paths alone cannot render this scene: {}; use --estimator light or both",
                                 sceneName(scene), cameraPathsUseless));
  compiled.device.constants.estimators = estimatorsFor(options, cameraPathsUseless);
  if (options.cameraPaths) compiled.cameraPathsOffBecause = cameraPathsUseless;
  compiled.device.constants.wavelengthsPerPath = scene.render.wavelengthsPerBeam;
  const bool cameraPaths = (compiled.device.constants.estimators & device::kEstimatorCameraPaths) != 0;
  // Camera connections, camera paths and beams of several wavelengths (each
  // counting its share) carry fractional weights.
  if (compiled.device.constants.connect != 0 || cameraPaths || compiled.device.constants.wavelengthsPerPath > 1)
    compiled.film.weightUnits = device::kWeightUnitsFractional;
  if (shortcutApplies(Shortcut::TrimSpectrum, options.trimSpectrum, scene)) trimSpectrum(compiled.device, compiled.film);
  if (shortcutApplies(Shortcut::TrimPixels, options.trimPixels, scene))
    compiled.film.window = reachablePixelWindow(scene.camera, reaches);
  if (compiled.film.exactColour && shortcutApplies(Shortcut::ColourFromBins, options.colourFromBins, scene) &&
      sharedSpectralTableMissingBecause(compiled.device.lights, compiled.device.intervals).empty())
    developColourFromBins(scene, compiled);
  filmConstants(compiled.film, compiled.device.constants);
  if (cameraPaths) setCameraPathWeights(scene, compiled);
  return compiled;
}

}  // namespace spectrace

namespace spectrace {

std::map<std::string, bool> namedCompileOptions(const CompileOptions& options) {
  std::map<std::string, bool> named;
  for (const CompileOptionField& field : kCompileOptionFields) named[field.name] = options.*field.member;
  return named;
}

CompileOptions compileOptionsNamed(const std::map<std::string, bool>& named) {
  CompileOptions options;
  for (const auto& [name, value] : named) {
    const CompileOptionField* found = nullptr;
    for (const CompileOptionField& field : kCompileOptionFields)
      if (name == field.name) found = &field;
    if (!found) throw std::invalid_argument(fmt::format("unknown compile option '{}'", name));
    options.*found->member = value;
  }
  return options;
}

}  // namespace spectrace
