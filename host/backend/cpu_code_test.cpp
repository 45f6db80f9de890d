// The CPU reference's two machine codes (CpuCode: the baseline and
// x86-64-v3) are one source compiled twice: they must draw and count the
// same beams bit for bit, on every light type, with and without a pinhole,
// aimed and analog, with per-beam colour and squared weights, and in every
// stage of the bench's profile.
#include <gtest/gtest.h>

#include "backend/cpu_tracer.h"
#include "compile/compile_scene.h"
#include "support/same_film.h"
#include "support/test_scale.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

using testing::expectSameFilm;

struct Variant {
  const char* name;
  bool pinhole;
  bool aim;
  bool perBeamColour;
};

constexpr Variant kVariants[] = {
    {"bare, aimed, colour from bins", false, true, false},
    {"bare, analog, per-beam colour", false, false, true},
    {"pinhole, aimed, per-beam colour", true, true, true},
    {"pinhole, analog, colour from bins", true, false, false},
};

CompiledScene compile(const Variant& v) {
  CompileOptions options;
  options.aim = v.aim;
  options.colourFromBins = !v.perBeamColour;
  return compileScene(testing::everyLightTypeScene(v.pinhole), 4242, options);
}

SpectralHistogram render(const CompiledScene& plan, CpuCode code, uint32_t stage, uint64_t first, uint64_t beams) {
  CpuTracer tracer(plan, 2, stage, code);
  EXPECT_EQ(tracer.trace(first, beams), beams);
  return tracer.download();
}

class CpuCodes : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!cpuRuns(CpuCode::X86_64_V3)) GTEST_SKIP() << "this processor cannot run x86-64-v3 code, so it never does";
  }
};

TEST(CpuCode, BaselineAlwaysRunsAndNamesItsCode) {
  EXPECT_TRUE(cpuRuns(CpuCode::Baseline));
  const CompiledScene plan = compile(kVariants[0]);
  EXPECT_NE(CpuTracer(plan, 1, device::kProfileStageFull, CpuCode::Baseline).deviceName().find("baseline"),
            std::string::npos);
  if (!cpuRuns(CpuCode::X86_64_V3))
    EXPECT_THROW(CpuTracer(plan, 1, device::kProfileStageFull, CpuCode::X86_64_V3), std::invalid_argument);
  else
    EXPECT_EQ(fastestCpuCode(), CpuCode::X86_64_V3);
}

TEST_F(CpuCodes, SameFilmsBitForBit) {
  for (const Variant& v : kVariants) {
    const CompiledScene plan = compile(v);
    const uint64_t beams = testing::scaledBeams(1'000'000, 200'000);
    const SpectralHistogram baseline = render(plan, CpuCode::Baseline, device::kProfileStageFull, 0, beams);
    const SpectralHistogram v3 = render(plan, CpuCode::X86_64_V3, device::kProfileStageFull, 0, beams);
    EXPECT_GT(baseline.countedBeams, 1'000u) << v.name << ": too few beams counted to compare";
    expectSameFilm(baseline, v3, v.name);
  }
}

TEST_F(CpuCodes, SameBeamRecordsPast2To32) {
  for (const Variant& v : kVariants) {
    const CompiledScene plan = compile(v);
    CpuTracer baseline(plan, 1, device::kProfileStageFull, CpuCode::Baseline);
    CpuTracer v3(plan, 1, device::kProfileStageFull, CpuCode::X86_64_V3);
    const uint64_t first = (uint64_t(1) << 32) - 100'000;
    const auto a = baseline.traceRecorded(first, 200'000);
    const auto b = v3.traceRecorded(first, 200'000);
    ASSERT_EQ(a.size(), b.size());
    size_t differing = 0, hits = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      differing += (a[i].pixel != b[i].pixel || a[i].bin != b[i].bin || a[i].ratioBits != b[i].ratioBits) ? 1 : 0;
      hits += a[i].pixel != device::kBeamMissed ? 1 : 0;
    }
    EXPECT_EQ(differing, 0u) << v.name;
    EXPECT_GT(hits, 100u) << v.name;
  }
}

TEST_F(CpuCodes, SameProfileStages) {
  const CompiledScene plan = compile(kVariants[0]);
  const uint64_t beams = testing::scaledBeams(300'000, 60'000);
  for (uint32_t stage = 0; stage <= device::kProfileStageFull; ++stage)
    expectSameFilm(render(plan, CpuCode::Baseline, stage, 7, beams), render(plan, CpuCode::X86_64_V3, stage, 7, beams),
                   "profile stage " + std::to_string(stage));
}

}  // namespace
}  // namespace spectrace
