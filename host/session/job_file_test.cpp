#include "session/job_file.h"

#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

namespace spectrace {
namespace {

namespace fs = std::filesystem;

const char* kScene = R"({
  "spectrum": {"min_nm": 380, "max_nm": 780, "bins": 40},
  "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1],
             "sensor": {"width_m": 0.024, "height_m": 0.016, "pixels": [24, 16]},
             "pinhole": {"distance_m": 0.05, "radius_m": 0.0015}},
  "lights": [{"type": "spot", "position": [0, 0, 1], "direction": [0, 0, -1], "cone_deg": 1,
              "power_w": 1, "spd": {"blackbody_k": 2700}}],
  "render": {"beams": 1000, "seed": 1}
})";

struct JobFileTest : ::testing::Test {
  fs::path dir;
  void SetUp() override {
    dir = fs::temp_directory_path() / ("spectrace_job_file_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "lamp.json") << kScene;
  }
  void TearDown() override { fs::remove_all(dir); }
  std::vector<JobEntry> read(const std::string& text) {
    std::ofstream(dir / "jobs.jsonl") << text;
    return readJobFile(dir / "jobs.jsonl");
  }
};

TEST_F(JobFileTest, SweepIsTheProductWithTheFirstKeyOutermostAndNamesOutputs) {
  const auto entries = read(
      "# comment\n\n"
      R"({"scene": "lamp.json", "output": "l_{index}_{/lights/0/spd/blackbody_k}K_{/lights/0/power_w}W.exr", "beams": 1e8, "seed": 3,)"
      R"( "set": {"/camera/position": [0, 0, -1]}, "sweep": {"/lights/0/spd/blackbody_k": [2700, 4000], "/lights/0/power_w": [1, 2.5, 3]}})"
      "\n");
  ASSERT_EQ(entries.size(), 6u);
  const char* names[] = {"l_0_2700K_1W.exr", "l_1_2700K_2.5W.exr", "l_2_2700K_3W.exr",
                         "l_3_4000K_1W.exr", "l_4_4000K_2.5W.exr", "l_5_4000K_3W.exr"};
  const double powers[] = {1, 2.5, 3, 1, 2.5, 3};
  for (size_t i = 0; i < entries.size(); ++i) {
    ASSERT_TRUE(entries[i].job) << entries[i].error;
    const RenderJob& job = *entries[i].job;
    EXPECT_EQ(entries[i].where, (dir / "jobs.jsonl").string() + ":3 [" + std::to_string(i) + "]");
    EXPECT_EQ(job.output, dir / names[i]);
    EXPECT_EQ(job.beamCount(), 100'000'000u);
    EXPECT_EQ(job.seedValue(), 3u);
    EXPECT_DOUBLE_EQ(job.scene.lights[0].powerW, powers[i]);
    EXPECT_DOUBLE_EQ(job.scene.camera.position.z, -1.0);
  }
}

TEST_F(JobFileTest, ABadLineIsAnErrorNamingFileLineAndFieldAndTheOthersStand) {
  const auto entries = read(
      R"({"scene": "lamp.json", "output": "a.exr"})" "\n"
      R"({"scene": "lamp.json", "output": "b.exr", "set": {"/lights/1/power_w": 2}})" "\n"
      R"({"scene": "lamp.json", "output": "c.exr", "sweep": {"/lights/0/power_w": [1, 2]}})" "\n"
      R"({"scene": "lamp.json", "output": "a.exr"})" "\n"
      R"({"scene": "lamp.json", "outptu": "d.exr"})" "\n");
  ASSERT_EQ(entries.size(), 5u);
  ASSERT_TRUE(entries[0].job) << entries[0].error;
  EXPECT_EQ(entries[0].job->beamCount(), 1000u);  // the scene's
  EXPECT_FALSE(entries[1].job);
  EXPECT_NE(entries[1].error.find("jobs.jsonl:2: /set/~1lights~11~1power_w: unknown pointer /lights/1/power_w"),
            std::string::npos) << entries[1].error;
  EXPECT_NE(entries[2].error.find("jobs.jsonl:3: /output: a sweep needs"), std::string::npos) << entries[2].error;
  EXPECT_NE(entries[3].error.find("jobs.jsonl:4: /output: "), std::string::npos) << entries[3].error;
  EXPECT_NE(entries[3].error.find("is also the output of"), std::string::npos) << entries[3].error;
  EXPECT_NE(entries[4].error.find("did you mean \"output\""), std::string::npos) << entries[4].error;
}

TEST_F(JobFileTest, ParseSceneJsonReadsWhatLoadSceneReads) {
  const Scene a = loadScene(dir / "lamp.json");
  const Scene b = parseSceneJson(readSceneJson(dir / "lamp.json"), dir / "lamp.json");
  EXPECT_EQ(a.lights.size(), b.lights.size());
  EXPECT_EQ(a.camera.pixelsX, b.camera.pixelsX);
  EXPECT_EQ(a.spectrum.bins, b.spectrum.bins);
  EXPECT_EQ(a.render.beams, b.render.beams);
  EXPECT_EQ(a.sourcePath, b.sourcePath);
}

TEST_F(JobFileTest, AMissingJobFileThrows) {
  EXPECT_THROW(readJobFile(dir / "none.jsonl"), JobFileError);
}

}  // namespace
}  // namespace spectrace
