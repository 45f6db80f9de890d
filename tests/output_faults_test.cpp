// Faults around outputs (docs/reliability.md "Checkpoints and faults"): a
// checkpoint that cannot be written does not stop the render, a final write
// that fails leaves the last good checkpoint, two renders to one output are
// refused, and a killed render's temporary files are cleaned up.
#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "camera/pinhole_camera.h"
#include "film/film_state.h"
#include "session/output_guard.h"
#include "session/session.h"
#include "spectrum/spd.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr uint64_t kBatch = 1 << 14;

// Writes fail (EFBIG) while set: RLIMIT_FSIZE 0 with SIGXFSZ ignored is a
// full disk for this process only, and needs no privileges or mounts.
class DiskFull {
 public:
  DiskFull() {
    ::getrlimit(RLIMIT_FSIZE, &saved_);
    previous_ = ::signal(SIGXFSZ, SIG_IGN);
  }
  ~DiskFull() {
    set(false);
    ::signal(SIGXFSZ, previous_);
  }
  void set(bool full) {
    rlimit limit = saved_;
    if (full) limit.rlim_cur = 0;
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }

 private:
  rlimit saved_{};
  sighandler_t previous_ = SIG_DFL;
};

struct OutputFaults : ::testing::Test {
  fs::path dir;
  void SetUp() override {
    dir = fs::temp_directory_path() / ("spectrace_output_faults_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  // A small render in batches of kBatch beams, with a checkpoint (EXR and
  // state) after every batch but the last.
  RenderJob job(const std::string& name, uint64_t batches, std::vector<std::string>& warnings) const {
    RenderJob job;
    job.scene = testing::bareSensorScene(0.02, 0.02, 16, 12, 32);
    job.scene.camera.model = pinholeModel({0.03, 0.002});
    Light rect = testing::surfaceLight(LightType::Rect, {0.0, 0.0, 0.5}, {0.0, 0.0, -1.0}, 3.0, *cieIlluminant("F11"));
    rect.sizeM = {0.2, 0.1};
    job.scene.lights = {rect};
    job.output = dir / (name + ".exr");
    job.state = dir / (name + ".state");
    job.beams = batches * kBatch;
    job.seed = 3;
    job.png = false;
    job.loop.batchBeams = kBatch;
    job.loop.checkpointSeconds = 1e-9;
    job.tracer.cpuThreads = 1;
    job.warn = [&warnings](const std::string& line) { warnings.push_back(line); };
    return job;
  }

  std::vector<fs::path> leftovers() const {
    std::vector<fs::path> found;
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.path().filename().string().find(".tmp-") != std::string::npos ||
          entry.path().filename().string().find(".lock") != std::string::npos)
        found.push_back(entry.path());
    return found;
  }
};

size_t countContaining(const std::vector<std::string>& lines, const std::string& text) {
  size_t n = 0;
  for (const auto& line : lines) n += line.find(text) != std::string::npos;
  return n;
}

TEST_F(OutputFaults, AFailedCheckpointWarnsOnceAndTheRenderGoesOnAndRetries) {
  const Session session(DeviceChoice::Cpu);
  std::vector<std::string> warnings;
  RenderJob render = job("retry", 8, warnings);
  DiskFull disk;
  std::vector<uint64_t> written;
  // The disk is full for the checkpoints after batches 2, 3 and 4.
  render.loop.onProgress = [&](uint64_t done, uint64_t) { disk.set(done >= 2 * kBatch && done <= 4 * kBatch); };
  render.loop.onCheckpoint = [&](const RenderImage&, uint64_t done, const std::string&) { written.push_back(done); };
  const RenderResult result = session.render(render);
  disk.set(false);
  EXPECT_EQ(result.beamsTraced, 8 * kBatch);
  EXPECT_EQ(written, (std::vector<uint64_t>{kBatch, 5 * kBatch, 6 * kBatch, 7 * kBatch}));
  // One warning per file for the streak of three failures, one when it recovers.
  EXPECT_EQ(countContaining(warnings, "not written"), 2u) << ::testing::PrintToString(warnings);
  EXPECT_EQ(countContaining(warnings, "checkpoint of 32768 beams not written"), 2u);
  EXPECT_EQ(countContaining(warnings, "retry.exr still holds the checkpoint of 16384 beams"), 1u);
  EXPECT_EQ(countContaining(warnings, "written to"), 2u);
  EXPECT_TRUE(outputIsComplete(render.output, 8 * kBatch));
  EXPECT_EQ(readFilmState(render.state).beams(), 8 * kBatch);
  EXPECT_THAT(leftovers(), ::testing::IsEmpty());
}

TEST_F(OutputFaults, AFailedFinalWriteFailsAndTheLastGoodCheckpointSurvives) {
  const Session session(DeviceChoice::Cpu);
  std::vector<std::string> warnings;
  RenderJob render = job("final", 5, warnings);
  DiskFull disk;
  // Full from the checkpoint after batch 3 to the end.
  render.loop.onProgress = [&](uint64_t done, uint64_t) { disk.set(done >= 3 * kBatch); };
  std::string message;
  try {
    session.render(render);
  } catch (const OutputError& e) {
    message = e.what();
  }
  disk.set(false);
  EXPECT_THAT(message, HasSubstr("final.state"));
  EXPECT_THAT(message, HasSubstr("still holds the last checkpoint (32768 beams)"));
  EXPECT_EQ(countContaining(warnings, "not written"), 2u);
  EXPECT_TRUE(outputIsComplete(render.output, 2 * kBatch));
  EXPECT_EQ(readFilmState(render.state).beams(), 2 * kBatch);
  EXPECT_THAT(leftovers(), ::testing::IsEmpty());
}

TEST_F(OutputFaults, ASecondRenderToALockedOutputIsRefusedNamingTheHolder) {
  const Session session(DeviceChoice::Cpu);
  std::vector<std::string> warnings;
  const RenderJob render = job("locked", 1, warnings);
  {
    const OutputLock first(render.output);
    EXPECT_EQ(first.path(), dir / ".locked.exr.lock");
    std::string message;
    try {
      session.render(render);
    } catch (const OutputLockedError& e) {
      message = e.what();
    }
    EXPECT_THAT(message, HasSubstr("output " + render.output.string() + " is being written by another spectrace (pid " +
                                   std::to_string(::getpid()) + ","));
    EXPECT_FALSE(fs::exists(render.output));
  }
  // Released: the lock file is gone and the render goes ahead.
  EXPECT_FALSE(fs::exists(dir / ".locked.exr.lock"));
  EXPECT_EQ(session.render(render).beamsTraced, kBatch);
  EXPECT_THAT(leftovers(), ::testing::IsEmpty());
}

TEST_F(OutputFaults, TemporaryFilesOfDeadProcessesAreRemovedByTheNextRender) {
  const Session session(DeviceChoice::Cpu);
  std::vector<std::string> warnings;
  RenderJob render = job("stale", 1, warnings);
  std::vector<std::string> logged;
  render.loop.log = [&](const std::string& line) { logged.push_back(line); };
  // A pid above the kernel's pid_max (at most 2^22) belongs to no process;
  // pid 1 is always alive, so its file may be in use and stays.
  const std::string dead = "2147483000";
  const std::vector<fs::path> stale = {dir / ("stale.exr.tmp-" + dead), dir / ("stale.png.tmp-" + dead),
                                       dir / ("stale.state.tmp-" + dead), dir / (".stale.exr.probe-" + dead),
                                       dir / ("stale.exr.tmp-" + std::to_string(::getpid()))};
  const std::vector<fs::path> kept = {dir / "stale.exr.tmp-1", dir / "other.exr.tmp-2147483000",
                                      dir / "stale.exr.tmp-12x"};
  for (const auto& p : stale) std::ofstream(p) << "partial";
  for (const auto& p : kept) std::ofstream(p) << "partial";
  session.render(render);
  for (const auto& p : stale) EXPECT_FALSE(fs::exists(p)) << p;
  for (const auto& p : kept) EXPECT_TRUE(fs::exists(p)) << p;
  EXPECT_EQ(countContaining(logged, "removed the stale temporary file"), stale.size());
}

TEST_F(OutputFaults, TheScenesCsvSpectraAreInputsThatAnOutputMayNotReplace) {
  // A CSV with an .exr name, so only the input check can stop it.
  const fs::path csv = dir / "lamp.exr";
  std::ofstream(csv) << "400,1\n700,1\n";
  const fs::path scene = dir / "lamp.json";
  std::ofstream(scene) << R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, 1],
    "sensor": {"width_m": 0.024, "height_m": 0.024, "pixels": [8, 8]},
    "pinhole": {"distance_m": 0.05, "radius_m": 0.0015}},
    "lights": [{"type": "point", "position": [0, 0, 1], "power_w": 1, "spd": {"csv": "lamp.exr"}}]})";
  RenderJob render;
  render.scene = loadScene(scene);
  render.output = csv;
  std::string message;
  try {
    checkOutputPath(render);
  } catch (const OutputPathError& e) {
    message = e.what();
  }
  EXPECT_THAT(message, HasSubstr("is the input file " + csv.string() + "; an input is never overwritten"));
  render.output = dir / "lamp_render.exr";
  EXPECT_NO_THROW(checkOutputPath(render));
}

}  // namespace
}  // namespace spectrace
