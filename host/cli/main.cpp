// spectrace: spectral light tracer. Parses the command line and hands over
// to the verbs in commands.cpp.
#include <CLI/CLI.hpp>
#include <malloc.h>

#include <atomic>
#include <climits>
#include <csignal>
#include <memory>
#include <string>
#include <cstdio>

#include "cli/cli_numbers.h"
#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "cli/version.h"

namespace {
std::atomic<bool> gCancel{false};
extern "C" void onSignal(int) { gCancel.store(true); }

int fail(int code, const char* message) {
  std::fprintf(stderr, "spectrace: error: %s\n", message);
  return code;
}

// CLI11 shows a flag declared "!--no-png" (false when given) as
// "--no-png{false}"; the braces are its bookkeeping, not something to type.
class HelpFormatter : public CLI::Formatter {
 public:
  std::string make_option_name(const CLI::Option* option, bool positional) const override {
    std::string name = CLI::Formatter::make_option_name(option, positional);
    for (size_t open = name.find('{'); open != std::string::npos; open = name.find('{', open)) {
      const size_t close = name.find('}', open);
      if (close == std::string::npos) break;
      name.erase(open, close - open + 1);
    }
    return name;
  }
};
}  // namespace

int main(int argc, char** argv) {
  using namespace spectrace;
  using namespace spectrace::cli;
  // Loading a large mesh allocates and frees arrays of tens of megabytes in
  // turn (the OBJ text, its vertices and faces, the BVH builder's items and
  // nodes). glibc maps each from the kernel and unmaps it when freed, so
  // every one's pages fault in afresh; kept in the heap, they are reused.
  // A million-triangle scene's process ran 0.15 s shorter of about 0.95 s
  // of start-up (docs/benchmarks.md); the cost is that the process keeps
  // its peak heap until it exits.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
  CLI::App app{"spectrace: a spectral light tracer on Vulkan compute, with an exact CPU reference"};
  app.formatter(std::make_shared<HelpFormatter>());  // before the subcommands, which copy it
  app.require_subcommand(1);
  app.set_version_flag("--version", versionText(), "Print the version (and the git commit built) and exit");
  // CLI11's parse errors start like every other error (exit code 2).
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("spectrace: error: ") + e.what() + "\nRun with --help for more information.\n";
  });

  RenderCommand render;
  auto* renderCmd = app.add_subcommand("render", "Render a scene file to OpenEXR (and a PNG preview)");
  renderCmd->add_option("scene", render.scenes, "Scene files (JSON), rendered one after another on one device")
      ->required()
      ->type_name("PATH");
  renderCmd->add_option("-o,--output", render.output,
                        "Output EXR (default out/<scene>.exr); with several scenes, a folder (DIR/)")
      ->type_name("PATH");
  renderCmd->add_option_function<std::string>(
      "--beams", [&](const std::string& v) { render.beams = parseU64("--beams", v, 1); },
      "Number of beams, 1 to 2^64-1 (default: the scene's render.beams)")
      ->type_name("COUNT");
  renderCmd->add_option_function<std::string>(
      "--seed", [&](const std::string& v) { render.seed = parseU64("--seed", v, 0); },
      "RNG seed, 0 to 2^64-1 (default: the scene's render.seed)")
      ->type_name("INT");
  renderCmd->add_option_function<std::string>(
      "--first-beam", [&](const std::string& v) { render.firstBeam = parseU64("--first-beam", v, 0); },
      "Index of the first beam (to split a render into parts); first beam + beams <= 2^64")
      ->type_name("INT")
      ->default_str("0");
  renderCmd->add_option("--device", render.device, "auto, gpu (any Vulkan device, lavapipe included) or cpu")
      ->check(CLI::IsMember({"auto", "gpu", "cpu"}))
      ->type_name("DEVICE")
      ->capture_default_str();
  renderCmd->add_option_function<std::string>(
      "--threads", [&](const std::string& v) { render.threads = parseThreads("--threads", v); },
      "CPU reference threads, 1 to 1024 (default: all)")
      ->type_name("COUNT");
  renderCmd->add_option("--cpu-code", render.cpuCode,
                        "CPU reference's machine code: auto (the fastest this processor runs), baseline or x86-64-v3; "
                        "all draw the same beams bit for bit")
      ->check(CLI::IsMember({"auto", "baseline", "x86-64-v3"}))
      ->type_name("CODE")
      ->capture_default_str();
  renderCmd->add_flag("!--no-png", render.png, "Do not write the PNG preview");
  renderCmd->add_flag("-q,--quiet", render.quiet, "Print only errors");
  renderCmd->add_option("--pipeline-cache", render.pipelineCache.path, "Vulkan pipeline cache file (default: under $XDG_CACHE_HOME/spectrace)")
      ->type_name("PATH");
  renderCmd->add_flag("!--no-pipeline-cache", render.pipelineCache.enabled, "Neither read nor write a Vulkan pipeline cache file");
  renderCmd->add_flag("--full-spectrum", render.fullSpectrum,
                      "Store every wavelength bin on the device, not only those the lights can reach");
  renderCmd->add_flag("--spectral", render.spectral,
                      "Also write one EXR channel per wavelength bin, S0.<nm>nm in W.m^-2.nm^-1 "
                      "(default: the scene's output.spectral)");
  renderCmd->add_flag("--full-sensor", render.fullSensor,
                      "Store every pixel on the device, not only those the beams can reach");
  renderCmd->add_flag("--general-pipeline", render.general,
                      "Use the general trace pipeline instead of one specialised to the scene");
  renderCmd->add_flag("--no-aim", render.noAim,
                      "Analog emission (the reference): do not aim beams at the pinhole or sensor");
  renderCmd->add_flag("--no-connect", render.noConnect,
                      "Analog transport (the reference): count only beams that reach the camera themselves, without "
                      "connecting diffuse surfaces to the camera");
  renderCmd
      ->add_option("--estimator", render.estimator,
                   "Which paths count: light (beams from the lights, the reference), camera (paths from the pixels, "
                   "sampling the lights at diffuse surfaces; needs a pinhole or a lens) or both, each path of light counted by "
                   "one of them")
      ->check(CLI::IsMember({"light", "camera", "both"}))
      ->type_name("ESTIMATOR")
      ->default_str("both");
  renderCmd
      ->add_option("--wavelengths-per-beam", render.wavelengthsPerBeam,
                   "Wavelengths each beam and camera path carries, stratified over its light's spectrum: 1, 2 or 4 "
                   "(default: the scene's render.wavelengths_per_beam, else 4)")
      ->check(CLI::IsMember({1u, 2u, 4u}))
      ->type_name("K");
  renderCmd->add_flag("--per-beam-colour", render.perBeamColour,
                      "Sum each counted beam's own CMF values per pixel (the reference), even where colour from the "
                      "bins is exact in expectation (one spectral table)");
  renderCmd->add_option_function<std::string>(
      "--checkpoint-seconds",
      [&](const std::string& v) { render.checkpointSeconds = parseNonNegativeSeconds("--checkpoint-seconds", v); },
      "Write the image so far at this interval, a finite number >= 0 (0: never)")
      ->type_name("SECONDS")
      ->default_str("60");
  renderCmd->add_option("--state", render.state, "Also write the exact render state (docs/state-format.md)")
      ->type_name("PATH");
  renderCmd->add_option("--resume", render.resume, "Go on from this render state, and keep writing it")
      ->type_name("PATH");
  renderCmd->add_option("--shard", render.shard, "I/K: render the I-th (0-based) of K equal beam ranges")
      ->type_name("I/K");
  // One value per --set, so that a scene path after it is not taken for another.
  renderCmd->add_option("--set", render.overrides,
                        "Replace a field of the scene file before it is checked: a JSON pointer, '=', a JSON value "
                        "(e.g. /lights/0/spd/blackbody_k=3000)")
      ->type_name("POINTER=JSON")
      ->allow_extra_args(false);
  renderCmd->add_flag("--mpi", render.mpi,
                      "Under mpirun: split the beams over the MPI ranks, sum their films exactly on rank 0, "
                      "which writes the image (docs/scaling.md)");

  MergeCommand merge;
  auto* mergeCmd = app.add_subcommand("merge", "Add render states of disjoint beam ranges exactly, write the image");
  mergeCmd->add_option("states", merge.states, "Render states (from render --state)")->required()->type_name("PATH");
  mergeCmd->add_option("-o,--output", merge.output, "Output EXR (and a PNG preview beside it)")
      ->required()
      ->type_name("PATH");
  mergeCmd->add_option("--state", merge.state, "Also write the merged state")->type_name("PATH");
  mergeCmd->add_option("--device", merge.device, "Where to develop: auto, gpu or cpu")
      ->check(CLI::IsMember({"auto", "gpu", "cpu"}))
      ->type_name("DEVICE")
      ->capture_default_str();
  mergeCmd->add_flag("--spectral", merge.spectral, "Also write one EXR channel per wavelength bin");
  mergeCmd->add_flag("!--no-png", merge.png, "Do not write the PNG preview");
  mergeCmd->add_flag("-q,--quiet", merge.quiet, "Print only errors");

  BatchCommand batch;
  auto* batchCmd = app.add_subcommand("batch", "Render the jobs of a JSON Lines job file on one device");
  batchCmd->add_option("jobs", batch.jobs, "Job file (JSON Lines: one job per line)")->required()->type_name("PATH");
  batchCmd->add_option("--device", batch.device, "auto, gpu (any Vulkan device, lavapipe included) or cpu")
      ->check(CLI::IsMember({"auto", "gpu", "cpu"}))
      ->type_name("DEVICE")
      ->capture_default_str();
  batchCmd->add_option("--out-dir", batch.outDir, "Folder relative outputs resolve against (default: the job file's)")
      ->type_name("DIR");
  batchCmd->add_flag("--skip-existing", batch.skipExisting, "Skip jobs whose EXR exists and holds all their beams");
  bool keepGoingFlag = false;
  auto* keepGoing = batchCmd->add_flag("--keep-going", keepGoingFlag, "Go on after a failed job (the default)");
  batchCmd->add_flag("--fail-fast", batch.failFast, "Stop at the first failed job")->excludes(keepGoing);
  batchCmd->add_flag("!--no-png", batch.png, "Do not write PNG previews");
  batchCmd->add_flag("-q,--quiet", batch.quiet, "Print only errors");
  batchCmd->add_option("--pipeline-cache", batch.pipelineCache.path, "Vulkan pipeline cache file (default: under $XDG_CACHE_HOME/spectrace)")
      ->type_name("PATH");
  batchCmd->add_flag("!--no-pipeline-cache", batch.pipelineCache.enabled, "Neither read nor write a Vulkan pipeline cache file");

  MeasureCommand measure;
  auto* measureCmd = app.add_subcommand(
      "measure", "Illuminance statistics of a render's image (lux from XYZ.Y): min, max, mean, U0, Ud");
  measureCmd->add_option("exr", measure.exr, "A render's OpenEXR image")->required()->type_name("PATH");
  measureCmd->add_option("--region", measure.region,
                         "Pixels to measure: columns [x0, x1) and rows [y0, y1), rows from the top (default: all)")
      ->type_name("x0,y0,x1,y1");
  measureCmd->add_option("--json", measure.json, "Write the statistics as JSON")->type_name("PATH");
  measureCmd->add_option("--csv", measure.csv, "Write the region's lux per pixel, rows from the top")->type_name("PATH");
  measureCmd->add_option("--false-colour", measure.falseColour,
                         "Write a false-colour PNG of the region with a lux legend and isolux contours")
      ->type_name("PATH");
  measureCmd->add_option("--max-lux", measure.maxLux,
                         "The false-colour legend's top (default: the maximum rounded up to 1, 2, 2.5 or 5 x 10^n)")
      ->type_name("LUX");

  auto* devicesCmd = app.add_subcommand("devices", "List Vulkan devices and the limits that matter here");

  BenchCommand bench;
  auto* benchCmd = app.add_subcommand("bench", "Beams per second: Vulkan device vs CPU reference on a fixed scene");
  benchCmd->add_option_function<std::string>(
      "--beams", [&](const std::string& v) { bench.beams = parseU64("--beams", v, 1); },
      "Beams per device in the throughput section")
      ->type_name("COUNT")
      ->default_str(std::to_string(bench.beams));
  benchCmd->add_option("--device", bench.devices, "Comma-separated devices: gpu, cpu or device names (default: all)")
      ->type_name("LIST");
  benchCmd->add_option_function<std::string>(
      "--threads", [&](const std::string& v) { bench.threads = parseThreads("--threads", v); },
      "CPU reference threads, 1 to 1024 (default: all)")
      ->type_name("COUNT");
  benchCmd->add_option("--out", bench.out, "Write benchmarks.md, CSV files and plots into this folder")
      ->type_name("DIR");
  benchCmd->add_option("--scenes", bench.scenesDir, "Folder of the reference scenes (default scenes/reference)")
      ->type_name("DIR");
  benchCmd->add_option("--min-decade", bench.minDecade, "Error sweep from 10^this beams")
      ->type_name("NUMBER")
      ->capture_default_str();
  benchCmd->add_option("--max-decade", bench.maxDecade, "Error sweep up to 10^this beams (x10 steps)")
      ->type_name("NUMBER")
      ->capture_default_str();
  benchCmd->add_option("--colour-beams", bench.colourBeams, "Beams per render of the colour-from-binning study")
      ->type_name("COUNT")
      ->capture_default_str();
  benchCmd->add_flag("!--no-throughput", bench.throughput, "Skip the throughput section");
  benchCmd->add_flag("!--no-sweep", bench.sweep, "Skip the error sweep");
  benchCmd->add_flag("!--no-colour", bench.colour, "Skip the colour-from-binning study");
  benchCmd->add_flag("!--no-specialisation", bench.specialisation, "Skip the specialised-pipeline comparison");
  benchCmd->add_flag("!--no-aim-study", bench.aim, "Skip the aimed-vs-analog comparison");
  benchCmd->add_flag("!--no-optics", bench.optics, "Skip the optics section (scenes with objects)");
  benchCmd->add_flag("!--no-fom", bench.fom, "Skip the error-per-second section (the scenes matched with pbrt-v4)");
  benchCmd->add_flag("!--no-pipeline-cache-study", bench.pipelineCache, "Skip the cold-vs-warm pipeline cache timing");
  benchCmd->add_flag("!--no-batch", bench.batch, "Skip the batch section (batch against processes, large jobs, pipeline cache)");
  benchCmd->add_option_function<std::string>(
      "--only",
      [&](const std::string& list) { selectBenchSections(bench, list); },
      "Run only these sections (comma-separated): " + benchSectionNames())
      ->type_name("LIST");
  benchCmd->add_option_function<std::string>(
      "--profile-beams", [&](const std::string& v) { bench.profileBeams = parseU64("--profile-beams", v, 1); },
      "Beams per stage and device in the profile and ceiling sections (a sixteenth of them in the objects "
      "profile; under 2^20, also the ray ceiling's rays, then through a 1,000-triangle mesh)")
      ->type_name("COUNT")
      ->default_str(std::to_string(bench.profileBeams));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help, or the parse error
    return code == 0 ? 0 : kExitBadInput;
  } catch (const UsageError& e) {
    return fail(kExitBadInput, e.what());
  }
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  try {
    if (renderCmd->parsed()) return runRender(render, gCancel);
    if (batchCmd->parsed()) return runBatch(batch, gCancel);
    if (mergeCmd->parsed()) return runMerge(merge);
    if (devicesCmd->parsed()) return runDevices();
    if (measureCmd->parsed()) return runMeasure(measure);
    if (benchCmd->parsed()) return runBench(bench, gCancel);
  } catch (...) {
    const Failure failure = failureOf(std::current_exception());
    return fail(failure.code, failure.message.c_str());
  }
  return 0;
}
