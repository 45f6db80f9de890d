#pragma once
// The benchmark's outputs: CSV files, gnuplot plots and a markdown report
// with the plots embedded and every ratio taken within the same run.
#include <filesystem>
#include <string>
#include <vector>

#include "bench/error_bench.h"

namespace spectrace {

struct ThroughputRow {
  std::string device, deviceName;
  bool exactColour = true;
  uint64_t beams = 0, hits = 0;
  double wallSeconds = 0.0, traceDeviceSeconds = 0.0;
};

// Beams/s of the general and the scene-specialised trace pipeline.
struct SpecialisationRow {
  std::string scene, deviceName;
  uint64_t beams = 0;
  double generalSeconds = 0.0, specialisedSeconds = 0.0;  // device time of the trace pass
};

// Storing the full spectrum against only the bins the lights reach.
struct TrimRow {
  std::string scene, deviceName;
  uint64_t beams = 0;
  uint32_t fullBins = 0, storedBins = 0;
  double fullMiB = 0.0, trimmedMiB = 0.0;                  // device histogram
  double fullTraceSeconds = 0.0, trimmedTraceSeconds = 0.0;  // device time
  double fullResolveSeconds = 0.0, trimmedResolveSeconds = 0.0;
};

struct BenchReport {
  std::string date;       // UTC, ISO 8601
  std::string machine;    // CPU model and cores
  std::vector<BenchDevice> devices;
  std::vector<ThroughputRow> throughput;
  std::vector<SpecialisationRow> specialisation;
  std::vector<TrimRow> trim;
  std::vector<SweepRow> sweep;
  std::vector<ColourBinRow> colour;
};

// Writes DIR/benchmarks.md and DIR/bench/{*.csv,*.png}. Plots need gnuplot;
// without it the report says so and keeps the tables.
void writeBenchReport(const std::filesystem::path& dir, const BenchReport& report);

}  // namespace spectrace
