#include "io/image.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>
#include <png.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace spectrace {
namespace {

namespace fs = std::filesystem;

// Each test gets its own directory, removed afterwards.
class IoDir : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("spectrace_io_test_" + std::to_string(::getpid())) /
           (std::string(info->test_suite_name()) + "." + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_.parent_path(), ignored);
  }

  // Every regular file below dir_, relative to it, so tests can assert that
  // no temporary is left behind.
  std::vector<std::string> filesBelow() const {
    std::vector<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(dir_)) {
      if (e.is_regular_file()) names.push_back(fs::relative(e.path(), dir_).string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path dir_;
};

RenderImage makeImage(int width, int height) {
  RenderImage img;
  img.width = width;
  img.height = height;
  const auto n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  img.rgb.assign(n * 3, 0.0f);
  img.xyz.assign(n * 3, 0.0f);
  img.irradiance.assign(n, 0.0f);
  return img;
}

void expectBitEqual(const std::vector<float>& expected, const std::vector<float>& actual, const char* what) {
  ASSERT_EQ(expected.size(), actual.size()) << what;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(std::bit_cast<std::uint32_t>(expected[i]), std::bit_cast<std::uint32_t>(actual[i]))
        << what << "[" << i << "]: " << expected[i] << " vs " << actual[i];
  }
}

template <class F>
void expectIoErrorMentioning(F&& f, const std::vector<std::string>& needles) {
  try {
    f();
    ADD_FAILURE() << "expected ImageIoError";
  } catch (const ImageIoError& e) {
    for (const auto& needle : needles) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << "\"" << e.what() << "\" lacks " << needle;
    }
  }
}

// Lowers the file-size limit so writes fail with EFBIG, and restores it.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    oldHandler_ = std::signal(SIGXFSZ, SIG_IGN);  // else the process is killed instead of write() failing
    rlimit lowered = saved_;
    lowered.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &lowered);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, oldHandler_);
  }

 private:
  rlimit saved_{};
  void (*oldHandler_)(int) = nullptr;
};

// ---------------------------------------------------------------- EXR

using ExrIo = IoDir;

TEST_F(ExrIo, RoundTripIsBitExact) {
  RenderImage img = makeImage(5, 3);
  const float specials[] = {-0.25f,
                            -0.0f,
                            std::numeric_limits<float>::denorm_min(),
                            -std::numeric_limits<float>::min(),
                            std::numeric_limits<float>::max(),
                            -1e30f,
                            1e-30f,
                            std::numeric_limits<float>::infinity(),
                            std::numeric_limits<float>::quiet_NaN()};
  // Distinct values everywhere, so any transposition or row flip shows.
  for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = static_cast<float>(i) * 0.37f - 3.1f;
  for (std::size_t i = 0; i < img.xyz.size(); ++i) img.xyz[i] = std::ldexp(1.0f + static_cast<float>(i) / 64.0f, int(i) - 20);
  for (std::size_t i = 0; i < img.irradiance.size(); ++i) img.irradiance[i] = 1e6f / static_cast<float>(i + 1);
  for (std::size_t i = 0; i < std::size(specials); ++i) {
    img.rgb[i * 4] = specials[i];
    img.xyz[img.xyz.size() - 1 - i] = specials[i];
    img.irradiance[i] = -specials[i];
  }

  ImageMetadata meta;
  meta.strings["beams"] = "18446744073709551615";
  meta.strings["scene"] = "scenes/cornell box.json";
  meta.strings["empty"] = "";
  meta.numbers["seconds"] = 0.1;
  meta.numbers["tiny"] = std::numeric_limits<double>::denorm_min();
  meta.numbers["huge"] = -1.7976931348623157e308;
  meta.numbers["pi"] = 3.141592653589793;

  const fs::path path = dir_ / "out" / "nested" / "image.exr";  // parents do not exist yet
  writeExr(path, img, meta);
  EXPECT_EQ(filesBelow(), std::vector<std::string>{"out/nested/image.exr"});

  const ExrContents back = readExr(path);
  EXPECT_EQ(back.image.width, 5);
  EXPECT_EQ(back.image.height, 3);
  expectBitEqual(img.rgb, back.image.rgb, "rgb");
  expectBitEqual(img.xyz, back.image.xyz, "xyz");
  expectBitEqual(img.irradiance, back.image.irradiance, "irradiance");
  EXPECT_EQ(back.meta.strings, meta.strings);
  ASSERT_EQ(back.meta.numbers.size(), meta.numbers.size());
  for (const auto& [name, value] : meta.numbers) {
    ASSERT_TRUE(back.meta.numbers.count(name)) << name;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(back.meta.numbers.at(name)), std::bit_cast<std::uint64_t>(value)) << name;
  }
}

