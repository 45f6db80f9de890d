#include "bench/error_bench.h"

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "colour/colour.h"
#include "compile/compile_scene.h"
#include "reference/exact_solution.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "scene/scene_builders.h"

namespace spectrace {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Colour from bins converges to the bin-averaged colour, not the exact one:
// compare each resolve with what it estimates.
ReferenceImage toReference(const ExactImage& exact, bool exactColour) {
  ReferenceImage ref;
  ref.width = exact.width;
  ref.height = exact.height;
  ref.irradiance = exact.irradiance;
  ref.valid = exact.valid;
  for (const auto& c : exactColour ? exact.xyz : exact.xyzBinned) ref.xyz.insert(ref.xyz.end(), c.begin(), c.end());
  return ref;
}

// Renders beams [0, beams) of `plan` on `tracer` (emptied first): the row
// gets the wall time of trace + develop and the device times; returns the
// image and the film.
std::pair<RenderImage, SpectralHistogram> timedRender(Tracer& tracer, const Scene& scene, const CompiledScene& plan,
                                                      uint64_t beams, SweepRow& row) {
  const ResolveParameters parameters = resolveParametersFor(scene, plan, beams);
  tracer.clear();
  const double traceBefore = tracer.traceDeviceSeconds(), developBefore = tracer.developDeviceSeconds();
  const auto start = Clock::now();
  tracer.trace(0, beams);
  RenderImage image = tracer.develop(parameters);
  row.wallSeconds = since(start);
  row.traceDeviceSeconds = tracer.traceDeviceSeconds() - traceBefore;
  row.resolveDeviceSeconds = tracer.developDeviceSeconds() - developBefore;
  return {std::move(image), tracer.download()};
}

// A tracer for one scene, warmed up: the first dispatch of each pipeline
// compiles it, which stays out of the timings.
std::unique_ptr<Tracer> warmTracer(const Device& device, const Scene& scene, const CompiledScene& plan) {
  auto tracer = device.makeTracer(plan);
  tracer->trace(0, 4096);
  tracer->develop(resolveParametersFor(scene, plan, 4096));
  return tracer;
}

}  // namespace

std::vector<SweepRow> runErrorSweep(const std::vector<DeviceSpec>& devices, const SweepOptions& options) {
  std::vector<SweepRow> rows;
  for (const auto& device : devices) {
    const auto opened = Device::open(device);
    for (const auto& path : options.scenes) {
      const Scene scene = loadScene(path);
      const auto exact = exactSolution(scene);
      if (!exact) throw std::runtime_error(fmt::format("{}: no exact solution is known for this scene", path));
      const ReferenceImage reference = toReference(*exact, options.plan.exactColour);
      const CompiledScene plan = compileScene(scene, options.seed, options.plan);
      const auto tracer = warmTracer(*opened, scene, plan);
      for (uint64_t beams : options.beamCounts) {
        SweepRow row;
        row.scene = std::filesystem::path(path).stem().string();
        row.device = device.kind();
        row.deviceName = device.name();
        row.beams = beams;
        row.exactColour = options.plan.exactColour;
        row.aimed = options.plan.aim;
        for (const auto& light : plan.device.lights) row.aimedLights += light.aimed != 0;
        auto [image, histogram] = timedRender(*tracer, scene, plan, beams, row);
        row.hits = histogram.countedBeams;
        row.metrics = computeErrorMetrics(image, reference, estimatedRelativeVariance(histogram, beams));
        row.fom = figureOfMerit(row.metrics.relMse, row.wallSeconds);
        if (options.onRow) options.onRow(row);
        rows.push_back(row);
      }
    }
  }
  return rows;
}

