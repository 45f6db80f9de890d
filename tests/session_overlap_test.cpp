// Session::renderOverlapped: job k is written on the writer thread while job
// k+1 traces. The images equal the same jobs rendered alone, a write failure
// is reported against its own job while the others finish, and a job
// interrupted while the previous one is written leaves that one complete.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>

#include "session/session.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

namespace fs = std::filesystem;

// The test process's folder, removed with everything in it when the process
// exits (each test runs in a process of its own).
const fs::path& processDir() {
  static const struct Folder {
    fs::path path;
    ~Folder() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  } folder{fs::temp_directory_path() / ("spectrace_overlap_" + std::to_string(::getpid()))};
  return folder.path;
}

fs::path freshDir(const std::string& name) {
  const fs::path dir = processDir() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

RenderJob pointJob(const fs::path& output, double kelvin, uint32_t pixelsX) {
  RenderJob job;
  job.scene = testing::bareSensorScene(0.02, 0.02, pixelsX, 24, 32);
  job.scene.lights = {testing::pointLight({-0.003, 0.002, 0.004}, 0.5, makeBlackbodySpd(kelvin, 360, 830))};
  job.output = output;
  job.beams = 200000;
  job.seed = 4;
  job.png = true;
  return job;
}

void expectSameImage(const RenderImage& a, const RenderImage& b) {
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_EQ(a.xyz, b.xyz);
  EXPECT_EQ(a.irradiance, b.irradiance);
  EXPECT_EQ(a.irradianceError, b.irradianceError);
}

class Overlap : public ::testing::TestWithParam<DeviceChoice> {};

TEST_P(Overlap, WriteFailureIsReportedForItsJobAndTheOthersFinishIdentical) {
  const fs::path dir = freshDir(std::string("failure_") + (GetParam() == DeviceChoice::Gpu ? "gpu" : "cpu"));
  std::vector<RenderJob> jobs = {pointJob(dir / "a.exr", 2700, 32), pointJob(dir / "b.exr", 4000, 40),
                                 pointJob(dir / "c.exr", 6500, 24)};
  // b's PNG preview cannot be written: a folder takes its name while b is
  // traced, after its outputs were checked, so the failure comes only when
  // b is written.
  jobs[1].loop.onProgress = [&dir](uint64_t, uint64_t) { fs::create_directories(dir / "b.png"); };
  const Session session(GetParam());
  std::vector<std::shared_future<RenderResult>> written;
  for (const RenderJob& job : jobs) written.push_back(session.renderOverlapped(job));
  session.finishWriting();

  EXPECT_NO_THROW(written[0].get());
  try {
    written[1].get();
    ADD_FAILURE() << "b's write failure was not reported";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("b.png"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(written[2].get());
  for (const char* name : {"a.exr", "a.png", "c.exr", "c.png"}) EXPECT_TRUE(fs::is_regular_file(dir / name)) << name;
  EXPECT_TRUE(outputIsComplete(dir / "a.exr", 200000));
  EXPECT_TRUE(outputIsComplete(dir / "c.exr", 200000));

  // The same jobs, each rendered alone on a fresh session.
  for (size_t i : {size_t(0), size_t(2)}) {
    RenderJob alone = jobs[i];
    alone.output = dir / ("alone_" + std::to_string(i) + ".exr");
    const RenderResult expected = Session(GetParam()).render(alone);
    SCOPED_TRACE(jobs[i].output.string());
    expectSameImage(written[i].get().image, expected.image);
    EXPECT_EQ(readExr(jobs[i].output).image.rgb, readExr(alone.output).image.rgb);
  }
}

TEST_P(Overlap, InterruptLeavesThePreviousJobComplete) {
  const fs::path dir = freshDir(std::string("interrupt_") + (GetParam() == DeviceChoice::Gpu ? "gpu" : "cpu"));
  std::atomic<bool> cancel{false};
  RenderJob first = pointJob(dir / "first.exr", 3000, 32);
  RenderJob second = pointJob(dir / "second.exr", 5000, 32);
  second.beams = 4000000;
  second.loop.batchBeams = 100000;
  second.loop.cancel = &cancel;
  // The interrupt comes while `first` may still be being written.
  second.loop.onProgress = [&](uint64_t, uint64_t) { cancel = true; };
  const Session session(GetParam());
  auto firstWritten = session.renderOverlapped(first);
  auto secondWritten = session.renderOverlapped(second);
  session.finishWriting();
  EXPECT_EQ(firstWritten.get().beamsTraced, 200000u);
  EXPECT_TRUE(outputIsComplete(dir / "first.exr", 200000));
  EXPECT_LT(secondWritten.get().beamsTraced, 4000000u);
  EXPECT_TRUE(fs::is_regular_file(dir / "second.exr"));
  EXPECT_FALSE(outputIsComplete(dir / "second.exr", 4000000));
}

INSTANTIATE_TEST_SUITE_P(Devices, Overlap, ::testing::Values(DeviceChoice::Gpu, DeviceChoice::Cpu),
                         [](const auto& info) { return info.param == DeviceChoice::Gpu ? "gpu" : "cpu"; });

}  // namespace
}  // namespace spectrace
