// The exact render state: it round-trips bit for bit, refuses damaged files
// and states that do not belong together, and shards of [0, N) merge into
// exactly the film of one render of N beams, on either device or both.
#include "film/film_state.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <openssl/evp.h>
#include <zstd.h>

#include "backend/cpu_tracer.h"
#include "backend/vulkan_tracer.h"
#include "camera/pinhole_camera.h"
#include "compile/compile_scene.h"
#include "render/renderer.h"
#include "support/test_scenes.h"

namespace spectrace {
namespace {

namespace fs = std::filesystem;

fs::path tempFile(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("spectrace_state_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

std::string fileBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// An aimed disk light through a pinhole: fractional weights, so every array
// (counts, colour sums, squared weights) is in use.
Scene weightedScene() {
  Scene scene = testing::bareSensorScene(0.01, 0.01, 12, 10, 24);
  scene.camera.model = pinholeModel({0.02, 0.001});
  Light disk = testing::surfaceLight(LightType::Disk, {0.0, 0.0, 0.3}, {0.0, 0.0, -1.0}, 2.0, *cieIlluminant("D65"));
  disk.radiusM = 0.05;
  scene.lights = {disk};
  return scene;
}

FilmState stateOf(const CompiledScene& plan, Tracer& tracer, uint64_t first, uint64_t count, uint64_t seed) {
  tracer.clear();
  tracer.trace(first, count);
  FilmState state;
  state.fingerprint = fingerprintOf(plan.film, "scene.json", "abc123", "CIE1931_2", seed, 31, namedCompileOptions({}));
  state.ranges = {{first, count}};
  state.histogram = tracer.download();
  return state;
}

TEST(FilmState, RoundTripsBitForBit) {
  const Scene scene = weightedScene();
  const CompiledScene plan = compileScene(scene, 4);
  ASSERT_TRUE(plan.film.weighted());
  CpuTracer cpu(plan, 2);
  const FilmState state = stateOf(plan, cpu, 1000, 200'000, 4);
  const fs::path file = tempFile("round.state");
  writeFilmState(file, state);
  const FilmState back = readFilmState(file);
  EXPECT_EQ(back.histogram.counts(), state.histogram.counts());
  EXPECT_EQ(back.histogram.colourSums(), state.histogram.colourSums());
  EXPECT_EQ(back.histogram.squaredWeightSums(), state.histogram.squaredWeightSums());
  EXPECT_EQ(back.histogram.countedBeams, state.histogram.countedBeams);
  EXPECT_EQ(back.ranges, state.ranges);
  EXPECT_EQ(mergeRefusal(back, back).find("overlap") != std::string::npos, true) << "a state overlaps itself";
}

TEST(FilmState, DamagedFilesAreRefusedNeverHalfRead) {
  const CompiledScene plan = compileScene(weightedScene(), 4);
  CpuTracer cpu(plan, 2);
  const fs::path file = tempFile("damaged.state");
  writeFilmState(file, stateOf(plan, cpu, 0, 50'000, 4));
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto refusedWith = [&](const std::string& content, const std::string& expected) {
    const fs::path damaged = tempFile("bad.state");
    std::ofstream(damaged, std::ios::binary) << content;
    try {
      readFilmState(damaged);
      ADD_FAILURE() << "accepted a file that should have been refused for " << expected;
    } catch (const FilmStateError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(damaged.string()), std::string::npos) << "names the file: " << e.what();
    }
  };
  // A truncated file, or one with bytes after its end, is refused by its
  // size, before its arrays are read; a flipped bit by its checksum.
  refusedWith(bytes.substr(0, bytes.size() / 2), "it is truncated or has bytes after its end");
  refusedWith(bytes + "x", "it is truncated or has bytes after its end");
  std::string flipped = bytes;
  flipped[flipped.size() / 2] ^= 0x10;
  refusedWith(flipped, "checksum");
  refusedWith("not a state at all, just some text that is long enough to hold a digest", "magic");
}

// State bytes with their SHA-256 appended, as writeFilmState ends a file.
std::string signedState(std::string bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_Digest(bytes.data(), bytes.size(), digest, &length, EVP_sha256(), nullptr);
  bytes.append(reinterpret_cast<const char*>(digest), length);
  return bytes;
}

// A header whose film is far larger than the arrays after it (found by
// film_state_fuzz) is refused before anything is allocated, not with a
// bad_alloc: the checksum is right, only the claimed shape is wrong.
TEST(FilmState, HeaderClaimingAHugeFilmIsRefusedBeforeAllocating) {
  FilmState small;
  small.fingerprint.bins = 2;
  small.fingerprint.pixelsX = small.fingerprint.pixelsY = 1;
  small.ranges = {{0, 1}};
  small.histogram = SpectralHistogram(1, 1, 2);
  const fs::path file = tempFile("huge.state");
  writeFilmState(file, small);
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  // Same-length edits of the header: 1 x 1 pixels become 65535 x 65535, and
  // 2 bins 99999 (the file keeps its 2 counts).
  for (auto [from, to] : {std::pair<std::string, std::string>{"\"pixels_x\":1,", "\"pixels_x\":65535,"},
                          {"\"pixels_y\":1,", "\"pixels_y\":65535,"}, {"\"bins\":2,", "\"bins\":99999,"}}) {
    const size_t at = bytes.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    bytes.replace(at, from.size(), to);
  }
  // The header grew by 12 bytes: re-state its length, then re-sign.
  uint32_t headerBytes = 0;
  std::memcpy(&headerBytes, bytes.data() + 12, 4);
  const uint32_t grown = headerBytes + 12;
  std::memcpy(bytes.data() + 12, &grown, 4);
  bytes.resize(bytes.size() - 32);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << signedState(bytes);
  try {
    readFilmState(file);
    ADD_FAILURE() << "accepted a state whose film does not fit its file";
  } catch (const FilmStateError& e) {
    EXPECT_NE(std::string(e.what()).find("/counts: 2 values, but its film (65535 x 65535 pixels, 99999 bins) has "
                                         "429479327663775"),
              std::string::npos)
        << e.what();
  }
}

// The file with its header replaced by `header` and its version by
// `version`, padded and signed as writeFilmState does.
std::string withHeader(const std::string& bytes, const nlohmann::json& header, uint32_t version) {
  uint32_t oldLength = 0;
  std::memcpy(&oldLength, bytes.data() + 12, 4);
  std::string text = header.dump();
  while ((16 + text.size()) % 8 != 0) text += ' ';
  std::string out = bytes.substr(0, 8);
  const uint32_t prefix[2] = {version, uint32_t(text.size())};
  out.append(reinterpret_cast<const char*>(prefix), sizeof prefix);
  out += text;
  out += bytes.substr(16 + oldLength, bytes.size() - 32 - 16 - oldLength);
  return signedState(out);
}

// A state file's header and the bytes between it and the digest.
struct StateParts {
  nlohmann::json header;
  std::string body;
};

StateParts partsOf(const std::string& bytes) {
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return {nlohmann::json::parse(bytes.substr(16, length)), bytes.substr(16 + length, bytes.size() - 48 - length)};
}

// A state file of `version` from a header and a body, padded and signed as
// writeFilmState does.
std::string stateBytes(uint32_t version, const nlohmann::json& header, const std::string& body) {
  std::string text = header.dump();
  while ((16 + text.size()) % 8 != 0) text += ' ';
  std::string out = "SPCTRSTA";
  const uint32_t prefix[2] = {version, uint32_t(text.size())};
  out.append(reinterpret_cast<const char*>(prefix), sizeof prefix);
  return signedState(out + text + body);
}

// `state` as an older spectrace wrote it (version 1 to 3): the header
// without the fields version 4 added, and the arrays uncompressed.
std::string legacyStateBytes(const FilmState& state, uint32_t version) {
  const fs::path file = tempFile("legacy_source.state");
  writeFilmState(file, state);
  nlohmann::json header = partsOf(fileBytes(file)).header;
  for (const char* added : {"irradiance_per_count", "compression", "compressed_bytes", "bundle"}) header.erase(added);
  std::string arrays;
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c)
    arrays.append(reinterpret_cast<const char*>(state.histogram.channel(c).data()),
                  state.histogram.channel(c).size() * sizeof(uint64_t));
  return stateBytes(version, header, arrays);
}

// Version 1 recorded four compile options as fields of their own; a state
// written then still reads, with those options and the rest at their
// defaults, and merges with the same render's version 2 state.
TEST(FilmState, VersionOneStatesStillRead) {
  FilmState state;
  state.fingerprint = fingerprintOf(FilmLayout{}, "scene.json", "abc", "CIE1931_2", 3, 31, namedCompileOptions({}));
  state.fingerprint.pixelsX = state.fingerprint.pixelsY = state.fingerprint.bins = 1;
  state.fingerprint.exactColour = state.fingerprint.colourFromBins = false;
  state.fingerprint.weightUnits = 1;
  state.ranges = {{0, 10}};
  state.histogram = SpectralHistogram(1, 1, 1);
  const fs::path file = tempFile("version1.state");
  const std::string bytes = legacyStateBytes(state, 3);
  uint32_t headerLength = 0;
  std::memcpy(&headerLength, bytes.data() + 12, 4);
  nlohmann::json header = nlohmann::json::parse(bytes.substr(16, headerLength));
  nlohmann::json& f = header["fingerprint"];
  ASSERT_TRUE(f.contains("compile_options"));
  f.erase("compile_options");
  f["aimed"] = true;
  f["skip_unreachable_lights"] = true;
  f["trim_spectrum"] = false;
  f["trim_pixels"] = true;
  std::ofstream(file, std::ios::binary | std::ios::trunc) << withHeader(bytes, header, 1);
  const FilmState read = readFilmState(file);
  EXPECT_EQ(read.fingerprint.compileOptions.at("trim_spectrum"), false);
  EXPECT_EQ(read.fingerprint.compileOptions.at("aim"), true);
  EXPECT_EQ(read.fingerprint.compileOptions.at("connect"), true);
  CompileOptions expected;
  expected.trimSpectrum = false;
  expected.exactColour = read.fingerprint.exactColour || read.fingerprint.colourFromBins;
  expected.colourFromBins = read.fingerprint.colourFromBins;
  expected.cameraPaths = false;  // states from before camera paths traced light paths only
  EXPECT_EQ(read.fingerprint.compileOptions, namedCompileOptions(expected));
}

// Two fingerprints that differ in one compile option: the refusal names it.
TEST(FilmState, ADifferentCompileOptionIsNamed) {
  CompileOptions analog;
  analog.connect = false;
  FilmState a, b;
  a.fingerprint = fingerprintOf(FilmLayout{}, "s.json", "abc", "CIE1931_2", 1, 31, namedCompileOptions({}));
  b.fingerprint = fingerprintOf(FilmLayout{}, "s.json", "abc", "CIE1931_2", 1, 31, namedCompileOptions(analog));
  EXPECT_EQ(fingerprintDifference(a.fingerprint, b.fingerprint), "compile_options/connect: true against false");
  EXPECT_EQ(fingerprintDifference(a.fingerprint, a.fingerprint), "");
}

// The fingerprint as text (what render --mpi ranks exchange) comes back
// equal, and a different one is still told apart.
TEST(FilmState, FingerprintTextRoundTrips) {
  const CompiledScene plan = compileScene(weightedScene(), 4);
  const FilmFingerprint f = fingerprintOf(plan.film, "s.json", "abc", "CIE1931_2", 7, 31, namedCompileOptions({}));
  const FilmFingerprint back = fingerprintOfText(fingerprintText(f));
  EXPECT_EQ(fingerprintDifference(back, f), "");
  EXPECT_EQ(back.sceneFile, "s.json");
  FilmFingerprint other = f;
  other.bins += 1;
  EXPECT_EQ(fingerprintDifference(fingerprintOfText(fingerprintText(other)), f),
            fmt::format("bins: {} against {}", f.bins + 1, f.bins));
  EXPECT_THROW(fingerprintOfText("{\"bins\": 3}"), FilmStateError);
}

TEST(FilmState, StatesOfOtherScenesSeedsOrOverlappingBeamsAreRefused) {
  const CompiledScene plan = compileScene(weightedScene(), 4);
  CpuTracer cpu(plan, 2);
  const FilmState a = stateOf(plan, cpu, 0, 10'000, 4);
  FilmState b = stateOf(plan, cpu, 10'000, 10'000, 4);
  EXPECT_EQ(mergeRefusal(a, b), "");
  FilmState otherSeed = b;
  otherSeed.fingerprint.seed = 5;
  EXPECT_NE(mergeRefusal(a, otherSeed).find("seed"), std::string::npos);
  FilmState otherScene = b;
  otherScene.fingerprint.sceneSha256 = "def456";
  EXPECT_NE(mergeRefusal(a, otherScene).find("scene_sha256"), std::string::npos);
  FilmState otherSpectrum = b;
  otherSpectrum.fingerprint.bins = 25;
  EXPECT_NE(mergeRefusal(a, otherSpectrum).find("bins"), std::string::npos);
  FilmState overlapping = b;
  overlapping.ranges = {{9'999, 5}};
  EXPECT_NE(mergeRefusal(a, overlapping).find("share beam 9999"), std::string::npos) << mergeRefusal(a, overlapping);
  EXPECT_THROW(mergeStates(a, overlapping), FilmStateError);
  // Ranges that end at 2^64 compare without overflow.
  FilmState top = b, below = b;
  top.ranges = {{UINT64_MAX - 9, 10}};
  below.ranges = {{UINT64_MAX - 20, 11}};
  EXPECT_EQ(mergeRefusal(top, below), "");
  below.ranges = {{UINT64_MAX - 20, 12}};
  EXPECT_NE(mergeRefusal(top, below), "");
}

// A 3 x 2 pixel film of 4 bins with the given ranges and counted beams, as
// a test crafts it: writeFilmState signs whatever it is given.
FilmState craftedState(std::vector<BeamRange> ranges, uint64_t countedBeams = 0, bool exactColour = false,
                       uint32_t weightUnits = 1) {
  FilmState state;
  state.fingerprint = fingerprintOf(FilmLayout{}, "scene.json", "abc", "CIE1931_2", 3, 31, namedCompileOptions({}));
  FilmFingerprint& f = state.fingerprint;
  f.bins = f.storedBins = 4;
  f.pixelsX = 3;
  f.pixelsY = 2;
  f.window = {0, 0, 3, 2};
  f.exactColour = exactColour;
  f.colourFromBins = false;
  f.weightUnits = weightUnits;
  state.ranges = std::move(ranges);
  state.histogram = SpectralHistogram(3, 2, 4, exactColour, weightUnits);
  state.histogram.countedBeams = countedBeams;
  return state;
}

// readFilmState's refusal of `file`, or "" when it reads.
std::string readRefusal(const fs::path& file) {
  try {
    readFilmState(file);
    return "";
  } catch (const FilmStateError& e) {
    return e.what();
  }
}

// The refusal of `state` written to a file and read back: "" when it reads.
std::string refusalOf(const FilmState& state) {
  const fs::path file = tempFile("crafted.state");
  writeFilmState(file, state);
  return readRefusal(file);
}

constexpr uint64_t kHalf = uint64_t(1) << 63;

// A 16 GiB sparse file is refused at once, naming the file, by its magic or
// by the size its header implies, without being read whole (it used to be,
// into memory, and fail with std::bad_alloc). Sparse: no disk space is used.
TEST(FilmState, HugeFilesAreRefusedByMagicOrSizeBeforeTheyAreRead) {
  constexpr uint64_t k16GiB = uint64_t(16) << 30;
  // Removed however the test ends: a reader that throws something else
  // (std::bad_alloc, as it did) must not leave 16 GiB files in /tmp.
  struct Removed {
    fs::path file;
    ~Removed() {
      std::error_code ignored;
      fs::remove(file, ignored);
    }
  };
  const Removed noMagic{tempFile("zeros.state")}, grown{tempFile("grown.state")};
  std::ofstream(noMagic.file, std::ios::binary | std::ios::trunc).close();
  fs::resize_file(noMagic.file, k16GiB);
  EXPECT_EQ(readRefusal(noMagic.file), noMagic.file.string() + ": not a spectrace state file (no SPCTRSTA magic)");

  writeFilmState(grown.file, craftedState({{0, 10}}));
  const uint64_t size = fs::file_size(grown.file);
  fs::resize_file(grown.file, k16GiB);
  const std::string refusal = readRefusal(grown.file);
  EXPECT_EQ(refusal.rfind(grown.file.string() + ": the file is 17179869184 bytes, but its header implies " +
                              std::to_string(size) + ": 16 (magic, version, header length) + ",
                          0),
            0u)
      << refusal;
  EXPECT_NE(refusal.find(" (/compressed_bytes) + 32 (SHA-256); it is truncated or has bytes after its end"),
            std::string::npos)
      << refusal;
}

// A range may end at 2^64 exactly but not pass it: beam numbers do not
// wrap to 0, where they would be beams another state already counts.
TEST(FilmState, RangesPassing2To64AreRefused) {
  EXPECT_EQ(refusalOf(craftedState({{UINT64_MAX - 9, 10}})), "");
  const std::string wraps = refusalOf(craftedState({{10, 10}, {20, UINT64_MAX - 9}}));
  EXPECT_NE(wraps.find("crafted.state: /ranges/1: [20, +18446744073709551606) runs past beam 2^64 - 1"),
            std::string::npos)
      << wraps;
  EXPECT_NE(refusalOf(craftedState({{UINT64_MAX, 2}})).find("/ranges/0: [18446744073709551615, +2) runs past"),
            std::string::npos);
}

// Two ranges of one state that share beams would count them twice.
TEST(FilmState, OverlappingRangesInOneStateAreRefused) {
  EXPECT_EQ(refusalOf(craftedState({{20, 5}, {0, 10}, {10, 10}})), "") << "touching ranges share no beam";
  const std::string overlap = refusalOf(craftedState({{0, 10}, {20, 5}, {8, 4}}));
  EXPECT_NE(overlap.find("crafted.state: /ranges/2: [8, +4) and /ranges/0 [0, +10) share beam 8"), std::string::npos)
      << overlap;
  const std::string same = refusalOf(craftedState({{5, 1}, {5, 1}}));
  EXPECT_NE(same.find("/ranges/1: [5, +1) and /ranges/0 [5, +1) share beam 5"), std::string::npos) << same;
  // A range ending at 2^64 is compared without overflow.
  const std::string top = refusalOf(craftedState({{UINT64_MAX - 9, 10}, {UINT64_MAX - 20, 12}}));
  EXPECT_NE(top.find("/ranges/1: [18446744073709551595, +12) and /ranges/0 [18446744073709551606, +10) share beam "
                     "18446744073709551606"),
            std::string::npos)
      << top;
}

// An empty range is what a render stopped before its first beam writes, as
// its only range; beside others it means nothing.
TEST(FilmState, EmptyRangesAreReadOnlyAlone) {
  EXPECT_EQ(refusalOf(craftedState({{7, 0}})), "");
  const std::string beside = refusalOf(craftedState({{0, 5}, {5, 0}}));
  EXPECT_NE(beside.find("/ranges/1: [5, +0) holds no beams; only a state of no beams at all has an empty range"),
            std::string::npos)
      << beside;
}

// FilmState::beams sums the ranges: disjoint ranges covering every beam
// would sum to 2^64, which wraps to 0.
TEST(FilmState, RangesOfMoreThan2To64Minus1BeamsAreRefused) {
  const std::string all = refusalOf(craftedState({{0, kHalf}, {kHalf, kHalf}}));
  EXPECT_NE(all.find("crafted.state: /ranges: the ranges hold more than 2^64 - 1 beams in all"), std::string::npos)
      << all;
  EXPECT_EQ(refusalOf(craftedState({{0, kHalf}, {kHalf, kHalf - 1}})), "");
}

// Each beam is counted at most once.
TEST(FilmState, MoreCountedBeamsThanRangesAreRefused) {
  EXPECT_EQ(refusalOf(craftedState({{0, 10}, {20, 5}}, 15)), "");
  const std::string more = refusalOf(craftedState({{0, 10}, {20, 5}}, 16));
  EXPECT_NE(more.find("crafted.state: /counted_beams: 16 beams counted, more than the 15 beams of /ranges"),
            std::string::npos)
      << more;
}

// A header field that is missing or of the wrong kind is named by its JSON
// pointer (it used to be a bare nlohmann message).
TEST(FilmState, BadHeaderFieldsAreNamed) {
  const fs::path file = tempFile("fields.state");
  writeFilmState(file, craftedState({{0, 10}}));
  const std::string bytes = fileBytes(file);
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  const nlohmann::json header = nlohmann::json::parse(bytes.substr(16, length));
  // `value` at `pointer`; null: the field left out.
  auto refusalWith = [&](const std::string& pointer, const nlohmann::json& value) {
    nlohmann::json edited = header;
    const nlohmann::json::json_pointer at(pointer);
    if (value.is_null()) edited.at(at.parent_pointer()).erase(at.back());
    else edited[at] = value;
    std::ofstream(file, std::ios::binary | std::ios::trunc) << withHeader(bytes, edited, 2);
    return readRefusal(file);
  };
  EXPECT_NE(refusalWith("/fingerprint/bins", "4").find("fields.state: /fingerprint/bins: must be an integer"),
            std::string::npos);
  EXPECT_NE(refusalWith("/ranges/0", {1, 2, 3}).find("fields.state: /ranges/0: must be [first, count]"),
            std::string::npos);
  EXPECT_NE(refusalWith("/ranges/0/1", -1).find("fields.state: /ranges/0/1: must be an integer"), std::string::npos);
  EXPECT_NE(refusalWith("/counted_beams", nullptr).find("fields.state: /counted_beams: missing required field"),
            std::string::npos);
  EXPECT_NE(refusalWith("/fingerprint/compile_options/aim", 1)
                .find("fields.state: /fingerprint/compile_options/aim: must be true or false"),
            std::string::npos);
}

// The sum of two states' counters past 2^64 - 1 would wrap to a small count
// (an image that was bright becomes black): refused, naming the channel, the
// pixel, the bin and the files.
TEST(FilmState, MergedCountersPassing2To64AreRefusedNamingTheCounter) {
  FilmState a = craftedState({{0, 10}}, 0, true), b = craftedState({{10, 10}}, 0, true);  // one-word counters
  const size_t pixel = 1 * 3 + 2;  // (2, 1)
  a.histogram.at(pixel, 3) = UINT64_MAX - 4;
  b.histogram.at(pixel, 3) = 4;
  EXPECT_NO_THROW(mergeStates(a, b)) << "a sum of exactly 2^64 - 1 fits";
  b.histogram.at(pixel, 3) = 5;
  try {
    mergeStates(a, b);
    ADD_FAILURE() << "merged counters that pass 2^64 - 1";
  } catch (const FilmStateError& e) {
    EXPECT_STREQ(e.what(), "counts at pixel (2, 1), bin 3: 18446744073709551611 + 5 passes 2^64 - 1, the most a "
                           "counter holds");
  }
  b.histogram.at(pixel, 3) = 0;
  a.histogram.colourSums()[3 * 3 + 1] = UINT64_MAX;  // pixel (0, 1), Y
  b.histogram.colourSums()[3 * 3 + 1] = 1;
  EXPECT_THROW(
      {
        try {
          mergeStates(a, b);
        } catch (const FilmStateError& e) {
          EXPECT_NE(std::string(e.what()).find("colour_sums at pixel (0, 1), Y: 18446744073709551615 + 1"),
                    std::string::npos)
              << e.what();
          throw;
        }
      },
      FilmStateError);
  // Through files, the refusal names both.
  const fs::path fileA = tempFile("a.state"), fileB = tempFile("b.state");
  writeFilmState(fileA, a);
  writeFilmState(fileB, b);
  try {
    mergeStateFiles({fileA, fileB});
    ADD_FAILURE() << "merged files whose counters pass 2^64 - 1";
  } catch (const FilmStateError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("cannot merge " + fileB.string() + " with " + fileA.string() +
                                              ": colour_sums at pixel (0, 1), Y: ",
                                          0),
              0u)
        << e.what();
  }
}

// Merging stops at the first counter that would pass 2^64 - 1 and leaves it
// and the ones after it as they were; the counted beams are checked too.
TEST(FilmState, AddChannelStopsAtTheFirstOverflow) {
  std::vector<uint64_t> mine = {1, UINT64_MAX, 7, UINT64_MAX}, theirs = {2, 1, 1, 1};
  EXPECT_EQ(addChannel(mine.data(), theirs.data(), 4, 1), std::optional<size_t>(1));
  EXPECT_EQ(mine, (std::vector<uint64_t>{3, UINT64_MAX, 7, UINT64_MAX}));
  mine = {1, 2};
  theirs = {UINT64_MAX - 1, 0};
  EXPECT_EQ(addChannel(mine.data(), theirs.data(), 2, 1), std::nullopt);
  EXPECT_EQ(mine, (std::vector<uint64_t>{UINT64_MAX, 2}));
  // Two words a counter: the low word's carry reaches the high word, and
  // only a sum past 2^128 - 1 stops the add.
  mine = {UINT64_MAX, 5, UINT64_MAX, UINT64_MAX, 0, 0};
  theirs = {2, 1, 1, 0, 1, 1};
  EXPECT_EQ(addChannel(mine.data(), theirs.data(), 6, 2), std::optional<size_t>(1));
  EXPECT_EQ(mine, (std::vector<uint64_t>{1, 7, UINT64_MAX, UINT64_MAX, 0, 0}));
  SpectralHistogram a(1, 1, 1), b(1, 1, 1);
  a.countedBeams = UINT64_MAX;
  b.countedBeams = 1;
  EXPECT_THROW(a.merge(b), CounterOverflow);
}

// Two states whose ranges together hold 2^64 beams: their sum would wrap.
TEST(FilmState, MergedRangesOfMoreThan2To64Minus1BeamsAreRefused) {
  const FilmState low = craftedState({{0, kHalf}}), high = craftedState({{kHalf, kHalf}});
  EXPECT_EQ(mergeRefusal(low, high),
            "/ranges: 9223372036854775808 + 9223372036854775808 beams pass 2^64 - 1, the most a state counts");
  EXPECT_THROW(mergeStates(low, high), FilmStateError);
  EXPECT_EQ(mergeStates(low, craftedState({{kHalf, kHalf - 1}})).beams(), UINT64_MAX);
  // An empty range (a render stopped before its first beam) is dropped, so
  // the merge reads back.
  const FilmState merged = mergeStates(craftedState({{0, 10}}), craftedState({{10, 0}}));
  EXPECT_EQ(merged.ranges, (std::vector<BeamRange>{{0, 10}}));
  EXPECT_EQ(refusalOf(merged), "");
}

// A state carries its scene bundle (binary bytes and all) and its
// irradiance scale, and reads back with them and its film bit for bit.
TEST(FilmState, VersionFourCarriesTheBundleAndScaleBitForBit) {
  const CompiledScene plan = compileScene(weightedScene(), 4);
  CpuTracer cpu(plan, 2);
  FilmState state = stateOf(plan, cpu, 1000, 50'000, 4);
  SceneBundle bundle;
  bundle.sceneText = "{\"lights\": []}\n";
  bundle.files["spd/lamp.csv"] = "wavelength_nm,value\n380,1\n";
  static constexpr char kBinary[] = "v 0 0 0\n\0\xff\x80 not UTF-8";  // a NUL and bytes that are not UTF-8
  bundle.files["models/cube.obj"] = std::string(kBinary, sizeof kBinary - 1);
  state.bundle = bundle;
  state.irradiancePerCount = plan.irradiancePerCount(50'000);
  const fs::path file = tempFile("bundle.state");
  writeFilmState(file, state);
  const FilmState back = readFilmState(file);
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c)
    EXPECT_EQ(back.histogram.channel(c), state.histogram.channel(c)) << filmChannelName(c);
  EXPECT_EQ(back.histogram.countedBeams, state.histogram.countedBeams);
  EXPECT_TRUE(back.histogram.sameShape(state.histogram));
  EXPECT_EQ(back.ranges, state.ranges);
  EXPECT_EQ(fingerprintText(back.fingerprint), fingerprintText(state.fingerprint));
  ASSERT_TRUE(back.bundle.has_value());
  EXPECT_EQ(*back.bundle, bundle);
  EXPECT_EQ(back.irradiancePerCount, state.irradiancePerCount);
  // The header says it for a reader without spectrace.
  const nlohmann::json header = partsOf(fileBytes(file)).header;
  EXPECT_EQ(header.at("irradiance_per_count").get<double>(), state.irradiancePerCount);
  EXPECT_EQ(header.at("compression"), "zstd");
  EXPECT_EQ(header.at("bundle").at("scene_bytes"), bundle.sceneText.size());
  EXPECT_EQ(header.at("bundle").at("files").at(0).at("path"), "models/cube.obj");
  EXPECT_EQ(header.at("bundle").at("files").at(0).at("bytes"), bundle.files.at("models/cube.obj").size());
}

// An empty 512 x 512 pixel film of 64 bins (128 MiB of counters) is a
// small file, and reads back whole.
TEST(FilmState, AnEmptyBigFilmCompressesSmall) {
  FilmState state = craftedState({{0, 0}});
  FilmFingerprint& f = state.fingerprint;
  f.pixelsX = f.pixelsY = 512;
  f.bins = f.storedBins = 64;
  f.window = {0, 0, 512, 512};
  state.histogram = SpectralHistogram(512, 512, 64);
  const fs::path file = tempFile("empty_big.state");
  writeFilmState(file, state);
  EXPECT_LT(fs::file_size(file), uint64_t(1) << 20);
  const FilmState back = readFilmState(file);
  EXPECT_EQ(back.histogram.counts(), state.histogram.counts());
}

// The crafted body `body` in place of the file's compressed stream, its
// length re-stated and the file re-signed: a stream that passes the
// checksum, for the decompressor's own refusals.
std::string withBody(const std::string& bytes, const std::string& body) {
  StateParts parts = partsOf(bytes);
  parts.header["compressed_bytes"] = body.size();
  return stateBytes(4, parts.header, body);
}

std::string zstdOf(const std::string& raw) {
  std::string out(ZSTD_compressBound(raw.size()), '\0');
  out.resize(ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), 1));
  return out;
}

// A compressed stream that is corrupt, inflates past the lengths its header
// declares, ends before them, is cut short or has bytes after its frame is
// refused naming the file, never read in part.
TEST(FilmState, BrokenCompressedStreamsAreRefusedNamingTheFile) {
  FilmState state = craftedState({{0, 10}}, 5, true);
  state.histogram.counts()[3] = 7;
  state.bundle = SceneBundle{"{\"scene\": 1}", {{"a.csv", "380,1\n"}}};
  const fs::path file = tempFile("stream.state");
  writeFilmState(file, state);
  const std::string bytes = fileBytes(file);
  const std::string body = partsOf(bytes).body;
  std::string raw = state.bundle->sceneText + state.bundle->files.at("a.csv");
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c)
    raw.append(reinterpret_cast<const char*>(state.histogram.channel(c).data()),
               state.histogram.channel(c).size() * sizeof(uint64_t));
  const fs::path crafted = tempFile("crafted_stream.state");
  auto refusal = [&](const std::string& newBody) {
    std::ofstream(crafted, std::ios::binary | std::ios::trunc) << withBody(bytes, newBody);
    const std::string why = readRefusal(crafted);
    if (!why.empty()) {
      EXPECT_EQ(why.rfind(crafted.string() + ": ", 0), 0u) << "names the file: " << why;
    }
    return why;
  };
  EXPECT_EQ(refusal(body), "") << "the re-signed stream itself reads";
  EXPECT_EQ(refusal(zstdOf(raw)), "") << "so does any zstd frame of the same bytes";
  std::string corrupt = body;
  corrupt[0] ^= 0x55;  // the frame's magic number
  EXPECT_NE(refusal(corrupt).find("the compressed stream is corrupt within the bundled scene"), std::string::npos)
      << refusal(corrupt);
  const std::string past = refusal(zstdOf(raw + std::string(8, '\1')));
  EXPECT_NE(past.find("the compressed stream inflates past the bytes its header declares"), std::string::npos) << past;
  const std::string shortOfIt = refusal(zstdOf(raw.substr(0, raw.size() - 8)));
  EXPECT_NE(shortOfIt.find("the compressed stream ends within /colour_sums, before the bytes its header declares"),
            std::string::npos)
      << shortOfIt;
  const std::string cut = refusal(body.substr(0, body.size() - 3));
  EXPECT_NE(cut.find("truncated"), std::string::npos) << cut;
  const std::string after = refusal(body + "xyz");
  EXPECT_NE(after.find("the compressed stream has bytes after its zstd frame"), std::string::npos) << after;
}

// A header may not declare a film bigger than its stream can inflate to:
// a file of a few hundred bytes cannot make the reader allocate gigabytes.
TEST(FilmState, AFilmBeyondWhatItsStreamCanHoldIsRefusedBeforeAllocating) {
  const fs::path file = tempFile("claims.state");
  writeFilmState(file, craftedState({{0, 10}}));
  StateParts parts = partsOf(fileBytes(file));
  parts.header["fingerprint"]["pixels_x"] = 4096;
  parts.header["fingerprint"]["pixels_y"] = 4096;
  parts.header["fingerprint"]["bins"] = 64;
  parts.header["counts"] = uint64_t(4096) * 4096 * 64;
  std::ofstream(file, std::ios::binary | std::ios::trunc) << stateBytes(4, parts.header, parts.body);
  const std::string refusal = readRefusal(file);
  EXPECT_NE(refusal.find("claims.state: /compressed_bytes: " + std::to_string(parts.body.size()) +
                         " bytes of zstd cannot inflate to the 8589934592 bytes the header declares"),
            std::string::npos)
      << refusal;
}

// A state written before version 4 (uncompressed, no bundle) still reads,
// and merged with a version 4 state of the same render takes that one's
// bundle, with the scene path its keys resolve from.
TEST(FilmState, VersionThreeStatesStillReadAndTakeABundleInAMerge) {
  FilmState old = craftedState({{0, 10}}, 4, true);
  old.histogram.counts()[5] = 3;
  old.histogram.colourSums()[2] = 11;
  const fs::path oldFile = tempFile("version3.state");
  std::ofstream(oldFile, std::ios::binary | std::ios::trunc) << legacyStateBytes(old, 3);
  const FilmState read = readFilmState(oldFile);
  EXPECT_EQ(read.histogram.counts(), old.histogram.counts());
  EXPECT_EQ(read.histogram.colourSums(), old.histogram.colourSums());
  EXPECT_EQ(read.histogram.countedBeams, 4u);
  EXPECT_EQ(read.ranges, old.ranges);
  EXPECT_FALSE(read.bundle.has_value());
  EXPECT_EQ(read.irradiancePerCount, 0.0);

  FilmState bundled = craftedState({{10, 10}}, 0, true);
  bundled.fingerprint.sceneFile = "elsewhere/scene.json";
  bundled.bundle = SceneBundle{"{}", {{"elsewhere/a.csv", "380,1\n"}}};
  const fs::path newFile = tempFile("version4.state");
  writeFilmState(newFile, bundled);
  for (const FilmState& merged : {mergeStateFiles({oldFile, newFile}), mergeStateFiles({newFile, oldFile})}) {
    ASSERT_TRUE(merged.bundle.has_value());
    EXPECT_EQ(*merged.bundle, *bundled.bundle);
    EXPECT_EQ(merged.fingerprint.sceneFile, "elsewhere/scene.json");
    EXPECT_EQ(merged.beams(), 20u);
  }
}

// Three shards of different sizes, traced on the CPU, the GPU and the CPU,
// written and read back, merge into the film of one render of all beams,
// and develop into the same image on the same device.
TEST(FilmState, ShardsMergeIntoExactlyOneRender) {
  const Scene scene = weightedScene();
  const CompiledScene plan = compileScene(scene, 4);
  constexpr uint64_t kBeams = 300'000;
  CpuTracer cpu(plan, 2);
  VulkanTracer gpu(testing::sharedVulkan(), plan);
  const uint64_t cuts[] = {0, 70'001, 190'000, kBeams};
  Tracer* devices[] = {&cpu, &gpu, &cpu};
  FilmState merged;
  for (int s = 0; s < 3; ++s) {
    const fs::path file = tempFile("shard" + std::to_string(s) + ".state");
    writeFilmState(file, stateOf(plan, *devices[s], cuts[s], cuts[s + 1] - cuts[s], 4));
    const FilmState shard = readFilmState(file);
    merged = s == 0 ? shard : mergeStates(merged, shard);
  }
  EXPECT_EQ(merged.beams(), kBeams);
  gpu.clear();
  gpu.trace(0, kBeams);
  const SpectralHistogram whole = gpu.download();
  EXPECT_EQ(merged.histogram.counts(), whole.counts());
  EXPECT_EQ(merged.histogram.colourSums(), whole.colourSums());
  EXPECT_EQ(merged.histogram.squaredWeightSums(), whole.squaredWeightSums());
  EXPECT_EQ(merged.histogram.countedBeams, whole.countedBeams);
  // Developed on the same device, the merged film gives the same pixels.
  const ResolveParameters parameters = resolveParametersFor(scene, plan, kBeams);
  const RenderImage one = gpu.develop(parameters);
  gpu.upload(merged.histogram);
  const RenderImage fromShards = gpu.develop(parameters);
  EXPECT_EQ(fromShards.rgb, one.rgb);
  EXPECT_EQ(fromShards.xyz, one.xyz);
  EXPECT_EQ(fromShards.irradiance, one.irradiance);
}

}  // namespace
}  // namespace spectrace
