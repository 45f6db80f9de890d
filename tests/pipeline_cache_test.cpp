// The persistent Vulkan pipeline cache: written after a render and reused;
// corrupt, truncated or foreign files are ignored with a warning and never
// change the image; "off" writes nothing.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include <vulkan/vulkan_core.h>

#include "render/renderer.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

namespace fs = std::filesystem;

Scene smallScene() {
  Scene scene = testing::bareSensorScene(0.02, 0.02, 40, 30, 24);
  scene.lights = {testing::pointLight({-0.005, 0.003, 0.004}, 0.5, makeBlackbodySpd(3000, 360, 830))};
  return scene;
}

struct Rendered {
  RenderResult result;
  std::string log;
};

Rendered renderWith(const PipelineCacheOptions& cache) {
  Rendered out;
  RenderOptions options;
  options.beams = 20000;
  options.seed = 7;
  options.device = DeviceChoice::Gpu;
  options.pipelineCache = cache;
  options.loop.log = [&](const std::string& line) { out.log += line + "\n"; };
  out.result = render(smallScene(), options);
  return out;
}

std::vector<char> readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeAll(const fs::path& p, const std::vector<char>& bytes) {
  std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

class PipelineCache : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(SPECTRACE_TEST_BUILD_DIR) / "pipeline_cache_test" /
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  fs::path dir_;
};

void expectSamePixels(const RenderImage& a, const RenderImage& b) {
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_EQ(a.xyz, b.xyz);
  EXPECT_EQ(a.irradiance, b.irradiance);
}

TEST_F(PipelineCache, IsWrittenAfterARenderAndReused) {
  const fs::path file = dir_ / "cache.bin";
  const Rendered first = renderWith({true, file.string()});
  ASSERT_TRUE(fs::exists(file)) << first.log;
  const auto bytes = readAll(file);
  ASSERT_GE(bytes.size(), 32u);  // at least a VkPipelineCacheHeaderVersionOne
  uint32_t headerSize, version;
  std::memcpy(&headerSize, bytes.data(), 4);
  std::memcpy(&version, bytes.data() + 4, 4);
  EXPECT_GE(headerSize, 32u);
  EXPECT_EQ(version, uint32_t(VK_PIPELINE_CACHE_HEADER_VERSION_ONE));

  const Rendered second = renderWith({true, file.string()});
  EXPECT_EQ(second.log.find("pipeline cache"), std::string::npos) << "a valid cache is used silently:\n" << second.log;
  const auto again = readAll(file);
  EXPECT_GE(again.size(), bytes.size());
  EXPECT_TRUE(std::equal(bytes.begin(), bytes.begin() + 32, again.begin())) << "the header must not change";
  expectSamePixels(first.result.image, second.result.image);
}

TEST_F(PipelineCache, CorruptTruncatedAndForeignFilesAreIgnoredWithAWarning) {
  const Rendered reference = renderWith({false, ""});
  const fs::path valid = dir_ / "valid.bin";
  renderWith({true, valid.string()});
  const auto good = readAll(valid);
  ASSERT_GE(good.size(), 32u);

  std::mt19937 rng(5);
  std::vector<char> random(4096);
  for (char& c : random) c = char(rng());
  std::vector<char> foreign = good;
  foreign[16] = char(foreign[16] ^ 0xff);  // another driver's pipelineCacheUUID
  std::vector<char> wrongDevice = good;
  wrongDevice[12] = char(wrongDevice[12] ^ 0x01);  // deviceID
  const std::pair<const char*, std::vector<char>> cases[] = {
      {"random", random},
      {"truncated", std::vector<char>(good.begin(), good.begin() + 10)},
      {"foreign", foreign},
      {"wrong_device", wrongDevice},
  };
  for (const auto& [name, bytes] : cases) {
    SCOPED_TRACE(name);
    const fs::path file = dir_ / (std::string(name) + ".bin");
    writeAll(file, bytes);
    const Rendered r = renderWith({true, file.string()});
    EXPECT_NE(r.log.find("pipeline cache " + file.string() + " ignored:"), std::string::npos) << r.log;
    expectSamePixels(reference.result.image, r.result.image);
    // Replaced on save by a cache for this device.
    const auto saved = readAll(file);
    ASSERT_GE(saved.size(), 32u);
    EXPECT_TRUE(std::equal(good.begin(), good.begin() + 32, saved.begin()));
  }
}

TEST_F(PipelineCache, OffWritesNothing) {
  // Default location under this test's own XDG_CACHE_HOME.
  const fs::path xdg = dir_ / "xdg";
  const char* saved = std::getenv("XDG_CACHE_HOME");
  const std::string previous = saved ? saved : "";
  setenv("XDG_CACHE_HOME", xdg.c_str(), 1);
  renderWith({false, ""});
  EXPECT_FALSE(fs::exists(xdg)) << "--no-pipeline-cache must write nothing";
  renderWith({true, ""});
  EXPECT_TRUE(fs::exists(xdg / "spectrace")) << "the default cache lives under $XDG_CACHE_HOME/spectrace";
  bool found = false;
  for (const auto& e : fs::directory_iterator(xdg / "spectrace"))
    found = found || e.path().filename().string().starts_with("pipelines-");
  EXPECT_TRUE(found);
  if (saved) setenv("XDG_CACHE_HOME", previous.c_str(), 1); else unsetenv("XDG_CACHE_HOME");
}

}  // namespace
}  // namespace spectrace
