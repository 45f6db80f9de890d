#include "session/job_file.h"

#include <atomic>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>

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
  fs::path write(const std::string& text) {
    std::ofstream(dir / "jobs.jsonl") << text;
    return dir / "jobs.jsonl";
  }
  // Every entry of the job file `text`, as many as the reader counted.
  std::vector<JobEntry> read(const std::string& text) {
    JobReader reader(write(text));
    std::vector<JobEntry> entries;
    while (auto entry = reader.next()) entries.push_back(std::move(*entry));
    EXPECT_EQ(entries.size(), reader.total());
    return entries;
  }
  std::string jobsFile() const { return (dir / "jobs.jsonl").string(); }
};

// A sweep line over `keys` pointers of `values` values each (1, 2, ...).
std::string sweepLine(const std::vector<std::string>& keys, size_t values) {
  nlohmann::ordered_json line = {{"scene", "lamp.json"}, {"output", "s_{index}.exr"}, {"beams", 1}};
  for (const auto& key : keys) {
    std::vector<int> list(values);
    for (size_t i = 0; i < values; ++i) list[i] = int(i + 1);
    line["sweep"][key] = list;
  }
  return line.dump() + "\n";
}

template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

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
    // What the EXR header records: "set", then the sweep's values in its order.
    EXPECT_EQ(job.scene.overrides,
              fmt::format(R"({{"/camera/position":[0,0,-1],"/lights/0/spd/blackbody_k":{},"/lights/0/power_w":{}}})",
                          i < 3 ? 2700 : 4000, powers[i]));
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
  EXPECT_EQ(entries[0].job->scene.overrides, "");
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
  EXPECT_THROW(JobReader{dir / "none.jsonl"}, JobFileError);
}

TEST_F(JobFileTest, ASweepOf2To64CombinationsIsRefusedNotWrappedToNone) {
  // 256^8 = 2^64: a 64-bit product wraps to 0 (this file used to read as "0 jobs").
  const std::vector<std::string> keys = {"/lights/0/power_w", "/lights/0/cone_deg", "/lights/0/position/0",
                                         "/lights/0/position/1", "/lights/0/position/2", "/camera/position/0",
                                         "/camera/position/1", "/render/seed"};
  const fs::path file = write(sweepLine(keys, 256));
  EXPECT_EQ(errorOf([&] { JobReader{file}; }),
            jobsFile() + ":1: /sweep: 2^64 or more combinations (256 x 256 x 256 x 256 x 256 x 256 x 256 x 256); "
                         "a job file may hold at most 1000000 jobs; split the sweep over several job files");
}

TEST_F(JobFileTest, ASweepPastTheJobLimitIsRefusedAndOneAtItIsCountedNotBuilt) {
  const fs::path over = write("{\"scene\": \"lamp.json\", \"output\": \"one.exr\"}\n" +
                              sweepLine({"/lights/0/power_w", "/render/seed"}, 1000));
  EXPECT_EQ(errorOf([&] { JobReader{over}; }),
            jobsFile() + ":2: /sweep: 1000000 combinations (1000 x 1000) after 1 job on the lines above; a job file "
                         "may hold at most 1000000 jobs; split the sweep over several job files");
  // At the limit: counted, not built; the jobs come one at a time.
  JobReader reader(write(sweepLine({"/lights/0/power_w", "/render/seed"}, 1000)));
  EXPECT_EQ(reader.total(), kMaxJobsPerFile);
  EXPECT_EQ(reader.sceneFilesRead(), 1u);
  for (int i = 0; i < 3; ++i) {
    const auto entry = reader.next();
    ASSERT_TRUE(entry && entry->job) << (entry ? entry->error : "no entry");
    EXPECT_EQ(entry->where, jobsFile() + ":1 [" + std::to_string(i) + "]");
    EXPECT_EQ(entry->job->output, dir / ("s_" + std::to_string(i) + ".exr"));
    EXPECT_EQ(entry->job->scene.render.seed, uint64_t(i + 1));
  }
}

TEST_F(JobFileTest, LinesPastAGivenLimitAreRefusedNamingTheLine) {
  const std::string job = R"({"scene": "lamp.json", "output": "{index}.exr"})" "\n";
  const std::string bad = R"({"scene": "none.json"})" "\n";  // a bad line is an entry too
  JobReaderOptions options;
  options.maxJobs = 3;
  EXPECT_EQ(JobReader(write("# three\n" + job + bad + job), options).total(), 3u);
  EXPECT_EQ(errorOf([&] { JobReader(write(job + job + bad + bad), options); }),
            jobsFile() + ":4: the job file holds more than 3 jobs, the most a job file may hold; split it over several "
                         "job files");
}

