#pragma once
// The CLI verbs, each a small function over the library; main() only parses.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "backend/device.h"
#include "session/session.h"

namespace spectrace::cli {

struct RenderCommand {
  PipelineCacheOptions pipelineCache;           // --pipeline-cache PATH, --no-pipeline-cache
  std::vector<std::filesystem::path> scenes;    // rendered one after another on one device
  // default out/<scene stem>.exr; with several scenes, a folder (DIR/ or an
  // existing directory) that holds <scene stem>.exr
  std::optional<std::filesystem::path> output;
  std::optional<uint64_t> beams;                // default: the scene's render.beams
  std::optional<uint64_t> seed;                 // default: the scene's render.seed
  uint64_t firstBeam = 0;
  std::string device = "auto";
  unsigned threads = 0;
  std::string cpuCode = "auto";                 // --cpu-code: auto, baseline or x86-64-v3
  bool png = true;
  bool quiet = false;
  double checkpointSeconds = 60.0;
  bool fullSpectrum = false;   // store every bin, not only those the lights reach
  bool spectral = false;       // spectral EXR channels (also when the scene's output.spectral is true)
  bool fullSensor = false;     // store every pixel, not only those beams can reach
  bool general = false;        // the general trace pipeline, not one specialised to the scene
  bool perBeamColour = false;  // per-beam colour counters even where colour from bins applies
  bool noAim = false;          // analog emission: beams in every direction the lights emit
  bool noConnect = false;      // analog transport: no camera connections at diffuse surfaces
  std::string estimator = "both";  // light, camera or both (compile/estimators.h)
  std::optional<uint32_t> wavelengthsPerBeam;  // default: the scene's render.wavelengths_per_beam
  // The exact render state (film/film_state.h), rewritten at checkpoints
  // and at the end; one scene only.
  std::optional<std::filesystem::path> state;
  std::optional<std::filesystem::path> resume;  // go on from this state (and keep writing it)
  std::optional<std::string> shard;             // "I/K": beams of the I-th (0-based) of K equal parts
  bool mpi = false;  // split the beams over the MPI ranks; rank 0 writes (cli/mpi_render.cpp)
  // --set POINTER=JSON, as given, in order: fields of every scene file
  // replaced before it is parsed (as a batch job's "set").
  std::vector<std::string> overrides;
};
int runRender(const RenderCommand& command, const std::atomic<bool>& cancel);
// The jobs of a render command, checked (throws UsageError and the scene's
// errors: bad input). `checkOutputs`: also check that each output can be
// written (checkOutputPath), which creates its folder.
std::vector<RenderJob> renderJobsOf(const RenderCommand& command, const std::atomic<bool>& cancel, bool checkOutputs);
// render --mpi: this process is one rank of an mpirun (cli/mpi_render.cpp;
// without MPI support, a UsageError saying so).
int runMpiRender(const RenderCommand& command, const std::atomic<bool>& cancel);

int runDevices();

struct BatchCommand {
  PipelineCacheOptions pipelineCache;           // --pipeline-cache PATH, --no-pipeline-cache
  std::filesystem::path jobs;                   // JSON Lines job file
  std::string device = "auto";
  std::optional<std::filesystem::path> outDir;  // relative outputs resolve here (default: the job file's folder)
  bool skipExisting = false;                    // skip jobs whose EXR holds all their beams
  bool failFast = false;                        // stop at the first failed job (default: keep going)
  bool quiet = false;
  bool png = true;
};
// Exit code 0 when every job rendered (or was skipped), 2 when any failed.
int runBatch(const BatchCommand& command, const std::atomic<bool>& cancel);

struct MergeCommand {
  std::vector<std::filesystem::path> states;     // render states of disjoint beam ranges
  std::filesystem::path output;                  // the EXR of the merged film
  std::optional<std::filesystem::path> state;    // also write the merged state
  std::string device = "auto";
  bool spectral = false;
  bool png = true;
  bool quiet = false;
};
// Exit code 2 when the states cannot be merged (the message says which field differs).
int runMerge(const MergeCommand& command);

struct MeasureCommand {
  std::filesystem::path exr;                   // any render's image
  std::optional<std::string> region;           // "x0,y0,x1,y1": columns [x0, x1), rows [y0, y1) from the top
  std::optional<std::filesystem::path> json;   // the statistics
  std::optional<std::filesystem::path> csv;    // lux per pixel of the region
  std::optional<std::filesystem::path> falseColour;  // PNG map with legend and isolux contours
  std::optional<double> maxLux;                // the map's top (default: its maximum, rounded up)
};
// Illuminance statistics of a render (printed), and the files asked for.
// Exit code 2 for an unreadable image, a bad region or output path.
int runMeasure(const MeasureCommand& command);

struct BenchCommand {
  uint64_t beams = uint64_t(1) << 25;   // throughput section, per device
  std::string devices;                  // "gpu", "cpu", device names; empty = all
  unsigned threads = 0;
  std::optional<std::filesystem::path> out;  // write benchmarks.md, CSV and plots here
  std::filesystem::path scenesDir;      // reference scenes (default scenes/reference)
  double minDecade = 3, maxDecade = 8;  // error sweep: 10^min .. 10^max beams in x10 steps
  uint64_t colourBeams = 50'000'000;    // per render of the colour-from-binning study
  bool throughput = true, sweep = true, colour = true, specialisation = true, aim = true, optics = true;
  bool batch = true;          // batch section: one batch against many processes, overhead of large jobs
  bool pipelineCache = true;  // batch section: time to first beam, cold vs warm pipeline cache
  bool profile = true;        // the kernel's cost by stage (shaders/profile.h)
  bool ceiling = true;        // spectrace against the ceiling kernel (backend/ceiling.h)
  bool fom = true;            // the scenes matched with pbrt-v4 (scenes/bench/fom_*): error per second
  uint64_t profileBeams = uint64_t(1) << 23;  // per stage and device, and per ceiling run
};
// The sections --only names, each with the flag that runs it: the one list
// that the help text, the refusal of an unknown name and --only all read.
struct BenchSection {
  const char* name;
  bool BenchCommand::*run;
};
inline constexpr BenchSection kBenchSections[] = {
    {"throughput", &BenchCommand::throughput}, {"specialisation", &BenchCommand::specialisation},
    {"aim", &BenchCommand::aim},               {"batch", &BenchCommand::batch},
    {"sweep", &BenchCommand::sweep},           {"colour", &BenchCommand::colour},
    {"profile", &BenchCommand::profile},       {"ceiling", &BenchCommand::ceiling},
    {"optics", &BenchCommand::optics},         {"fom", &BenchCommand::fom}};
// "throughput, specialisation, ...": kBenchSections' names, for messages.
std::string benchSectionNames();
// --only: keeps only the comma-separated sections of kBenchSections;
// UsageError for an unknown name.
void selectBenchSections(BenchCommand& command, const std::string& list);
int runBench(const BenchCommand& command, const std::atomic<bool>& cancel);

}  // namespace spectrace::cli
