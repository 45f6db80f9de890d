#pragma once
// The scene compiler: a scene, in double precision on the host, becomes what
// a tracer runs (a DeviceScene: light records in the camera frame, spectral
// tables, the light-selection CDF, camera constants), the film it fills
// (FilmLayout), the physical scale of one count, and a report per light.
// Skipping and aiming are passes, each taken only when its precondition
// holds (compile/shortcuts.h).
#include <cstdint>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "device_data/scene_data.h"
#include "device_shared.h"
#include "film/film_layout.h"
#include "scene/scene.h"

namespace spectrace {

// What the kernel reads: its constants and tables (shaders/device_shared.h).
struct DeviceScene {
  // Scene-wide kernel constants. Their film fields (window, stored bins,
  // countersPerPixel, weightUnits) mirror the FilmLayout; pixelsPerChunk is
  // left 0 for the backend that splits the film into buffers to set.
  device::TraceConstants constants{};
  std::vector<device::LightRecord> lights;          // traced lights, with the selection CDF
  std::vector<device::SpectralInterval> intervals;  // every traced light's spectral table
  std::vector<device::AliasColumn> aliasColumns;    // the light choice's, then each light's table's
  std::vector<glm::vec3> cmfTable;                  // the observer's CMF nodes, for exact colour
  // Scene objects (empty without): primitives in the BVH's leaf order, the
  // BVH, the materials.
  std::vector<device::Primitive> primitives;
  std::vector<device::BvhNode> bvhNodes;
  std::vector<device::Material> materials;
  // The scene data (device_shared.h): units' parameters and tables, by
  // offset.
  SceneData data;
};

// What became of one scene light, for messages and the bench.
struct LightSummary {
  std::string label;       // e.g. "/lights/2 (disk, D65)", or with a name light "lamp" (/lights/2, disk, D65)
  double powerW = 0.0;     // as given, or from power_lm
  double powerLm = -1.0;   // power_lm when given (Light::powerLm)
  double inRangeShare = 0.0;  // share of the emission inside the spectrum range
  double tracedPowerW = 0.0;  // powerW * inRangeShare
  bool traced = false;        // false: never sampled
  bool aimed = false;         // beams drawn only towards the camera
  // Aimed: the largest weight a beam can carry, about the share of the
  // light's emission that is sampled (1 when not aimed).
  double largestWeight = 1.0;
  std::string notTracedBecause;  // why, when not traced
  // Why no beam of it can reach the camera directly, objects aside (the
  // light unit's reach test), or "" when one might.
  std::string cannotShineOnCameraBecause;
};

// What CompiledScene::irradiancePerCount needs, kept by what writes render
// states after the plan has gone to the tracer.
struct IrradianceScale {
  double sampledPowerW = 0.0, pixelAreaM2 = 0.0;
  uint64_t weightUnits = 1;
  double perCount(uint64_t beams) const { return sampledPowerW / (double(beams) * pixelAreaM2 * double(weightUnits)); }
};

struct CompiledScene {
  DeviceScene device;
  FilmLayout film;                      // what the device stores, and how
  std::vector<LightSummary> summaries;  // one per scene light, in scene order
  // The physical scale. tracedPowerW: the sum over traced lights;
  // sampledPowerW: the sum of power x largest weight, the power a
  // full-weight beam stands for, times the beam count (= tracedPowerW
  // without aiming).
  double tracedPowerW = 0.0;
  double sampledPowerW = 0.0;
  // With the colour-from-bins shortcut (film.colourFromBins): per bin of
  // the full spectrum, the mean CMF of the wavelengths drawn in it
  // (sampledBinCmfMeans), which develops colour in place of per-beam sums.
  std::vector<std::array<double, 3>> colourBinMeans;
  // Why camera paths do not run though the options asked for them (their
  // estimator's precondition, compile/estimators.h), or "".
  std::string cameraPathsOffBecause;