TEST_F(JobFileTest, ASceneFileIsReadOnceHoweverManyLinesNameIt) {
  // Each line used to read its scene again (1.3 ms a job at 100,000 lines).
  fs::create_directories(dir / "sub");
  std::ofstream(dir / "sub" / "lamp2.json") << kScene;
  std::string text;
  const char* names[] = {"lamp.json", "./lamp.json", "sub/../lamp.json", "sub/lamp2.json"};
  for (int i = 0; i < 400; ++i)
    text += fmt::format(R"({{"scene": "{}", "output": "o{}.exr", "set": {{"/render/seed": {}}}}})" "\n", names[i % 4], i, i);
  JobReader reader(write(text));
  EXPECT_EQ(reader.total(), 400u);
  EXPECT_EQ(reader.sceneFilesRead(), 2u);  // counting read each scene once
  uint64_t n = 0;
  while (auto entry = reader.next()) {
    ASSERT_TRUE(entry->job) << entry->error;
    EXPECT_EQ(entry->job->scene.render.seed, n++);
  }
  EXPECT_EQ(n, 400u);
  EXPECT_EQ(reader.sceneFilesRead(), 2u);  // and building the jobs read none again
}

TEST_F(JobFileTest, AnOutputPatternMustMakeAnExrOfItsOwn) {
  const auto entries = read(
      R"({"scene": "lamp.json", "output": "{/lights/0/name}", "sweep": {"/lights/0/name": ["x.png", "a", "b.exr", "b.EXR"]}})" "\n"
      R"({"scene": "lamp.json", "output": "p{/lights/0/power_w}.exr", "sweep": {"/lights/0/power_w": [1, 1.0, 2]}})" "\n"
      R"({"scene": "lamp.json", "output": "b.exr"})" "\n");
  ASSERT_EQ(entries.size(), 8u);
  const std::string at = jobsFile() + ":1 [";
  EXPECT_EQ(entries[0].error, at + "0]: /output: output " + (dir / "x.png").string() +
                                  " (from the pattern \"{/lights/0/name}\") must end in .exr (the PNG preview is "
                                  "written beside it as .png)");
  EXPECT_NE(entries[1].error.find(at + "1]: /output: output " + (dir / "a").string() + " (from the pattern"),
            std::string::npos) << entries[1].error;
  ASSERT_TRUE(entries[2].job) << entries[2].error;
  EXPECT_EQ(entries[3].error, at + "3]: /output: its PNG preview " + (dir / "b.png").string() + " is also that of " +
                                  at + "2]");
  ASSERT_TRUE(entries[4].job) << entries[4].error;
  EXPECT_EQ(entries[5].error, jobsFile() + ":2 [1]: /output: " + (dir / "p1.exr").string() + " is also the output of " +
                                  jobsFile() + ":2 [0]");
  ASSERT_TRUE(entries[6].job) << entries[6].error;
  EXPECT_EQ(entries[7].error, jobsFile() + ":3: /output: " + (dir / "b.exr").string() + " is also the output of " + at + "2]");
}

TEST_F(JobFileTest, AnOutputWithANulCharacterIsRefused) {
  // The system would cut the name at the NUL: EXR and PNG preview both to "a".
  const auto entries = read(
      R"({"scene": "lamp.json", "output": "a\u0000b.exr"})" "\n"
      R"({"scene": "lamp.json", "output": "{/lights/0/name}.exr", "sweep": {"/lights/0/name": ["c\u0000", "c"]}})" "\n");
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[0].error, jobsFile() + ":1: /output: output \"a\\u0000b.exr\" holds a NUL character, which no "
                                           "file name can (it would be cut to \"a\")");
  EXPECT_NE(entries[1].error.find(":2 [0]: /output: output \"c\\u0000.exr\" holds a NUL"), std::string::npos)
      << entries[1].error;
  ASSERT_TRUE(entries[2].job) << entries[2].error;
}