TEST_F(ExrIo, OverwritesAtomicallyAndLeavesNoTemp) {
  const fs::path path = dir_ / "image.exr";
  RenderImage img = makeImage(2, 2);
  writeExr(path, img, {});
  img.rgb[0] = 42.0f;
  writeExr(path, img, {});
  EXPECT_EQ(filesBelow(), std::vector<std::string>{"image.exr"});
  EXPECT_EQ(readExr(path).image.rgb[0], 42.0f);
}

TEST_F(ExrIo, ReadMissingFileNamesPath) {
  const fs::path path = dir_ / "does_not_exist.exr";
  expectIoErrorMentioning([&] { readExr(path); }, {path.string()});
}

TEST_F(ExrIo, ReadNonExrFileNamesPath) {
  const fs::path path = dir_ / "not_an_image.exr";
  std::ofstream(path) << "this is plain text, not OpenEXR\n";
  expectIoErrorMentioning([&] { readExr(path); }, {path.string()});
}

TEST_F(ExrIo, ReadTruncatedFileNamesPath) {
  const fs::path path = dir_ / "truncated.exr";
  RenderImage img = makeImage(64, 64);
  for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = std::sin(static_cast<float>(i));
  writeExr(path, img, {});
  fs::resize_file(path, fs::file_size(path) / 2);
  expectIoErrorMentioning([&] { readExr(path); }, {path.string()});
}

TEST_F(ExrIo, ReadMissingChannelNamesPathAndChannel) {
  // An EXR written directly with OpenEXR that has everything but irradiance.E.
  const fs::path path = dir_ / "partial.exr";
  const int w = 3, h = 2;
  std::vector<float> data(static_cast<std::size_t>(w * h), 1.0f);
  Imf::Header header(w, h);
  Imf::FrameBuffer frame;
  for (const char* name : {"R", "G", "B", "XYZ.X", "XYZ.Y", "XYZ.Z"}) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    frame.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data.data()), sizeof(float), sizeof(float) * w));
  }
  {
    Imf::OutputFile out(path.c_str(), header);
    out.setFrameBuffer(frame);
    out.writePixels(h);
  }
  expectIoErrorMentioning([&] { readExr(path); }, {path.string(), "irradiance.E"});
}

TEST_F(ExrIo, MetadataNameClashThrows) {
  const fs::path path = dir_ / "clash.exr";
  ImageMetadata meta;
  meta.strings["compression"] = "none";  // a standard attribute of another type
  expectIoErrorMentioning([&] { writeExr(path, makeImage(1, 1), meta); }, {path.string(), "compression"});
  ImageMetadata both;
  both.strings["x"] = "1";
  both.numbers["x"] = 1.0;
  expectIoErrorMentioning([&] { writeExr(path, makeImage(1, 1), both); }, {path.string(), "\"x\""});
  EXPECT_TRUE(filesBelow().empty());
}

TEST_F(ExrIo, UncreatableDirectoryNamesPath) {
  std::ofstream(dir_ / "file") << "x";
  const fs::path path = dir_ / "file" / "image.exr";  // parent is a regular file
  expectIoErrorMentioning([&] { writeExr(path, makeImage(1, 1), {}); }, {path.string()});
}

TEST_F(ExrIo, WriteFailureNamesPathAndLeavesNothing) {
  const fs::path path = dir_ / "big.exr";
  RenderImage img = makeImage(256, 256);
  for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = std::sin(static_cast<float>(i) * 1.7f);
  {
    FileSizeLimit limit(4096);
    expectIoErrorMentioning([&] { writeExr(path, img, {}); }, {path.string()});
  }
  EXPECT_TRUE(filesBelow().empty());
}

// ---------------------------------------------------------------- sizes

using ImageValidation = IoDir;

