#pragma once
// Run time against error: renders the reference scenes (scenes/reference/,
// each with an exact answer from host/reference) on every device over a
// sweep of beam counts, and measures time and error of each render.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "backend/device.h"
#include "compile/compile_scene.h"
#include "metrics/error_metrics.h"

namespace spectrace {

struct SweepRow {
  std::string scene;
  DeviceKind device = DeviceKind::Cpu;
  std::string deviceName;
  uint64_t beams = 0, hits = 0;       // beams traced, beams counted
  double wallSeconds = 0.0;           // trace + resolve, host clock (no setup)
  double traceDeviceSeconds = 0.0;    // timestamps (GPU only)
  double resolveDeviceSeconds = 0.0;
  bool exactColour = true;
  bool aimed = true;                  // aimed sampling asked for
  int aimedLights = 0;                // lights it applied to (0: none gains from it)
  ErrorMetrics metrics;
  double fom = 0.0;                   // 1 / (relMSE * wallSeconds)
};

struct SweepOptions {
  std::vector<std::string> scenes;    // paths of reference scene files
  std::vector<uint64_t> beamCounts;   // e.g. 1e3 .. 1e8
  uint64_t seed = 1;
  CompileOptions plan;              // exact colour, aiming (false: analog, --no-aim), ...
  std::function<void(const SweepRow&)> onRow;
};

std::vector<SweepRow> runErrorSweep(const std::vector<DeviceSpec>& devices, const SweepOptions& options);

// Colour error from binning: uniform irradiance of one SPD at several bin
// counts, colour from bins vs from per-beam CMFs, against the exact colour.
struct ColourBinRow {
  std::string spd;
  int bins = 0;
  uint64_t beams = 0;
  double binnedChromaticityError = 0.0, exactChromaticityError = 0.0;   // of the image mean
  double binnedDeltaE = 0.0, exactDeltaE = 0.0;                         // CIEDE2000 of the image mean
  double expectedBinnedChromaticityError = 0.0;  // from exact integration of the bin-averaged CMF (no noise)
  // Monte Carlo standard error of the image mean's chromaticity, from the
  // scatter of the (independent, equally lit) pixels: an error below ~3x
  // this is noise, not bias.
  double chromaticitySigma = 0.0;
};
std::vector<ColourBinRow> runColourBinStudy(const DeviceSpec& device, uint64_t beams,
                                            const std::function<void(const ColourBinRow&)>& onRow = {});

// Writes `rows` as CSV.
void writeSweepCsv(const std::filesystem::path& file, const std::vector<SweepRow>& rows);
void writeColourCsv(const std::filesystem::path& file, const std::vector<ColourBinRow>& rows);

// Least-squares slope of log(relRmse) against log(beams) for the given rows.
double convergenceSlope(const std::vector<SweepRow>& rows);

}  // namespace spectrace