TEST_F(JobFileTest, AStateIsNamedLikeTheOutputAndClaimedOnce) {
  const auto entries = read(
      R"({"scene": "lamp.json", "output": "a.exr", "state": "{/lights/0/type}_{/render/seed}_{index}.state"})" "\n"
      R"({"scene": "lamp.json", "output": "b.exr", "state": "spot_1_0.state"})" "\n"
      R"({"scene": "lamp.json", "output": "c.exr", "state": "a.exr"})" "\n"
      R"({"scene": "lamp.json", "output": "d.exr", "state": "a.png"})" "\n"
      R"({"scene": "lamp.json", "output": "spot_1_0.state.exr", "state": "e.state"})" "\n"
      R"({"scene": "lamp.json", "output": "e.exr"})" "\n"
      R"({"scene": "lamp.json", "output": "f.exr", "state": "{/nothing}.state"})" "\n"
      R"({"scene": "lamp.json", "output": "g.exr", "state": "g.state", "set": {"/lights/0/power_w": 2}})" "\n"
      R"({"scene": "lamp.json", "output": "h.exr", "state": "h\u0000.state"})" "\n");
  ASSERT_EQ(entries.size(), 9u);
  ASSERT_TRUE(entries[0].job) << entries[0].error;
  EXPECT_EQ(entries[0].job->state, dir / "spot_1_0.state");
  EXPECT_EQ(entries[0].job->stateRole, "state");
  // The scene file's own digest, as render records it: merge and resume check it.
  EXPECT_EQ(entries[0].job->scene.sourceSha256, loadScene(dir / "lamp.json").sourceSha256);
  const std::string first = jobsFile() + ":1";
  EXPECT_EQ(entries[1].error, jobsFile() + ":2: /state: " + (dir / "spot_1_0.state").string() + " is also the state of " + first);
  EXPECT_EQ(entries[2].error, jobsFile() + ":3: /state: " + (dir / "a.exr").string() + " is also the output of " + first);
  EXPECT_EQ(entries[3].error, jobsFile() + ":4: /state: " + (dir / "a.png").string() + " is also the PNG preview of " + first);
  ASSERT_TRUE(entries[4].job) << entries[4].error;  // another file than spot_1_0.state
  ASSERT_TRUE(entries[5].job) << entries[5].error;  // e.exr beside the state e.state
  EXPECT_NE(entries[6].error.find(":7: /state: {/nothing} names no field of the scene"), std::string::npos)
      << entries[6].error;
  // The state carries the scene the job renders, overrides applied.
  ASSERT_TRUE(entries[7].job) << entries[7].error;
  EXPECT_EQ(entries[7].job->state, dir / "g.state");
  EXPECT_NE(entries[8].error.find(":9: /state: state \"h\\u0000.state\" holds a NUL"), std::string::npos)
      << entries[8].error;
}

TEST_F(JobFileTest, AnOutputOntoAnEarlierStateIsRefused) {
  const auto entries = read(
      R"({"scene": "lamp.json", "output": "a.exr", "state": "s.exr"})" "\n"
      R"({"scene": "lamp.json", "output": "s.exr"})" "\n"
      R"({"scene": "lamp.json", "output": "b.exr", "state": "t.png"})" "\n"
      R"({"scene": "lamp.json", "output": "t.exr"})" "\n"
      R"({"scene": "lamp.json", "output": "c{index}.exr", "sweep": {"/lights/0/power_w": [1, 2]}, "state": "c{index}.state"})" "\n");
  ASSERT_EQ(entries.size(), 6u);
  ASSERT_TRUE(entries[0].job) << entries[0].error;
  EXPECT_EQ(entries[1].error, jobsFile() + ":2: /output: " + (dir / "s.exr").string() + " is also the state of " +
                                  jobsFile() + ":1");
  ASSERT_TRUE(entries[2].job) << entries[2].error;
  EXPECT_EQ(entries[3].error, jobsFile() + ":4: /output: its PNG preview " + (dir / "t.png").string() +
                                  " is also the state of " + jobsFile() + ":3");
  // A swept scene's state carries the scene it renders: it is written too.
  ASSERT_TRUE(entries[4].job) << entries[4].error;
  EXPECT_EQ(entries[4].job->state, dir / "c0.state");
  ASSERT_TRUE(entries[5].job) << entries[5].error;
  EXPECT_EQ(entries[5].job->state, dir / "c1.state");
}

TEST_F(JobFileTest, TheCancelFlagStopsReadingBetweenLines) {
  std::atomic<bool> cancel{true};
  JobReaderOptions options;
  options.cancel = &cancel;
  const fs::path file = write("# first\n" R"({"scene": "lamp.json"})" "\n");
  EXPECT_EQ(errorOf([&] { JobReader(file, options); }), "interrupted while reading " + jobsFile() + " (at line 1)");
  cancel = false;
  EXPECT_EQ(JobReader(file, options).total(), 1u);
}

}  // namespace
}  // namespace spectrace