TEST_F(ImageValidation, ExrRejectsInconsistentSizes) {
  const fs::path path = dir_ / "bad.exr";
  struct Case {
    const char* field;
    void (*mutate)(RenderImage&);
  };
  const Case cases[] = {
      {"rgb", [](RenderImage& i) { i.rgb.pop_back(); }},
      {"xyz", [](RenderImage& i) { i.xyz.push_back(0.0f); }},
      {"irradiance", [](RenderImage& i) { i.irradiance.clear(); }},
      {"size", [](RenderImage& i) { i.width = 0; }},
      {"size", [](RenderImage& i) { i.height = -3; }},
      {"rgb", [](RenderImage& i) { i.width = 3; }},  // vectors sized for 4x2, header says 3x2
  };
  for (const Case& c : cases) {
    RenderImage img = makeImage(4, 2);
    c.mutate(img);
    expectIoErrorMentioning([&] { writeExr(path, img, {}); }, {path.string(), c.field});
  }
  EXPECT_TRUE(filesBelow().empty());
}

TEST_F(ImageValidation, PngRejectsInconsistentSizes) {
  const fs::path path = dir_ / "bad.png";
  RenderImage img = makeImage(4, 2);
  img.rgb.resize(4 * 2 * 3 + 1);
  expectIoErrorMentioning([&] { writePngPreview(path, img); }, {path.string(), "rgb"});
  img = makeImage(0, 2);
  expectIoErrorMentioning([&] { writePngPreview(path, img); }, {path.string(), "size"});
  EXPECT_TRUE(filesBelow().empty());
}

// ---------------------------------------------------------------- PNG

struct Png {
  std::uint32_t width = 0, height = 0;
  int bitDepth = 0, colourType = -1;
  std::vector<std::uint8_t> rgb;
  std::uint8_t at(std::uint32_t x, std::uint32_t y, int c) const { return rgb[(std::size_t(y) * width + x) * 3 + c]; }
};

Png readPng(const fs::path& path) {
  Png out;
  // IHDR is always the first chunk: signature(8) length(4) type(4) then
  // width, height, bit depth, colour type. Read it raw to check what was
  // stored, independent of any conversion by the reader below.
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> head(26);
  in.read(reinterpret_cast<char*>(head.data()), 26);
  if (!in) {
    ADD_FAILURE() << "short PNG " << path;
    return out;
  }
  const auto be32 = [&](int o) {
    return std::uint32_t(head[o]) << 24 | std::uint32_t(head[o + 1]) << 16 | std::uint32_t(head[o + 2]) << 8 | head[o + 3];
  };
  out.width = be32(16);
  out.height = be32(20);
  out.bitDepth = head[24];
  out.colourType = head[25];

  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    ADD_FAILURE() << "libpng: " << image.message;
    return out;
  }
  image.format = PNG_FORMAT_RGB;
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr)) {
    ADD_FAILURE() << "libpng: " << image.message;
  }
  return out;
}

std::uint8_t srgbByte(double linear) {
  const double e = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(e * 255.0));
}

using PngPreview = IoDir;

