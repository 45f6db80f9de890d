#include "bench/report.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

namespace spectrace {
namespace {

// Runs gnuplot on a script; false when gnuplot is missing or fails.
bool runGnuplot(const std::filesystem::path& script) {
  return std::system(fmt::format("gnuplot '{}' > /dev/null 2>&1", script.string()).c_str()) == 0;
}

std::vector<std::string> uniqueInOrder(const std::vector<std::string>& items) {
  std::vector<std::string> out;
  for (const auto& i : items)
    if (std::find(out.begin(), out.end(), i) == out.end()) out.push_back(i);
  return out;
}

bool plotErrorVsTime(const std::filesystem::path& dir, const BenchReport& report) {
  std::vector<std::string> scenes, devices;
  for (const auto& r : report.sweep) {
    scenes.push_back(r.scene);
    devices.push_back(r.deviceName);
  }
  scenes = uniqueInOrder(scenes);
  devices = uniqueInOrder(devices);
  const int columns = 4, rows = int((scenes.size() + columns - 1) / columns);
  std::ofstream gp(dir / "error_vs_time.gp");
  gp << fmt::format("set terminal pngcairo size 1600,{} font 'sans,9'\nset output '{}'\n", 380 * rows,
                    (dir / "error_vs_time.png").string());
  gp << "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\nset grid\nset key bottom left\n";
  gp << fmt::format("set multiplot layout {},{} title 'relative RMSE of pixel irradiance against wall time (trace + resolve)'\n",
                    rows, columns);
  for (const auto& scene : scenes) {
    gp << fmt::format("set title '{}' noenhanced\nset xlabel 'seconds'\nset ylabel 'relative RMSE'\n", scene);
    std::string plot = "plot ";
    double anchorT = 0, anchorE = 0;
    for (size_t d = 0; d < devices.size(); ++d) {
      gp << fmt::format("$d{}_{} << EOD\n", d, &scene - scenes.data());
      for (const auto& r : report.sweep) {
        if (r.scene != scene || r.deviceName != devices[d] || !(r.metrics.relRmse > 0)) continue;
        gp << fmt::format("{:.6g} {:.6g}\n", r.wallSeconds, r.metrics.relRmse);
        if (d == 0) {
          anchorT = r.wallSeconds;
          anchorE = r.metrics.relRmse;
        }
      }
      gp << "EOD\n";
      plot += fmt::format("$d{}_{} with linespoints lw 2 title '{}' noenhanced, ", d, &scene - scenes.data(), devices[d]);
    }
    // Guide: error proportional to time^-1/2 through the first device's last point.
    plot += fmt::format("{:.6g}*(x/{:.6g})**-0.5 with lines dt 2 lc 'gray' title 'N^{{-1/2}}'", anchorE, anchorT);
    gp << plot << "\n";
  }
  gp << "unset multiplot\n";
  gp.close();
  return runGnuplot(dir / "error_vs_time.gp");
}

bool plotColourBins(const std::filesystem::path& dir, const BenchReport& report) {
  if (report.colour.empty()) return false;
  std::vector<std::string> spds;
  for (const auto& r : report.colour) spds.push_back(r.spd);
  spds = uniqueInOrder(spds);
  std::ofstream gp(dir / "colour_bins.gp");
  gp << fmt::format("set terminal pngcairo size 1000,600 font 'sans,10'\nset output '{}'\n", (dir / "colour_bins.png").string());
  gp << "set logscale xy\nset grid\nset key outside right\nset xlabel 'wavelength bins (360-830 nm)'\n"
        "set ylabel 'chromaticity error |Δ(x,y)| of the image mean'\nset xtics (16,32,64,94,471)\n"
        "set title 'colour from bin-averaged CMFs (solid) vs per-beam CMFs (dashed)'\n";
  std::string plot = "plot ";
  for (size_t s = 0; s < spds.size(); ++s) {
    gp << fmt::format("$c{} << EOD\n", s);
    for (const auto& r : report.colour)
      if (r.spd == spds[s])
        gp << fmt::format("{} {:.6g} {:.6g}\n", r.bins, std::max(r.binnedChromaticityError, 1e-9),
                          std::max(r.exactChromaticityError, 1e-9));
    gp << "EOD\n";
    plot += fmt::format("$c{0} using 1:2 with linespoints lw 2 lc {1} title '{2}, bins', "
                        "$c{0} using 1:3 with linespoints lw 2 dt 2 lc {1} title '{2}, per beam', ",
                        s, s + 1, spds[s]);
  }
  plot += "5e-5 with lines lc 'gray' dt 3 title 'target 5e-5'";
  gp << plot << "\n";
  gp.close();
  return runGnuplot(dir / "colour_bins.gp");
}

void writeProfileCsv(const std::filesystem::path& file, const std::vector<ProfileRow>& rows) {
  std::ofstream csv(file);
  csv << "device,device_name,beams,stage,stage_name,seconds,ns_per_beam,increment_ns_per_beam,share_of_full\n";
  for (const auto& r : rows) {
    const double full = r.nsPerBeam(device::kProfileStageFull);
    for (size_t s = 0; s < r.stageSeconds.size(); ++s) {
      const double increment = r.nsPerBeam(s) - (s ? r.nsPerBeam(s - 1) : 0.0);
      csv << fmt::format("{},\"{}\",{},{},\"{}\",{:.6g},{:.6g},{:.6g},{:.6g}\n", deviceKindName(r.device), r.deviceName,
                         r.beams, s, kProfileStageNames[s], r.stageSeconds[s], r.nsPerBeam(s), increment, increment / full);
    }
  }
}

void writeObjectsProfileCsv(const std::filesystem::path& file, const std::vector<ObjectsProfileRow>& rows) {
  std::ofstream csv(file);
  csv << "device,device_name,beams,triangles,stage,stage_name,seconds,ns_per_beam,increment_ns_per_beam,share_of_full\n";
  for (const auto& r : rows) {
    const double full = r.nsPerBeam(r.stageSeconds.size() - 1);
    for (size_t s = 0; s < r.stageSeconds.size(); ++s) {
      const double increment = r.nsPerBeam(s) - (s ? r.nsPerBeam(s - 1) : 0.0);
      csv << fmt::format("{},\"{}\",{},{},{},\"{}\",{:.6g},{:.6g},{:.6g},{:.6g}\n", deviceKindName(r.device),
                         r.deviceName, r.beams, r.triangles, kObjectsProfileStages[s], kObjectsProfileStageNames[s],
                         r.stageSeconds[s], r.nsPerBeam(s), increment, increment / full);
    }
  }
}

void writeCeilingCsv(const std::filesystem::path& file, const std::vector<CeilingRow>& rows) {
  std::ofstream csv(file);
  csv << "device,device_name,beams,ceiling_s,spectrace_s,ceiling_beams_per_s,spectrace_beams_per_s,spectrace_to_ceiling,"
         "ceiling_hits\n";
  for (const auto& r : rows)
    csv << fmt::format("{},\"{}\",{},{:.6g},{:.6g},{:.6g},{:.6g},{:.4f},{}\n", deviceKindName(r.device), r.deviceName, r.beams,
                       r.ceilingSeconds, r.spectraceSeconds, double(r.beams) / r.ceilingSeconds,
                       double(r.beams) / r.spectraceSeconds, r.ratio(), r.ceilingHits);
}

void writeRayCeilingCsv(const std::filesystem::path& file, const std::vector<RayCeilingRow>& rows) {
  std::ofstream csv(file);
  csv << "tracer,triangles,rays,threads,seconds,rays_per_s,bytes_per_triangle,spectrace_to_embree,hits,"
         "hit_miss_disagreements,other_primitive,distance_disagreements\n";
  for (const auto& r : rows) {
    auto line = [&](const char* tracer, unsigned threads, double seconds, double bytes, double ratio) {
      csv << fmt::format("{},{},{},{},{:.6g},{:.6g},{:.1f},{:.4f},{},{},{},{}\n", tracer, r.triangles, r.rays, threads,
                         seconds, double(r.rays) / seconds, bytes, ratio, r.hits, r.disagreements.hitMiss,
                         r.disagreements.otherPrimitive, r.disagreements.distance);
    };
    line("spectrace", 1, r.spectrace1, r.bytesPerTriangle, 1.0);
    line("spectrace", r.threads, r.spectraceN, r.bytesPerTriangle, 1.0);
    line("spectrace_interleaved", 1, r.interleaved1, r.bytesPerTriangle, r.embree ? r.interleavedRatio1() : 1.0);
    line("spectrace_interleaved", r.threads, r.interleavedN, r.bytesPerTriangle, r.embree ? r.interleavedRatioN() : 1.0);
    if (!r.embree) continue;
    line("embree", 1, r.embree1, r.embreeBytesPerTriangle, r.ratio1());
    line("embree", r.threads, r.embreeN, r.embreeBytesPerTriangle, r.ratioN());
  }
}

void writeProfileSection(std::ofstream& md, const BenchReport& report) {
  md << "## Profile: where a beam's time goes, and the ceiling\n\n";
  if (!report.profile.empty()) {
    md << "The throughput scene (exact colour on) with the kernel cut after each stage (`shaders/profile.h`, "
          "specialisation constant `kSpecProfileStage`): each stage adds one part of the kernel to the one "
          "before. Up to \"+ exact colour\" beams are emitted unaimed with unit weight; \"+ counting\" counts "
          "the bin only. Device time of the trace pass on Vulkan, wall time of the trace on the CPU, each the "
          "least of 3 runs taken in turn, all in this run. The increment is a stage's own cost; its share is "
          "of the full kernel.\n\n";
    for (const auto& r : report.profile) {
      const double full = r.nsPerBeam(device::kProfileStageFull);
      md << fmt::format("{} ({} beams per stage):\n\n", r.deviceName, r.beams);
      md << "| stage | ns/beam | increment ns/beam | share of full |\n| --- | ---: | ---: | ---: |\n";
      for (size_t s = 0; s < r.stageSeconds.size(); ++s) {
        const double increment = r.nsPerBeam(s) - (s ? r.nsPerBeam(s - 1) : 0.0);
        md << fmt::format("| {} | {:.2f} | {:+.2f} | {:.1f}% |\n", kProfileStageNames[s], r.nsPerBeam(s), increment,
                          100.0 * increment / full);
      }
      md << "\n";
    }
    md << "All rows: [bench/profile.csv](bench/profile.csv).\n\n";
  }
  if (!report.objectsProfile.empty()) {
    md << "### Objects profile\n\nThe optics bench's mesh scene (a grey diffuse sphere lit by a spot, through a "
          "pinhole), light paths only, with the kernel cut after emission, after the beam's first object hit, and "
          "without camera connections, then whole: each row adds what it names to the one before. The scene is "
          "compiled once, so no row includes building the BVH. Timed as above.\n\n";
    for (const auto& r : report.objectsProfile) {
      const double full = r.nsPerBeam(r.stageSeconds.size() - 1);
      md << fmt::format("{} ({} triangles, {} beams per stage):\n\n", r.deviceName, r.triangles, r.beams);
      md << "| stage | ns/beam | increment ns/beam | share of full |\n| --- | ---: | ---: | ---: |\n";
      for (size_t s = 0; s < r.stageSeconds.size(); ++s) {
        const double increment = r.nsPerBeam(s) - (s ? r.nsPerBeam(s - 1) : 0.0);
        md << fmt::format("| {} | {:.2f} | {:+.2f} | {:.1f}% |\n", kObjectsProfileStageNames[s], r.nsPerBeam(s),
                          increment, 100.0 * increment / full);
      }
      md << "\n";
    }
    md << "All rows: [bench/objects_profile.csv](bench/objects_profile.csv).\n\n";
  }
  if (!report.ceiling.empty()) {
    md << "The ceiling: the same scene's work with no exactness guarantees (`shaders/ceiling.comp` on Vulkan, "
          "plain scalar C++ on the CPU in `host/backend/ceiling.cpp`): a PCG hash of the beam index for random "
          "numbers, the wavelength by a float CDF search over D65 at 1 nm, cosine-weighted disk emission, the "
          "sensor plane, one 32-bit atomic per counted beam. Against spectrace's full kernel with exact colour "
          "on; device time against device time on Vulkan, wall against wall on the CPU; same run.\n\n";
    md << "| device | beams | ceiling Mbeam/s | spectrace Mbeam/s | spectrace : ceiling |\n| --- | ---: | ---: | ---: | ---: |\n";
    for (const auto& r : report.ceiling)
      md << fmt::format("| {} | {} | {:.2f} | {:.2f} | {:.3f} |\n", r.deviceName, r.beams,
                        double(r.beams) / r.ceilingSeconds * 1e-6, double(r.beams) / r.spectraceSeconds * 1e-6, r.ratio());
    md << "\n[bench/ceiling.csv](bench/ceiling.csv).\n\n";
  }
  if (!report.rayCeiling.empty()) {
    // The largest mesh in full; the others in the table by size.
    const RayCeilingRow& r = report.rayCeiling.back();
    md << "### Ray ceiling (Embree)\n\n";
    md << fmt::format("{} incoherent closest-hit rays (from points around the mesh, each towards a "
                      "point in a ball about it) through the optics bench's mesh of {} triangles, by the shared "
                      "kernel's BVH walk (`intersectObjects`, on the CPU, {} code as the renderer runs it) and by "
                      "Intel Embree {}; wall time, least of 2, same run.\n\n",
                      r.rays, r.triangles, r.cpuCode, r.embree ? "(RTC_BUILD_QUALITY_HIGH, rtcIntersect1)" : "(unavailable in this build)");
    md << "| tracer | threads | Mray/s | bytes/triangle | spectrace : Embree |\n| --- | ---: | ---: | ---: | ---: |\n";
    const double m = double(r.rays) * 1e-6;
    md << fmt::format("| spectrace | 1 | {:.3f} | {:.1f} | |\n", m / r.spectrace1, r.bytesPerTriangle);
    md << fmt::format("| spectrace | {} | {:.3f} | {:.1f} | |\n", r.threads, m / r.spectraceN, r.bytesPerTriangle);
    const auto interleavedRatio = [&](double ratio) { return r.embree ? fmt::format("{:.3f}", ratio) : std::string(); };
    md << fmt::format("| spectrace, {} walks in turn | 1 | {:.3f} | {:.1f} | {} |\n", kCeilingWalksInFlight,
                      m / r.interleaved1, r.bytesPerTriangle, interleavedRatio(r.interleavedRatio1()));
    md << fmt::format("| spectrace, {} walks in turn | {} | {:.3f} | {:.1f} | {} |\n", kCeilingWalksInFlight, r.threads,
                      m / r.interleavedN, r.bytesPerTriangle, interleavedRatio(r.interleavedRatioN()));
    if (r.embree) {
      md << fmt::format("| Embree | 1 | {:.3f} | {:.1f} | {:.3f} |\n", m / r.embree1, r.embreeBytesPerTriangle, r.ratio1());
      md << fmt::format("| Embree | {} | {:.3f} | {:.1f} | {:.3f} |\n", r.threads, m / r.embreeN, r.embreeBytesPerTriangle,
                        r.ratioN());
      md << fmt::format("\n{} of {} rays hit; they disagree on hit or miss for {}, on the primitive for {} (edge "
                        "ties), on the distance (beyond 1e-5 of it) for {}.\n",
                        r.hits, r.rays, r.disagreements.hitMiss, r.disagreements.otherPrimitive, r.disagreements.distance);
    }
    md << fmt::format("\nspectrace's bytes are the CPU reference's (128-byte nodes); the Vulkan trace reads the same "
                      "tree with 64-byte packed nodes, {:.1f} bytes a triangle.\n",
                      r.vulkanBytesPerTriangle);
    if (report.rayCeiling.size() > 1 && r.embree) {
      md << "\nBy the mesh's size, one thread each, the rays built alike for every mesh: where the tree fits "
            "in the caches, the ratio is the walk's instructions against Embree's; on the large meshes, their "
            "waits on memory too.\n\n";
      md << "| triangles | spectrace Mray/s | Embree Mray/s | spectrace : Embree |\n| ---: | ---: | ---: | ---: |\n";
      for (const RayCeilingRow& s : report.rayCeiling)
        md << fmt::format("| {} | {:.3f} | {:.3f} | {:.3f} |\n", s.triangles, double(s.rays) * 1e-6 / s.spectrace1,
                          double(s.rays) * 1e-6 / s.embree1, s.ratio1());
    }
    md << fmt::format("\nWalks in turn: each thread steps {} walks one node or leaf at a time, as the CPU reference's "
                      "threads step their beams' walks on a tree larger than the last-level cache; {} rays hit differently from "
                      "one walk at a time.\n",
                      kCeilingWalksInFlight, r.interleavedDifferences);
    md << "\n[bench/ray_ceiling.csv](bench/ray_ceiling.csv).\n\n";
  }
}

}  // namespace

namespace {

// Scenes with objects: rates, figures of merit, and the same-run ratios the
// optics issue asks for (connection : analog, BVH : brute force, GPU : CPU),
// and the draws' cost against the emitter's size.
void writeOpticsSection(std::ostream& md, const std::vector<OpticsRow>& rows) {
  md << "## Optics: scenes with objects\n\n";
  md << "Beams through objects (shaders/transport.h). relMSE comes from two renders with seeds 1 and 2: "
        "sum (A - B)^2 / 2 over sum R^2, where R is the mean of the scene's connected (or only) renders; FOM = "
        "1 / (relMSE x trace seconds), trace seconds the lesser of the two. Analog transport (`--no-connect`) is "
        "given ten times the beams.\n\n";
  md << "| scene | variant | device | primitives | beams | counted | trace s | Mbeam/s | relMSE | FOM |\n";
  md << "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const OpticsRow& r : rows)
    md << fmt::format("| {} | {} | {} | {} | {} | {} | {:.3f} | {:.2f} | {:.3g} | {:.4g} |\n", r.scene, r.variant,
                      r.deviceName, r.primitives, r.beams, r.counted, r.traceSeconds, r.beamsPerSecond() * 1e-6,
                      r.relMse, r.fom);
  md << "\nRatios, same run:\n\n";
  auto find = [&](const std::string& scene, const std::string& variant, const std::string& device) -> const OpticsRow* {
    for (const OpticsRow& r : rows)
      if (r.scene == scene && r.variant == variant && r.deviceName == device) return &r;
    return nullptr;
  };
  for (const OpticsRow& r : rows) {
    if (r.variant == "connect")
      if (const OpticsRow* analog = find(r.scene, "analog", r.deviceName))
        md << fmt::format("- {} on {}: FOM camera connection : analog = **{:.3g}**\n", r.scene, r.deviceName,
                          r.fom / analog->fom);
    if (r.variant == "bvh")
      if (const OpticsRow* brute = find(r.scene, "brute force", r.deviceName))
        md << fmt::format("- {} on {}: beams/s BVH : brute force = **{:.3g}** ({})\n", r.scene, r.deviceName,
                          r.beamsPerSecond() / brute->beamsPerSecond(),
                          brute->sameImageAsFirst ? "the same image bit for bit" : "the images differ");
  }
  // The O(1) draws: each emission-only row against its scene's first (the
  // smallest table or the single primitive), and the whole beams likewise.
  const std::string kCut = ", emission";
  const auto isCut = [&](const OpticsRow& r) {
    return r.variant.size() > kCut.size() && r.variant.compare(r.variant.size() - kCut.size(), kCut.size(), kCut) == 0;
  };
  for (const OpticsRow& r : rows) {
    if (!isCut(r)) continue;
    const OpticsRow* first = nullptr;
    for (const OpticsRow& f : rows)
      if (!first && isCut(f) && f.scene == r.scene && f.deviceName == r.deviceName) first = &f;
    if (first == &r) continue;
    const std::string smallest = first->variant.substr(0, first->variant.size() - kCut.size());
    const std::string size = r.variant.substr(0, r.variant.size() - kCut.size());
    const OpticsRow* wholeFirst = find(r.scene, smallest, r.deviceName);
    const OpticsRow* whole = find(r.scene, size, r.deviceName);
    md << fmt::format("- {} on {}: emission beams/s {} : {} = **{:.3g}**", r.scene, r.deviceName, smallest, size,
                      first->beamsPerSecond() / r.beamsPerSecond());
    if (wholeFirst && whole)
      md << fmt::format(" (whole beams {:.3g})", wholeFirst->beamsPerSecond() / whole->beamsPerSecond());
    md << "\n";
  }
  for (const OpticsRow& gpu : rows)
    for (const OpticsRow& cpu : rows)
      if (!gpu.reference && cpu.reference && gpu.scene == cpu.scene && gpu.variant == cpu.variant)
        md << fmt::format("- {} ({}): beams/s {} : {} = {:.2f}\n", gpu.scene, gpu.variant, gpu.deviceName,
                          cpu.deviceName, gpu.beamsPerSecond() / cpu.beamsPerSecond());
  md << "\n";
}

}  // namespace

void writeBenchReport(const std::filesystem::path& dir, const BenchReport& report) {
  const auto data = dir / "bench";
  std::filesystem::create_directories(data);
  // Only the sections that ran have rows; a skipped one writes no file (an
  // empty CSV would read as a measurement of nothing).
  if (!report.sweep.empty()) writeSweepCsv(data / "error_sweep.csv", report.sweep);
  if (!report.colour.empty()) writeColourCsv(data / "colour_bins.csv", report.colour);
  if (!report.profile.empty()) writeProfileCsv(data / "profile.csv", report.profile);
  if (!report.objectsProfile.empty())
    writeObjectsProfileCsv(data / "objects_profile.csv", report.objectsProfile);
  if (!report.ceiling.empty()) writeCeilingCsv(data / "ceiling.csv", report.ceiling);
  if (!report.rayCeiling.empty()) writeRayCeilingCsv(data / "ray_ceiling.csv", report.rayCeiling);
  if (!report.aim.empty()) {
    std::vector<SweepRow> aimRows;
    for (const auto& a : report.aim) aimRows.insert(aimRows.end(), {a.aimed, a.analog});
    writeSweepCsv(data / "aim.csv", aimRows);
  }
  if (!report.throughput.empty()) {
    std::ofstream csv(data / "throughput.csv");
    csv << "device,device_name,exact_colour,beams,hits,wall_s,trace_device_s,beams_per_s\n";
    for (const auto& t : report.throughput)
      csv << fmt::format("{},\"{}\",{},{},{},{:.6g},{:.6g},{:.6g}\n", deviceKindName(t.device), t.deviceName, int(t.exactColour),
                         t.beams, t.hits, t.wallSeconds, t.traceDeviceSeconds, double(t.beams) / t.wallSeconds);
  }
  const bool errorPlot = !report.sweep.empty() && plotErrorVsTime(data, report);
  const bool colourPlot = plotColourBins(data, report);

  // Hand-written notes at the end of an existing report survive regeneration.
  std::string notes;
  {
    std::ifstream old(dir / "benchmarks.md");
    const std::string text((std::istreambuf_iterator<char>(old)), std::istreambuf_iterator<char>());
    const auto at = text.find(kNotesHeading);
    if (at != std::string::npos) notes = text.substr(at);
  }
  std::ofstream md(dir / "benchmarks.md");
  md << "# Benchmarks\n\n";
  md << "Generated by `spectrace bench --out " << dir.string() << "` on " << report.date << ".\n\n";
  md << "Machine: " << report.machine << ". Devices:\n\n";
  for (const auto& d : report.devices) md << "- " << deviceKindName(d.kind()) << ": " << d.name() << "\n";
  md << "\nEvery ratio below compares figures taken in this one run (the machine's timings vary by 10-20% "
        "between runs).\n\n";

  if (!report.throughput.empty()) {
    md << "## Throughput: fixed scene (D65 disk light, bare 512x512 sensor, 64 bins)\n\n";
    md << "| device | exact colour | beams | wall s | Mbeam/s (wall) | Mbeam/s (device time) | hit rate |\n";
    md << "| --- | --- | ---: | ---: | ---: | ---: | ---: |\n";
    for (const auto& t : report.throughput)
      md << fmt::format("| {} | {} | {} | {:.3f} | {:.2f} | {} | {:.1f}% |\n", t.deviceName, t.exactColour ? "on" : "off",
                        t.beams, t.wallSeconds, double(t.beams) / t.wallSeconds * 1e-6,
                        t.traceDeviceSeconds > 0 ? fmt::format("{:.2f}", double(t.beams) / t.traceDeviceSeconds * 1e-6) : "-",
                        100.0 * double(t.hits) / double(t.beams));
    md << "\nRatios (wall-clock beams/s):\n\n";
    for (const auto& a : report.throughput)
      for (const auto& b : report.throughput)
        if (a.exactColour == b.exactColour && !a.reference && b.reference)
          md << fmt::format("- {} : {} (exact colour {}) = {:.2f}\n", a.deviceName, b.deviceName, a.exactColour ? "on" : "off",
                            b.wallSeconds / a.wallSeconds * double(a.beams) / double(b.beams));
    for (const auto& a : report.throughput)
      for (const auto& b : report.throughput)
        if (a.deviceName == b.deviceName && a.exactColour && !b.exactColour)
          md << fmt::format("- cost of exact colour on {}: beams/s with it : without it = {:.2f}\n", a.deviceName,
                            (double(a.beams) / a.wallSeconds) / (double(b.beams) / b.wallSeconds));
    md << "\n";
  }

  if (!report.profile.empty() || !report.objectsProfile.empty() || !report.ceiling.empty() || !report.rayCeiling.empty()) writeProfileSection(md, report);

  if (!report.specialisation.empty()) {
    md << "## Pipelines specialised to the scene\n\n";
    md << "Specialisation constants compile out the light types a scene lacks, the choice among lights when "
          "there is one, the camera model's branch, the exact-colour path and the aiming code. Device time of the trace "
          "pass, each the least of 3 runs taken in turn with the other variants, all in this run; the results are "
          "bit-identical "
          "(`Render.SpecialisedPipelineMatchesGeneralBitForBit`).\n\n";
    md << "| scene | device | beams | general Mbeam/s | specialised Mbeam/s | specialised : general |";
    for (const char* name : kSpecialisedFeatureNames) md << " " << name << " alone |";
    md << "\n| --- | --- | ---: | ---: | ---: | ---: |";
    for (size_t i = 0; i < std::size(kSpecialisedFeatureNames); ++i) md << " ---: |";
    md << "\n";
    for (const auto& r : report.specialisation) {
      md << fmt::format("| {} | {} | {} | {:.2f} | {:.2f} | {:.2f} |", r.scene, r.deviceName, r.beams,
                        double(r.beams) / r.generalSeconds * 1e-6, double(r.beams) / r.specialisedSeconds * 1e-6,
                        r.generalSeconds / r.specialisedSeconds);
      for (double s : r.featureSeconds) md << fmt::format(" {:.2f} |", r.generalSeconds / s);
      md << "\n";
    }
    md << "\nThe \"alone\" columns are general : (only that feature specialised), beams/s ratios. Compiling out "
          "code can pay even where the scene never takes its branch (the aiming code in scenes with no aimed "
          "light): the shader gets smaller.\n\n";
  }

  if (!report.batchProcesses.empty() || !report.batchOverhead.empty() || !report.pipelineCache.empty()) {
    md << "## Batch\n\n";
    md << "Many renders in one process (`spectrace batch`, a Session): the device is opened once, pipelines and "
          "device buffers are kept between jobs, and each job's writing (error channel, EXR, PNG) overlaps the "
          "next job's trace.\n\n";
  }
  if (!report.batchProcesses.empty()) {
    md << "### Small jobs: one batch against one process per job\n\n";
    md << "A sweep over the blackbody temperature of `scenes/batch/lamp.json`: one `spectrace batch` process "
          "against one `spectrace render` process per job, wall time of the processes (start-up, device, "
          "trace, writing the EXR), same run, same pipeline cache. Target on lavapipe: at least 10x.\n\n";
    md << "| device | jobs | beams per job | one batch s | separate processes s | separate : batch |\n";
    md << "| --- | ---: | ---: | ---: | ---: | ---: |\n";
    for (const auto& r : report.batchProcesses)
      md << fmt::format("| {} | {} | {} | {:.2f} | {:.2f} | {:.1f} |\n", r.deviceName, r.jobs, r.beamsPerJob,
                        r.batchSeconds, r.separateSeconds, r.ratio());
    md << "\n";
  }
  if (!report.batchOverhead.empty()) {
    md << "### Large jobs: batch wall time against device time\n\n";
    md << "Large jobs of `scenes/batch/lamp.json` in one session (device already open): wall time from the first "
          "job's start to the last job's files written, against the sum of the trace passes' device time "
          "(timestamps). Target: within 5%.\n\n";
    md << "| device | jobs | beams per job | batch wall s | trace device s | overhead | buffer allocations |\n";
    md << "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const auto& r : report.batchOverhead)
      md << fmt::format("| {} | {} | {} | {:.2f} | {:.2f} | {:+.1f}% | {} |\n", r.deviceName, r.jobs, r.beamsPerJob,
                        r.batchWallSeconds, r.traceDeviceSeconds, 100.0 * r.overhead(), r.bufferAllocations);
    md << "\n";
  }
  if (!report.pipelineCache.empty()) {
    md << "### Time to first beam, cold and warm pipeline cache\n\n";
    md << "Wall time from opening the Vulkan device to the end of a first small render (pipelines compiled, "
          "4096 beams traced and resolved), first with an empty pipeline cache file, then with the file that run "
          "saved; same run. Drivers that keep nothing in the Vulkan pipeline cache (lavapipe stores only the "
          "header and relies on Mesa's own shader cache) show a ratio near 1.\n\n";
    md << "| device | cold s | warm s | cold : warm | cache bytes |\n|---|---|---|---|---|\n";
    for (const auto& r : report.pipelineCache)
      md << fmt::format("| {} | {:.3f} | {:.3f} | {:.2f} | {} |\n", r.deviceName, r.coldSeconds, r.warmSeconds,
                        r.ratio(), r.cacheBytes);
    md << "\n";
  }

  if (!report.optics.empty()) writeOpticsSection(md, report.optics);
  if (!report.aim.empty()) {
    md << "## Beams aimed at the camera\n\n";
    md << "Aimed sampling draws each light's beams only towards the pinhole (or the bare sensor) and weights "
          "them by emission density over sampling density; analog sampling (`--no-aim`) emits as the light "
          "does. Both against the exact answer, each at its own beam count, in this run. FOM = 1 / (relMSE x "
          "wall seconds of trace and resolve); \"counted\" beams are those that reach the sensor and are "
          "added to the histogram. Expected values agree (`AimedVersusAnalog.*`). Lights whose target cone "
          "would be wider than their own emission (close to a bare sensor, or a laser thinner than the target) "
          "stay analog, so those scenes show the cost of the check alone.\n\n";
    md << "| scene | device | sampling | beams | counted | Mbeam/s all | Mbeam/s counted | relRMSE | FOM | FOM aimed : analog |\n";
    md << "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    auto sampling = [](const SweepRow& r) {
      if (!r.aimed) return std::string("analog");
      return r.aimedLights > 0 ? std::string("aimed") : std::string("aimed (no light gains: analog)");
    };
    for (const auto& a : report.aim) {
      for (const SweepRow* r : {&a.aimed, &a.analog})
        md << fmt::format("| {} | {} | {} | {:.0e} | {:.3g}% | {:.2f} | {:.3g} | {:.3g} | {:.4g} | {} |\n", r->scene,
                          r->deviceName, sampling(*r), double(r->beams),
                          100.0 * double(r->hits) / double(r->beams), double(r->beams) / r->wallSeconds * 1e-6,
                          double(r->hits) / r->wallSeconds * 1e-6, r->metrics.relRmse, r->fom,
                          r->aimed ? fmt::format("**{:.3g}**", a.fomGain()) : "");
    }
    md << "\n";
  }

