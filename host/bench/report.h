#pragma once
// The benchmark's outputs: CSV files, gnuplot plots and a markdown report
// with the plots embedded and every ratio taken within the same run.
#include <filesystem>
#include <string>
#include <vector>

#include "bench/error_bench.h"
#include "bench/optics_bench.h"
#include "bench/ray_ceiling.h"

namespace spectrace {

struct ThroughputRow {
  DeviceKind device = DeviceKind::Cpu;
  bool reference = false;  // the CPU reference (the other devices' ratios are to it)
  std::string deviceName;
  bool exactColour = true;
  uint64_t beams = 0, hits = 0;
  double wallSeconds = 0.0, traceDeviceSeconds = 0.0;
};

// Beams/s of the general and the scene-specialised trace pipeline, and of
// each specialisation alone.
struct SpecialisationRow {
  std::string scene, deviceName;
  uint64_t beams = 0;
  double generalSeconds = 0.0, specialisedSeconds = 0.0;  // device time of the trace pass
  std::vector<double> featureSeconds;  // one per SpecialisedFeature bit, alone
};
// The names of the SpecialisedFeature bits, in bit order.
inline const char* const kSpecialisedFeatureNames[] = {"light types", "light choice", "camera model", "exact colour", "aim"};

// Storing the full spectrum against only the bins the lights reach.
struct TrimRow {
  std::string scene, deviceName;
  uint64_t beams = 0;
  uint32_t fullBins = 0, storedBins = 0;
  uint64_t fullPixels = 0, storedPixels = 0;
  double fullMiB = 0.0, trimmedMiB = 0.0;                  // device histogram
  double fullTraceSeconds = 0.0, trimmedTraceSeconds = 0.0;  // device time
  double fullResolveSeconds = 0.0, trimmedResolveSeconds = 0.0;
};

// Aimed against analog sampling of one reference scene on one device: each
// at its own beam count (analog needs many more to count enough), compared
// by figure of merit, which does not depend on the beam count once the
// error falls as N^-1/2.
struct AimRow {
  SweepRow aimed, analog;
  double fomGain() const { return aimed.fom / analog.fom; }
};

// Batch warm-up: time from opening a Vulkan device to the first finished
// render, with an empty (cold) and then a just-saved (warm) pipeline cache,
// same run.
struct PipelineCacheRow {
  std::string deviceName;
  double coldSeconds = 0, warmSeconds = 0;
  uint64_t cacheBytes = 0;  // the saved cache file
  double ratio() const { return coldSeconds / warmSeconds; }
};

// Many small jobs in one `spectrace batch` process against one `spectrace
// render` process per job (wall time of the processes, same run).
struct BatchProcessRow {
  std::string deviceName;
  DeviceKind device = DeviceKind::Cpu;
  uint64_t jobs = 0, beamsPerJob = 0;
  double batchSeconds = 0, separateSeconds = 0;
  double ratio() const { return separateSeconds / batchSeconds; }
};

// Large jobs in one session: the batch's wall time (trace, resolve and
// writing overlapped with the next job's trace) against the sum of the
// traces' device time.
struct BatchOverheadRow {
  std::string deviceName;
  uint64_t jobs = 0, beamsPerJob = 0;
  double batchWallSeconds = 0, traceDeviceSeconds = 0;
  uint64_t bufferAllocations = 0;  // device buffers allocated for all the jobs (reused when they fit)
  double overhead() const { return batchWallSeconds / traceDeviceSeconds - 1.0; }
};

// The cost profile of the kernel on the throughput scene: its time with
// the kernel cut after each stage (shaders/profile.h), on one device; device
// time on Vulkan, wall time of the trace on the CPU, each the least of 3
// runs taken in turn.
struct ProfileRow {
  DeviceKind device = DeviceKind::Cpu;
  std::string deviceName;
  uint64_t beams = 0;
  std::vector<double> stageSeconds;  // one per ProfileStage, in order
  double nsPerBeam(size_t stage) const { return stageSeconds[stage] / double(beams) * 1e9; }
};
// The stages' names, in ProfileStage order (each adds one to the one before),
// then the default kernel (colour from bins) in place of per-beam colour.
inline const char* const kProfileStageNames[] = {"Philox",
                                                 "+ light choice",
                                                 "+ wavelength",
                                                 "+ emission",
                                                 "+ sensor",
                                                 "+ counting (bins)",
                                                 "+ exact colour (per beam)",
                                                 "+ aiming and weights (full kernel, per-beam colour)",
                                                 "default: full kernel, colour from bins"};

// The same on the optics bench's mesh scene (light paths only): the
// emission stage, then the stages of a beam among objects.
struct ObjectsProfileRow {
  DeviceKind device = DeviceKind::Cpu;
  std::string deviceName;
  uint64_t beams = 0;
  uint64_t triangles = 0;
  std::vector<double> stageSeconds;  // one per kObjectsProfileStages entry, in order
  double nsPerBeam(size_t stage) const { return stageSeconds[stage] / double(beams) * 1e9; }
};
inline constexpr uint32_t kObjectsProfileStages[] = {device::kProfileStageEmission,
                                                     device::kProfileStageObjectsFirstHit,
                                                     device::kProfileStageObjectsNoConnection,
                                                     device::kProfileStageFull};
// Each names what it adds to the one before.
inline const char* const kObjectsProfileStageNames[] = {
    "emission (Philox, light, wavelength, origin and direction)",
    "+ first object hit (BVH traversal, primitive tests)",
    "+ camera test, material, later bounces, counting (no connection)",
    "+ camera connection (shadow ray, its count): full kernel"};

// spectrace's full kernel (exact colour on) against the ceiling kernel
// (backend/ceiling.h) on the throughput scene, one device, same run and measure.
struct CeilingRow {
  DeviceKind device = DeviceKind::Cpu;
  std::string deviceName;
  uint64_t beams = 0;
  double ceilingSeconds = 0.0, spectraceSeconds = 0.0;
  uint64_t ceilingHits = 0;
  double ratio() const { return ceilingSeconds / spectraceSeconds; }  // spectrace : ceiling, beams/s
};

struct BenchReport {
  std::string date;       // UTC, ISO 8601
  std::string machine;    // CPU model and cores
  std::vector<DeviceSpec> devices;
  std::vector<ThroughputRow> throughput;
  std::vector<SpecialisationRow> specialisation;
  std::vector<TrimRow> trim;
  std::vector<AimRow> aim;
  std::vector<PipelineCacheRow> pipelineCache;
  std::vector<BatchProcessRow> batchProcesses;
  std::vector<BatchOverheadRow> batchOverhead;
  std::vector<ProfileRow> profile;
  std::vector<ObjectsProfileRow> objectsProfile;
  std::vector<CeilingRow> ceiling;
  std::vector<RayCeilingRow> rayCeiling;  // the CPU's, by mesh size, the largest last
  std::vector<SweepRow> sweep;
  std::vector<ColourBinRow> colour;
  std::vector<OpticsRow> optics;
};

// Writes DIR/benchmarks.md and DIR/bench/{*.csv,*.png}. Plots need gnuplot;
// without it the report says so and keeps the tables. A section of an
// existing DIR/benchmarks.md that starts with kNotesHeading, and everything
// after it, is hand-written and kept.
inline constexpr const char* kNotesHeading = "## Notes (hand-written";
void writeBenchReport(const std::filesystem::path& dir, const BenchReport& report);

}  // namespace spectrace