TEST_F(PngPreview, ExposureFromPercentileAndSrgbCurve) {
  // 11x10 = 110 pixels. Pixels 0..99 are lit with max channel k+1 (a ramp),
  // so the nearest-rank 99th percentile of the 100 lit maxima is 99. The
  // other 10 pixels are unlit (negative, NaN, inf, zero) and must not count.
  const int w = 11, h = 10;
  RenderImage img = makeImage(w, h);
  auto px = [&](int i) { return &img.rgb[static_cast<std::size_t>(i) * 3]; };
  for (int i = 0; i < 100; ++i) {
    float* p = px(i);
    p[0] = p[1] = p[2] = static_cast<float>(i + 1);
  }
  px(0)[1] = 0.2f;  // below the sRGB linear-segment threshold after exposure
  // Percentile level, with the other channels negative / NaN.
  px(98)[1] = -3.0f;
  px(98)[2] = std::numeric_limits<float>::quiet_NaN();
  // Half the level (49.5 keeps the ranks: 49 < 49.5 < 51).
  px(49)[0] = px(49)[1] = px(49)[2] = 49.5f;
  // Unlit pixels.
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const float unlit[10][3] = {{-1, -1, -1}, {nan, nan, nan}, {inf, 0, 0}, {-inf, -5, 0}, {0, 0, 0},
                              {-0.0f, 0, 0}, {nan, -1, 0}, {0, 0, -7}, {-1e30f, 0, 0}, {0, nan, inf}};
  for (int i = 0; i < 10; ++i) std::copy(unlit[i], unlit[i] + 3, px(100 + i));

  const fs::path path = dir_ / "preview" / "image.png";
  writePngPreview(path, img);
  EXPECT_EQ(filesBelow(), std::vector<std::string>{"preview/image.png"});

  const Png png = readPng(path);
  EXPECT_EQ(png.width, 11u);
  EXPECT_EQ(png.height, 10u);
  EXPECT_EQ(png.bitDepth, 8);
  EXPECT_EQ(png.colourType, PNG_COLOR_TYPE_RGB);
  ASSERT_EQ(png.rgb.size(), 11u * 10u * 3u);
  const auto pixelXY = [&](int i, int c) { return png.at(std::uint32_t(i % w), std::uint32_t(i / w), c); };

  EXPECT_EQ(pixelXY(98, 0), 255);  // the 99th-percentile level maps to 1
  EXPECT_EQ(pixelXY(98, 1), 0);    // negative
  EXPECT_EQ(pixelXY(98, 2), 0);    // NaN
  EXPECT_EQ(pixelXY(99, 0), 255);  // above the level: clipped
  EXPECT_EQ(srgbByte(0.5), 188);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(pixelXY(49, c), 188) << c;  // half the level
  EXPECT_EQ(pixelXY(0, 0), srgbByte(1.0 / 99.0));
  EXPECT_EQ(pixelXY(0, 0), 26);                     // power segment: 1/99 > 0.0031308
  EXPECT_EQ(pixelXY(0, 1), srgbByte(0.2 / 99.0));  // linear segment: 0.2/99 <= 0.0031308
  EXPECT_EQ(pixelXY(0, 1), 7);                      // (a pure power law would give 6)
  EXPECT_EQ(pixelXY(9, 2), srgbByte(10.0 / 99.0));
  for (int i = 100; i < 110; ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(pixelXY(i, c), 0) << "pixel " << i << " channel " << c;
  }
}

TEST_F(PngPreview, UnlitImageIsBlack) {
  RenderImage img = makeImage(7, 5);
  for (std::size_t i = 0; i < img.rgb.size(); ++i) {
    img.rgb[i] = (i % 3 == 0) ? -2.0f : (i % 3 == 1) ? std::numeric_limits<float>::quiet_NaN() : 0.0f;
  }
  const fs::path path = dir_ / "black.png";
  writePngPreview(path, img);
  EXPECT_EQ(filesBelow(), std::vector<std::string>{"black.png"});
  const Png png = readPng(path);
  EXPECT_EQ(png.width, 7u);
  EXPECT_EQ(png.height, 5u);
  EXPECT_EQ(png.rgb, std::vector<std::uint8_t>(7 * 5 * 3, 0));
}

TEST_F(PngPreview, TinyLevelDoesNotOverflow) {
  // 200 lit pixels: one at denorm_min, 198 at twice that (the 99th
  // percentile), one at FLT_MAX, far above it: the ratio overflows float.
  const float d = std::numeric_limits<float>::denorm_min();
  RenderImage img = makeImage(20, 10);
  for (std::size_t i = 0; i < img.rgb.size(); i += 3) img.rgb[i] = 2 * d;
  img.rgb[0] = d;
  img.rgb[3] = std::numeric_limits<float>::max();
  writePngPreview(dir_ / "t.png", img);
  const Png png = readPng(dir_ / "t.png");
  EXPECT_EQ(png.at(0, 0, 0), 188);
  EXPECT_EQ(png.at(1, 0, 0), 255);
  EXPECT_EQ(png.at(2, 0, 0), 255);
  EXPECT_EQ(png.at(2, 0, 1), 0);
}

TEST_F(PngPreview, WriteFailureNamesPathAndLeavesNothing) {
  // Noise compresses badly, so the encoder must hit the size limit; the
  // error comes back through libpng's longjmp path as an ImageIoError.
  const fs::path path = dir_ / "noise.png";
  RenderImage img = makeImage(256, 256);
  std::uint32_t state = 12345;
  for (float& v : img.rgb) {
    state = state * 1664525u + 1013904223u;
    v = static_cast<float>(state >> 8) / 16777216.0f;
  }
  {
    FileSizeLimit limit(4096);
    expectIoErrorMentioning([&] { writePngPreview(path, img); }, {path.string()});
  }
  EXPECT_TRUE(filesBelow().empty());
  writePngPreview(path, img);  // and the writer is usable again afterwards
  EXPECT_EQ(readPng(path).width, 256u);
}

}  // namespace
}  // namespace spectrace
