// Resume: a render that stopped after k beams, with its state written,
// goes on from that state and ends bit-identical to an uninterrupted render;
// a state that does not belong to the render is refused.
#include <gtest/gtest.h>

#include <filesystem>

#include "camera/pinhole_camera.h"
#include "session/session.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() {
  const fs::path dir = fs::temp_directory_path() / ("spectrace_resume_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

RenderJob lampJob(const fs::path& output, uint64_t beams) {
  RenderJob job;
  job.scene = testing::bareSensorScene(0.02, 0.02, 16, 12, 32);
  job.scene.camera.model = pinholeModel({0.03, 0.002});
  Light rect = testing::surfaceLight(LightType::Rect, {0.0, 0.0, 0.5}, {0.0, 0.0, -1.0}, 3.0, *cieIlluminant("F11"));
  rect.sizeM = {0.2, 0.1};
  job.scene.lights = {rect};
  job.output = output;
  job.beams = beams;
  job.seed = 9;
  job.png = false;
  job.firstBeam = 12345;
  return job;
}

class Resume : public ::testing::TestWithParam<DeviceChoice> {};

TEST_P(Resume, EndsBitIdenticalToAnUninterruptedRender) {
  const Session session(GetParam());
  const fs::path dir = tempDir();
  constexpr uint64_t kBeams = 400'000, kStoppedAfter = 123'457;
  const RenderResult whole = session.render(lampJob(dir / "whole.exr", kBeams));

  RenderJob first = lampJob(dir / "part.exr", kStoppedAfter);
  first.state = dir / "part.state";
  session.render(first);
  RenderJob rest = lampJob(dir / "resumed.exr", kBeams);
  rest.resume = readFilmState(first.state);
  EXPECT_EQ(rest.resume->beams(), kStoppedAfter);
  const RenderResult resumed = session.render(rest);

  EXPECT_EQ(resumed.beamsTraced, kBeams);
  EXPECT_EQ(resumed.histogram.counts(), whole.histogram.counts());
  EXPECT_EQ(resumed.histogram.colourSums(), whole.histogram.colourSums());
  EXPECT_EQ(resumed.histogram.squaredWeightSums(), whole.histogram.squaredWeightSums());
  EXPECT_EQ(resumed.image.rgb, whole.image.rgb);
  EXPECT_EQ(resumed.image.xyz, whole.image.xyz);
  EXPECT_EQ(resumed.image.irradiance, whole.image.irradiance);
  EXPECT_EQ(resumed.image.irradianceError, whole.image.irradianceError);
}

TEST_P(Resume, AStateOfAnotherRenderIsRefused) {
  const Session session(GetParam());
  const fs::path dir = tempDir();
  RenderJob first = lampJob(dir / "a.exr", 50'000);
  first.state = dir / "a.state";
  session.render(first);
  RenderJob otherSeed = lampJob(dir / "b.exr", 100'000);
  otherSeed.seed = 10;
  otherSeed.resume = readFilmState(first.state);
  try {
    session.render(otherSeed);
    ADD_FAILURE() << "resumed from another seed's state";
  } catch (const FilmStateError& e) {
    EXPECT_NE(std::string(e.what()).find("seed"), std::string::npos) << e.what();
  }
  RenderJob otherStart = lampJob(dir / "c.exr", 100'000);
  otherStart.firstBeam = 0;
  otherStart.resume = readFilmState(first.state);
  EXPECT_THROW(session.render(otherStart), FilmStateError);
}

// A state's fingerprint holds every compile option (namedCompileOptions
// over kCompileOptionFields, whose size a static_assert ties to
// CompileOptions): flipping any one of them changes it, so a resume or
// merge under the other value is refused.
TEST(ResumeFingerprint, HoldsEveryCompileOption) {
  const RenderJob job = lampJob("x.exr", 1000);
  const FilmFingerprint base = jobFingerprint(job);
  ASSERT_EQ(base.compileOptions.size(), std::size(kCompileOptionFields));
  for (const CompileOptionField& field : kCompileOptionFields) {
    RenderJob changed = job;
    changed.plan.*field.member = !(job.plan.*field.member);
    const FilmFingerprint other = jobFingerprint(changed);
    EXPECT_EQ(other.compileOptions.at(field.name), changed.plan.*field.member) << field.name;
    EXPECT_NE(other.compileOptions.at(field.name), base.compileOptions.at(field.name)) << field.name;
    EXPECT_NE(fingerprintDifference(base, other), "") << field.name;
  }
}

TEST(ResumeFingerprint, AStateOfAnAnalogRenderIsRefusedForAConnectedOne) {
  const Session session(DeviceChoice::Cpu);
  const fs::path dir = tempDir();
  RenderJob analog = lampJob(dir / "analog.exr", 20'000);
  analog.plan.connect = false;
  analog.state = dir / "analog.state";
  session.render(analog);
  RenderJob connected = lampJob(dir / "connected.exr", 40'000);
  connected.resume = readFilmState(analog.state);
  try {
    session.render(connected);
    ADD_FAILURE() << "resumed a connected render from an analog one's state";
  } catch (const FilmStateError& e) {
    EXPECT_NE(std::string(e.what()).find("compile_options/connect"), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Devices, Resume, ::testing::Values(DeviceChoice::Gpu, DeviceChoice::Cpu),
                         [](const auto& info) { return info.param == DeviceChoice::Gpu ? "gpu" : "cpu"; });

}  // namespace
}  // namespace spectrace