  if (!report.trim.empty()) {
    md << "## Trimmed spectra and sensor\n\n";
    md << "The device stores only the wavelength bins the scene's lights can reach and the rectangle of pixels "
          "beams can reach (histograms and images are bit-identical, "
          "`Render.TrimmedSpectrumMatchesFullSpectrumBitForBit`, `Render.TrimmedSensorMatchesFullSensorBitForBit`), and resolves only those pixels. Device memory of "
          "the histogram and device time of the trace and resolve passes (each the least of 3 runs taken in turn), "
          "untrimmed against trimmed, in this run.\n\n";
    md << "| scene | device | bins stored | pixels stored | histogram MiB | trace s | resolve ms |\n"
          "| --- | --- | ---: | ---: | ---: | ---: | ---: |\n";
    for (const auto& r : report.trim)
      md << fmt::format("| {} | {} | {} → {} | {} → {} | {:.2f} → {:.2f} | {:.3f} → {:.3f} | {:.2f} → {:.2f} |\n", r.scene,
                        r.deviceName, r.fullBins, r.storedBins, r.fullPixels, r.storedPixels, r.fullMiB, r.trimmedMiB, r.fullTraceSeconds,
                        r.trimmedTraceSeconds, r.fullResolveSeconds * 1e3, r.trimmedResolveSeconds * 1e3);
    md << "\n";
  }