  // W/m^2 per bin carried by one count when `beams` beams were traced: a
  // full-weight beam carries sampledPowerW * exposure / beams joules, spread
  // over one pixel's area and the exposure time (which cancels), and adds
  // weightUnits counts.
  double irradiancePerCount(uint64_t beams) const { return irradianceScale().perCount(beams); }
  IrradianceScale irradianceScale() const { return {sampledPowerW, film.pixelAreaM2, film.weightUnits}; }
};

// Each shortcut can be turned off here (the unshortened reference path);
// compile/shortcuts.h says when each is valid at all.
struct CompileOptions {
  // Accumulate each counted beam's own CMF values per pixel (exact colour
  // whatever the bin count); otherwise colour comes from bin-averaged CMFs.
  bool exactColour = true;
  // Exact colour from the bins where compile/shortcuts.h allows it (no
  // per-beam colour counters); off: per-beam CMF sums.
  bool colourFromBins = true;
  // Never sample lights that provably cannot reach the sensor.
  bool skipUnreachableLights = true;
  // Store only the wavelength bins the traced lights can reach.
  bool trimSpectrum = true;
  // Store only the pixels beams can reach.
  bool trimPixels = true;
  // Draw beams only towards the camera, weighted so the estimate is
  // unbiased; off: analog emission.
  bool aim = true;
  // Connect diffuse vertices to the camera (light tracing); off: the analog
  // estimator, which counts only beams that reach the camera themselves.
  // Not a shortcut: both are unbiased, and a test holds them to each other.
  bool connect = true;
  // The estimators (shaders/camera_path.h): light paths (beams), camera
  // paths (from the pixels, with next-event estimation), or both, each path
  // of light then counted by one of them. Camera paths are kept only where
  // they can count something (a pinhole camera, and an emitter with an area
  // or a diffuse object with a light other than a laser). Not shortcuts:
  // each is unbiased on the paths it counts, and tests hold them to each
  // other and to closed forms.
  bool lightPaths = true;
  bool cameraPaths = true;
  // Bench only: every object primitive in one BVH leaf, so each ray tests
  // them all (brute force through the same kernel code).
  bool bruteForceObjects = false;
};

// Every compile option by the name a render state records it under (so a
// state's fingerprint holds the options as a whole, and a merge or resume
// compiles the scene the same way). A new option goes here, or the
// static_assert fails: the struct holds bools only, one byte each.
struct CompileOptionField {
  const char* name;
  bool CompileOptions::*member;
};
inline constexpr CompileOptionField kCompileOptionFields[] = {
    {"exact_colour", &CompileOptions::exactColour},
    {"colour_from_bins", &CompileOptions::colourFromBins},
    {"skip_unreachable_lights", &CompileOptions::skipUnreachableLights},
    {"trim_spectrum", &CompileOptions::trimSpectrum},
    {"trim_pixels", &CompileOptions::trimPixels},
    {"aim", &CompileOptions::aim},
    {"connect", &CompileOptions::connect},
    {"light_paths", &CompileOptions::lightPaths},
    {"camera_paths", &CompileOptions::cameraPaths},
    {"brute_force_objects", &CompileOptions::bruteForceObjects},
};
static_assert(sizeof(CompileOptions) == std::size(kCompileOptionFields) * sizeof(bool),
              "every CompileOptions field needs its row in kCompileOptionFields");
// The options by name, and back (a name missing from `named` keeps its
// default; an unknown name throws std::invalid_argument).
std::map<std::string, bool> namedCompileOptions(const CompileOptions& options);
CompileOptions compileOptionsNamed(const std::map<std::string, bool>& named);

// Throws SceneError (with the scene file's name) for scenes that cannot be
// traced, e.g. when no light has power inside the spectrum range.
CompiledScene compileScene(const Scene& scene, uint64_t seed, const CompileOptions& options = {});
// Throws SceneError (naming the field) when one count of a render of `beams`
// beams would underflow the float image. compileScene checks the upper end.
void checkBeamScale(const Scene& scene, const CompiledScene& compiled, uint64_t beams);

}  // namespace spectrace
