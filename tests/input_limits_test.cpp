// Bounds on what spectrace reads and allocates (docs/reliability.md "Input
// limits" and "Memory bounds"): each refusal is a clear error naming the file
// and the field, found before the work or the memory is spent.
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "backend/vulkan_tracer.h"
#include "compile/compile_scene.h"
#include "json/input_file.h"
#include "json/json_fields.h"
#include "json/scene_error.h"
#include "render/renderer.h"
#include "backend/cpu_device.h"
#include "scene/scene.h"
#include "scene/scene_limits.h"
#include "session/job_file.h"
#include "spectrum/spd.h"

namespace spectrace {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

DeviceCapabilities cpuReference() { return CpuDevice::referenceCapabilities(); }

// One light, `bins` bins, `pixels` square; the light's spd is `spd` (JSON).
std::string sceneText(int pixels, int bins, const std::string& spd, int lights = 1) {
  std::string list;
  for (int i = 0; i < lights; ++i)
    list += std::string(i ? "," : "") +
            R"({"type": "point", "position": [0, 0, 1], "power_w": 1, "spd": )" + spd + "}";
  return R"({"spectrum": {"min_nm": 380, "max_nm": 780, "bins": )" + std::to_string(bins) +
         R"(}, "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1],
             "sensor": {"width_m": 0.024, "height_m": 0.024, "pixels": [)" +
         std::to_string(pixels) + ", " + std::to_string(pixels) + R"(]},
             "pinhole": {"distance_m": 0.05, "radius_m": 0.0015}},
  "lights": [)" + list + "]}";
}