std::vector<ColourBinRow> runColourBinStudy(const DeviceSpec& device, uint64_t beams,
                                            const std::function<void(const ColourBinRow&)>& onRow) {
  const auto opened = Device::open(device);
  const Observer& observer = cie1931Observer();
  struct NamedSpd {
    std::string name;
    Spd spd;
  };
  const std::vector<NamedSpd> spds = {{"D65", *cieIlluminant("D65")},
                                      {"F11", *cieIlluminant("F11")},
                                      {"LED-B3", *cieIlluminant("LED-B3")},
                                      {"line 532 nm", makeLineSpd(532.0)}};
  std::vector<ColourBinRow> rows;
  for (const auto& named : spds) {
    for (int bins : {16, 32, 64, 94, 471}) {
      // Uniform irradiance: a collimated beam wider than a small bare sensor.
      Scene scene = bareSensorScene(0.01, 0.01, 8, 8, bins);
      Light laser = surfaceLight(LightType::Laser, {0.0, 0.0, 0.1}, {0.0, 0.0, -1.0}, 1.0, named.spd, named.name);
      laser.radiusM = 0.0075;
      scene.lights = {laser};
      const CompiledScene plan = compileScene(scene, 5);
      const auto tracer = warmTracer(*opened, scene, plan);
      SweepRow timing;
      auto [image, histogram] = timedRender(*tracer, scene, plan, beams, timing);

      const Spd inRange = named.spd.clipped(360.0, 830.0);
      const auto exactXyz = spdToXyz(inRange, observer);
      const auto exactXy = chromaticity(exactXyz);
      ResolveParameters parameters = resolveParametersFor(scene, plan, beams);
      // The film by reference: clang 14 cannot capture a structured binding.
      auto meanXyz = [&, &film = histogram](bool exactColour) {
        parameters.useExactColour = exactColour;
        const RenderImage resolved = resolveOnCpu(film, parameters);
        std::array<double, 3> sum{0, 0, 0};
        for (size_t i = 0; i < resolved.xyz.size(); ++i) sum[i % 3] += resolved.xyz[i];
        return sum;
      };
      const auto binned = meanXyz(false), perBeam = meanXyz(true);
      // The pixels' chromaticity variance in two passes (mean, then squared
      // deviations): the one-pass sumXX - sumX^2 / n cancels to a small
      // negative number, and a NaN sigma, for a line spectrum's equal pixels.
      const size_t pixels = image.irradiance.size();
      std::vector<std::array<double, 2>> xys(pixels);
      double sumX = 0, sumY = 0;
      for (size_t p = 0; p < pixels; ++p) {
        xys[p] = chromaticity({image.xyz[p * 3], image.xyz[p * 3 + 1], image.xyz[p * 3 + 2]});
        sumX += xys[p][0];
        sumY += xys[p][1];
      }
      const double n = double(pixels), meanX = sumX / n, meanY = sumY / n;
      double squaresX = 0, squaresY = 0;
      for (const auto& xy : xys) {
        squaresX += (xy[0] - meanX) * (xy[0] - meanX);
        squaresY += (xy[1] - meanY) * (xy[1] - meanY);
      }
      const double varX = squaresX / (n - 1), varY = squaresY / (n - 1);
      auto chromaError = [&](const std::array<double, 3>& xyz) {
        const auto xy = chromaticity(xyz);
        return std::hypot(xy[0] - exactXy[0], xy[1] - exactXy[1]);
      };
      // Colours compared at equal luminance, white = D65 at that luminance.
      auto deltaE = [&](std::array<double, 3> xyz) {
        const double y = xyz[1];
        std::array<double, 3> ref = exactXyz;
        for (double& v : ref) v *= y / exactXyz[1];
        const std::array<double, 3> white{0.95047 * y, y, 1.08883 * y};
        return ciede2000(xyzToLab(xyz, white), xyzToLab(ref, white));
      };
      // The bias of binning alone: bin-averaged CMFs weighted exactly.
      const auto weights = binAveragedCmf(observer, 360.0, 830.0, bins);
      std::array<double, 3> expected{0, 0, 0};
      const double binWidth = 470.0 / bins;
      for (int b = 0; b < bins; ++b) {
        const Spd part = inRange.clipped(360.0 + b * binWidth, 360.0 + (b + 1) * binWidth);
        const double power = part.lambdaNm.empty() ? 0.0 : part.integral();
        for (int k = 0; k < 3; ++k) expected[k] += power * weights[b][k];
      }
      ColourBinRow row;
      row.spd = named.name;
      row.bins = bins;
      row.beams = beams;
      row.binnedChromaticityError = chromaError(binned);
      row.exactChromaticityError = chromaError(perBeam);
      row.binnedDeltaE = deltaE(binned);
      row.exactDeltaE = deltaE(perBeam);
      row.expectedBinnedChromaticityError = chromaError(expected);
      row.chromaticitySigma = std::sqrt((varX + varY) / n);
      if (onRow) onRow(row);
      rows.push_back(row);
    }
  }
  return rows;
}

void writeSweepCsv(const std::filesystem::path& file, const std::vector<SweepRow>& rows) {
  std::ofstream out(file);
  out << "scene,device,device_name,aimed,beams,counted,wall_s,trace_device_s,resolve_device_s,beams_per_s,rel_rmse,rel_mse,"
         "bias,de2000_mean,de2000_p99,chromaticity_error,estimated_rel_rmse,honesty,fom\n";
  for (const auto& r : rows) {
    const auto& m = r.metrics;
    out << fmt::format("{},{},\"{}\",{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n",
                       r.scene, deviceKindName(r.device), r.deviceName, int(r.aimed), r.beams, r.hits, r.wallSeconds, r.traceDeviceSeconds,
                       r.resolveDeviceSeconds, double(r.beams) / r.wallSeconds, m.relRmse, m.relMse, m.bias,
                       m.deltaE2000Mean, m.deltaE2000P99, m.meanChromaticityError, m.estimatedRelRmse, m.honesty, r.fom);
  }
}

void writeColourCsv(const std::filesystem::path& file, const std::vector<ColourBinRow>& rows) {
  std::ofstream out(file);
  out << "spd,bins,beams,binned_chromaticity_error,expected_binned_chromaticity_error,exact_chromaticity_error,"
         "chromaticity_sigma,binned_de2000,exact_de2000\n";
  for (const auto& r : rows)
    out << fmt::format("\"{}\",{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n", r.spd, r.bins, r.beams,
                       r.binnedChromaticityError, r.expectedBinnedChromaticityError, r.exactChromaticityError,
                       r.chromaticitySigma, r.binnedDeltaE, r.exactDeltaE);
}

double convergenceSlope(const std::vector<SweepRow>& rows) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(rows.size());
  for (const auto& r : rows) {
    const double x = std::log(double(r.beams)), y = std::log(r.metrics.relRmse);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace spectrace
