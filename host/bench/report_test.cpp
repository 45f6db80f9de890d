// The bench report's ray-ceiling part: the largest mesh in full, and the
// table by mesh size only where there is more than one.
#include "bench/report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace spectrace {
namespace {

RayCeilingRow ceilingRow(uint64_t triangles, double spectraceSeconds, double embreeSeconds) {
  RayCeilingRow r;
  r.embree = true;
  r.triangles = triangles;
  r.rays = 1'000'000;
  r.threads = 2;
  r.spectrace1 = spectraceSeconds;
  r.spectraceN = spectraceSeconds / 2.0;
  r.embree1 = embreeSeconds;
  r.embreeN = embreeSeconds / 2.0;
  r.bytesPerTriangle = 59.5;
  r.vulkanBytesPerTriangle = 53.75;
  return r;
}

std::string reportWith(const std::vector<RayCeilingRow>& rows, const std::string& name) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / name;
  std::filesystem::remove_all(dir);
  BenchReport report;
  report.rayCeiling = rows;
  writeBenchReport(dir, report);
  std::ifstream in(dir / "benchmarks.md");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(BenchReport, RayCeilingDetailsTheLargestMeshAndTabulatesTheSizes) {
  // 1M rays: 0.25 s against 0.125 s is 4 against 8 Mray/s, ratio 0.5;
  // 1.25 s against 0.5 s is 0.8 against 2 Mray/s, ratio 0.4.
  const std::string md = reportWith({ceilingRow(960, 0.25, 0.125), ceilingRow(998000, 1.25, 0.5)}, "ceiling_sizes");
  EXPECT_EQ(occurrences(md, "### Ray ceiling (Embree)"), 1u);
  EXPECT_NE(md.find("mesh of 998000 triangles"), std::string::npos);
  EXPECT_EQ(md.find("mesh of 960 triangles"), std::string::npos);
  EXPECT_NE(md.find("| 960 | 4.000 | 8.000 | 0.500 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 998000 | 0.800 | 2.000 | 0.400 |"), std::string::npos) << md;
}

TEST(BenchReport, RayCeilingGivesTheTreesBytesOnBothDevices) {
  const std::string md = reportWith({ceilingRow(998000, 1.25, 0.5)}, "ceiling_bytes");
  EXPECT_NE(md.find("| spectrace | 1 | 0.800 | 59.5 | |"), std::string::npos) << md;
  EXPECT_NE(md.find("64-byte packed nodes, 53.8 bytes a triangle"), std::string::npos) << md;
}

TEST(BenchReport, RayCeilingOfOneMeshHasNoTableBySize) {
  const std::string md = reportWith({ceilingRow(960, 0.25, 0.125)}, "ceiling_one");
  EXPECT_NE(md.find("mesh of 960 triangles"), std::string::npos);
  EXPECT_EQ(md.find("By the mesh's size"), std::string::npos);
}

}  // namespace
}  // namespace spectrace