  if (!report.sweep.empty()) {
    md << "## Error against time on the reference scenes\n\n";
    md << "Each scene in `scenes/reference/` has an exact answer (`host/reference`). Beams are swept over "
          "the counts below on each device; the error is the relative RMSE of the pixel irradiance; the "
          "dashed line is the Monte Carlo rate N^-1/2.\n\n";
    if (errorPlot) md << "![error against time](bench/error_vs_time.png)\n\n";
    else md << "(gnuplot was not available: no plot.)\n\n";

    std::map<std::string, std::map<std::string, SweepRow>> largest;  // scene -> device -> largest-N row
    std::vector<std::string> scenes, devices;
    for (const auto& r : report.sweep) {
      scenes.push_back(r.scene);
      devices.push_back(r.deviceName);
      auto& slot = largest[r.scene][r.deviceName];
      if (r.beams >= slot.beams) slot = r;
    }
    scenes = uniqueInOrder(scenes);
    devices = uniqueInOrder(devices);
    md << "### Figure of merit at the largest beam count (FOM = 1 / (relMSE x seconds))\n\n| scene | beams |";
    for (const auto& d : devices) md << " FOM " << d << " |";
    if (devices.size() > 1) md << " ratio " << devices[0] << " : " << devices[1] << " |";
    md << " relRMSE | estimated relRMSE | bias | ΔE2000 mean / p99 | chromaticity error |\n| --- | ---: |";
    for (size_t i = 0; i < devices.size() + (devices.size() > 1 ? 1 : 0); ++i) md << " ---: |";
    md << " ---: | ---: | ---: | ---: | ---: |\n";
    for (const auto& s : scenes) {
      const SweepRow& first = largest[s][devices[0]];
      md << fmt::format("| {} | {:.0e} |", s, double(first.beams));
      for (const auto& d : devices) md << fmt::format(" {:.4g} |", largest[s][d].fom);
      if (devices.size() > 1) md << fmt::format(" {:.2f} |", largest[s][devices[0]].fom / largest[s][devices[1]].fom);
      const auto& m = first.metrics;
      md << fmt::format(" {:.3g} | {:.3g} | {:+.2e} | {:.3f} / {:.3f} | {:.2e} |\n", m.relRmse, m.estimatedRelRmse, m.bias,
                        m.deltaE2000Mean, m.deltaE2000P99, m.meanChromaticityError);
    }
    md << "\n(The error columns are the first device's; the devices trace the same beams.)\n\n";

    md << "### Convergence slope of relRMSE over the three largest beam counts (N^-1/2 is -0.5)\n\n";
    md << "| scene |";
    for (const auto& d : devices) md << " " << d << " |";
    md << "\n| --- |";
    for (size_t i = 0; i < devices.size(); ++i) md << " ---: |";
    md << "\n";
    for (const auto& s : scenes) {
      md << "| " << s << " |";
      for (const auto& d : devices) {
        std::vector<SweepRow> rows;
        for (const auto& r : report.sweep)
          if (r.scene == s && r.deviceName == d) rows.push_back(r);
        std::sort(rows.begin(), rows.end(), [](const SweepRow& a, const SweepRow& b) { return a.beams < b.beams; });
        if (rows.size() > 3) rows.erase(rows.begin(), rows.end() - 3);
        md << fmt::format(" {:.3f} |", convergenceSlope(rows));
      }
      md << "\n";
    }
    md << "\nAll rows, with device times split into trace and resolve: [bench/error_sweep.csv](bench/error_sweep.csv).\n\n";
  }

  if (!report.colour.empty()) {
    md << "## Colour error from binning\n\n";
    md << "Uniform irradiance of each SPD, colour of the image mean from the histogram's bin-averaged CMFs "
          "against colour from each beam's own CMF values (the per-pixel exact-colour sums), both against "
          "the exact integral of SPD x CMF. \"expected\" is the bias of binning computed without noise.\n\n";
    if (colourPlot) md << "![colour error against bins](bench/colour_bins.png)\n\n";
    md << "| SPD | bins | beams | chromaticity error, bins (expected) | chromaticity error, per beam | noise σ | ΔE2000 bins | ΔE2000 per beam |\n";
    md << "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const auto& r : report.colour)
      md << fmt::format("| {} | {} | {:.0e} | {:.2e} ({:.2e}) | {:.2e} | {:.1e} | {:.4f} | {:.4f} |\n", r.spd, r.bins,
                        double(r.beams), r.binnedChromaticityError, r.expectedBinnedChromaticityError,
                        r.exactChromaticityError, r.chromaticitySigma, r.binnedDeltaE, r.exactDeltaE);
    md << "\n";
  }
  if (!notes.empty()) md << notes;
}

}  // namespace spectrace