struct InputLimits : ::testing::Test {
  fs::path dir;
  void SetUp() override {
    dir = fs::temp_directory_path() / ("spectrace_input_limits_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir / name, std::ios::binary) << text;
    return dir / name;
  }
};

template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

TEST_F(InputLimits, DeepJsonFailsAtTheDepthLimitNotAfterEatingMemory) {
  // 100,000 levels: refused at level 65 (this used to take 4.4 GB).
  const fs::path deep = write("deep.json", std::string(100000, '[') + std::string(100000, ']'));
  const std::string message = errorOf([&] { loadScene(deep); });
  EXPECT_THAT(message, HasSubstr(deep.string()));
  EXPECT_THAT(message, HasSubstr("nest more than 64 levels"));
  // Exactly at the limit is fine as JSON (then the scene schema speaks).
  json_fields::Source source;
  source.file = "x.json";
  const std::string atLimit = std::string(json_fields::kMaxJsonDepth, '[') + std::string(json_fields::kMaxJsonDepth, ']');
  EXPECT_NO_THROW(json_fields::parseJson(source, atLimit));
  const std::string over = "[" + atLimit + "]";
  EXPECT_THAT(errorOf([&] { json_fields::parseJson(source, over); }), HasSubstr("nest more than 64"));
  // Job files go through the same parser.
  const fs::path jobs = write("deep.jsonl", "{\"scene\": " + std::string(1000, '[') + std::string(1000, ']') + "}\n");
  JobReader reader(jobs);
  ASSERT_EQ(reader.total(), 1u);
  const auto entry = reader.next();
  ASSERT_TRUE(entry);
  EXPECT_THAT(entry->error, HasSubstr("nest more than 64"));
}

TEST_F(InputLimits, OnlyRegularFilesWithinTheSizeLimitAreRead) {
  EXPECT_THAT(errorOf([] { loadScene("/dev/zero"); }), HasSubstr("/dev/zero: is a device, not a scene file"));
  EXPECT_THAT(errorOf([&] { loadScene(dir); }), HasSubstr("is a directory, not a scene file"));
  const fs::path fifo = dir / "fifo.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Refused without opening it (opening a FIFO with no writer would block).
  EXPECT_THAT(errorOf([&] { loadScene(fifo); }), HasSubstr("is a pipe (FIFO), not a scene file"));
  EXPECT_THAT(errorOf([&] { loadCsvSpd(fifo); }), HasSubstr("is a pipe (FIFO), not a SPD file"));
  EXPECT_THAT(errorOf([&] { JobReader{fifo}; }), HasSubstr("is a pipe (FIFO), not a job file"));
  EXPECT_THAT(errorOf([] { loadCsvSpd("/dev/zero"); }), HasSubstr("/dev/zero: is a device"));
  // A sparse file one byte over the limit: refused by its size, unread.
  const fs::path big = dir / "big.json";
  std::ofstream(big).close();
  fs::resize_file(big, kMaxInputFileBytes + 1);
  EXPECT_THAT(errorOf([&] { loadScene(big); }), HasSubstr("is 67108865 bytes; at most 67108864 bytes (64 MiB) are read"));
  fs::resize_file(big, kMaxInputFileBytes);  // at the limit it is read (and is not JSON)
  EXPECT_THAT(errorOf([&] { loadScene(big); }), HasSubstr("invalid JSON"));
  const fs::path small = write("small.txt", "0123456789");
  EXPECT_EQ(readInputFile(small, "file", 10), "0123456789");
  EXPECT_EQ(readInputFile(small, "file", UINT64_MAX), "0123456789");  // no bound (state files)
  EXPECT_THROW(readInputFile(small, "file", 9), InputFileError);
}

TEST_F(InputLimits, LightCountIsBounded) {
  const std::string spd = R"({"blackbody_k": 3000})";
  EXPECT_NO_THROW(parseScene(sceneText(4, 8, spd, kMaxLights), dir / "many.json"));
  const std::string message = errorOf([&] { parseScene(sceneText(4, 8, spd, kMaxLights + 1), dir / "many.json"); });
  EXPECT_THAT(message, HasSubstr("many.json: /lights: has 4097 lights; a scene has at most 4096"));
}

TEST_F(InputLimits, SpectrumRowsAreBoundedInCsvAndInlineTables) {
  std::string rows;
  rows.reserve(16 * (kMaxSpdPoints + 1));
  for (size_t i = 0; i <= kMaxSpdPoints; ++i) rows += std::to_string(300.0 + double(i) * 1e-4) + ",1\n";
  const fs::path csv = write("rows.csv", rows);
  const fs::path scene = write("rows.json", sceneText(4, 8, R"({"csv": "rows.csv"})"));
  const std::string message = errorOf([&] { loadScene(scene); });
  EXPECT_THAT(message, HasSubstr("rows.json: /lights/0/spd/csv"));
  EXPECT_THAT(message, HasSubstr("rows.csv:1000001: more than 1000000 data rows"));
  std::vector<double> lambda(kMaxSpdPoints + 1), value(kMaxSpdPoints + 1, 1.0);
  for (size_t i = 0; i < lambda.size(); ++i) lambda[i] = 300.0 + double(i) * 1e-4;
  EXPECT_THAT(errorOf([&] { makeTabulatedSpd(lambda, value); }), HasSubstr("at most 1000000 points (got 1000001)"));
}

TEST_F(InputLimits, AFilmThatDoesNotFitInMemoryIsRefusedBeforeTracing) {
  // 16384^2 pixels x 100,000 bins: about 600,000 GiB of histogram.
  Scene scene = parseScene(sceneText(16384, kMaxBins, R"({"blackbody_k": 3000})"), dir / "huge.json");
  scene.render.wavelengthsPerBeam = 1;  // a plain film: one word a counter
  const CompiledScene plan = compileScene(scene, 1, {});
  const uint64_t bytes = filmHostBytes(plan, cpuReference(), false);
  const uint64_t histogramBytes = uint64_t(16384) * 16384 * kMaxBins * 8;
  EXPECT_GE(bytes, 2 * histogramBytes);  // the result's histogram and the downloaded one
  // Without a download only the CPU reference's counters (the stored
  // pixels and bins) hold the film; still far too large here.
  const uint64_t withoutDownload = filmHostBytes(plan, cpuReference(), false, false);
  EXPECT_EQ(bytes - withoutDownload, 2 * histogramBytes);
  EXPECT_GE(withoutDownload, plan.film.storedCounterCount() * sizeof(uint64_t));
  EXPECT_THROW(checkFilmFitsMemory(scene, plan, cpuReference(), false, false), SceneError);
  const std::string message = errorOf([&] { checkFilmFitsMemory(scene, plan, cpuReference(), false); });
  EXPECT_THAT(message, HasSubstr("huge.json: /camera/sensor/pixels: a film of 16384x16384 pixels x 100000 bins needs about " +
                                 std::to_string(bytes) + " bytes"));
  EXPECT_THAT(message, HasSubstr("are available"));
  // render() makes the check itself, before any tracer (and its film) exists.
  RenderOptions options;
  options.beams = 1;
  options.device = DeviceChoice::Cpu;
  EXPECT_THROW(render(scene, options), SceneError);
  // A small film passes.
  const Scene small = parseScene(sceneText(64, 32, R"({"blackbody_k": 3000})"), dir / "small.json");
  EXPECT_NO_THROW(checkFilmFitsMemory(small, compileScene(small, 1, {}), cpuReference(), true));
}

TEST_F(InputLimits, DeviceTablesBeyondTheStorageBufferRangeNameTheLightAndTheLimit) {
  std::string table = "[";
  for (int i = 0; i < 2000; ++i) table += std::string(i ? "," : "") + "[" + std::to_string(380 + i * 0.2) + ", 1]";
  table += "]";
  const Scene scene = parseScene(sceneText(8, 32, R"({"table": )" + table + "}"), dir / "table.json");
  const CompiledScene plan = compileScene(scene, 1, {});
  const uint64_t tableBytes = plan.device.intervals.size() * sizeof(device::SpectralInterval);
  ASSERT_GT(tableBytes, 1000u);
  EXPECT_NO_THROW(checkSceneFitsDevice(plan, tableBytes, 0, "test device"));
  const std::string message = errorOf([&] { checkSceneFitsDevice(plan, tableBytes - 1, 0, "test device"); });
  EXPECT_THAT(message, HasSubstr("/lights/*/spd: the spectral tables need " + std::to_string(tableBytes) + " bytes"));
  EXPECT_THAT(message, HasSubstr("/lights/0"));
  EXPECT_THAT(message, HasSubstr(std::to_string(tableBytes - 1) + " bytes of one storage buffer (maxStorageBufferRange of test device)"));
  const uint64_t filmBytes = plan.film.storedCounterCount() * 8;
  EXPECT_THAT(errorOf([&] { checkSceneFitsDevice(plan, tableBytes, filmBytes - 1, "test device"); }),
              HasSubstr("/camera/sensor/pixels: the film"));
}

}  // namespace
}  // namespace spectrace
