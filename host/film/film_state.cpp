#include "film/film_state.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <numeric>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <openssl/evp.h>
#include <zstd.h>

#include "io/atomic_file.h"
#include "json/input_file.h"
#include "json/json_fields.h"

namespace spectrace {
namespace {

using nlohmann::json;
namespace jf = json_fields;

constexpr char kMagic[8] = {'S', 'P', 'C', 'T', 'R', 'S', 'T', 'A'};
// 4: the scene bundle, the irradiance scale, and the bundle and arrays in
// one zstd stream; 3: weighted films in two-word counters
// (kWeightUnitsFractional, 2^63); 2: the fingerprint's compile_options
// object; 1: four of the options as fields of their own. 1 to 3 are still
// read, except weighted films of 1 and 2 (2^24 units in one word), which are
// refused by name.
constexpr uint32_t kVersion = 4;
constexpr uint32_t kFirstCompressedVersion = 4;
constexpr size_t kPrefixBytes = 16;  // magic, version, header length
constexpr size_t kDigestBytes = 32;  // SHA-256
constexpr uint64_t kReadPieceBytes = uint64_t(1) << 20;  // compressed bytes read at a time

json toJson(const FilmFingerprint& f) {
  return {{"scene_file", f.sceneFile},
          {"scene_sha256", f.sceneSha256},
          {"referenced_files_sha256", f.referencedFilesSha256},
          {"observer", f.observer},
          {"spectrum_min_nm", f.lambdaMinNm},
          {"spectrum_max_nm", f.lambdaMaxNm},
          {"bins", f.bins},
          {"pixels_x", f.pixelsX},
          {"pixels_y", f.pixelsY},
          {"window", {f.window.x0, f.window.y0, f.window.width, f.window.height}},
          {"first_stored_bin", f.firstStoredBin},
          {"stored_bins", f.storedBins},
          {"exact_colour", f.exactColour},
          {"colour_from_bins", f.colourFromBins},
          {"weight_units", f.weightUnits},
          {"seed", f.seed},
          {"specialisation", f.specialisation},
          {"compile_options", f.compileOptions},
          {"wavelengths_per_beam", f.wavelengthsPerBeam}};
}

// Header refusals are "<file>: <json pointer>: <what is wrong>".
[[noreturn]] void raiseStateError(const std::string& message) { throw FilmStateError(message); }

jf::Source sourceOf(const std::filesystem::path& file) {
  jf::Source source;
  source.file = file.string();
  source.raise = raiseStateError;
  return source;
}

// The fields of one header object, each refused by its pointer when it is
// missing or of the wrong kind.
struct HeaderFields {
  const jf::Source& source;
  const json& object;
  std::string ptr;

  std::string where(const std::string& key) const { return jf::child(ptr, key); }
  const json& at(const std::string& key) const { return jf::require(source, object, ptr, key); }
  uint64_t u64(const std::string& key) const { return jf::getU64(source, at(key), where(key), 0); }
  uint32_t u32(const std::string& key) const { return u32Of(at(key), where(key)); }
  uint32_t u32Of(const json& v, const std::string& at) const {
    return uint32_t(jf::getInt(source, v, at, 0, UINT32_MAX));
  }
  double number(const std::string& key) const { return jf::getNumber(source, at(key), where(key)); }
  std::string text(const std::string& key) const { return jf::getString(source, at(key), where(key), true); }
  bool flagOf(const json& v, const std::string& at) const {
    if (!v.is_boolean()) source.fail(at, fmt::format("must be true or false (got {})", jf::describe(v)));
    return v.get<bool>();
  }
  bool flag(const std::string& key) const { return flagOf(at(key), where(key)); }
  HeaderFields child(const std::string& key) const {
    if (!at(key).is_object())
      source.fail(where(key), fmt::format("must be an object (got {})", jf::describe(at(key))));
    return {source, at(key), where(key)};
  }
};

PixelWindow windowOf(const HeaderFields& j) {
  const json& w = j.at("window");
  if (!w.is_array() || w.size() != 4)
    j.source.fail(j.where("window"), fmt::format("must be [x0, y0, width, height] (got {})", jf::describe(w)));
  auto part = [&](size_t i) { return j.u32Of(w[i], jf::child(j.where("window"), i)); };
  return {part(0), part(1), part(2), part(3)};
}

std::map<std::string, bool> compileOptionsOf(const HeaderFields& j, const FilmFingerprint& f, uint32_t version) {
  std::map<std::string, bool> options;
  if (version >= 2) {
    const HeaderFields named = j.child("compile_options");
    for (const auto& [name, value] : named.object.items()) options[name] = named.flagOf(value, named.where(name));
    // States from before camera paths traced light paths only.
    options.try_emplace("light_paths", true);
    options.try_emplace("camera_paths", false);
    return options;
  }
  // Version 1 recorded four options and the film's colour; the other two
  // options it did not record are taken at their defaults (a version 1
  // state of a --no-connect render is refused on resume by its weight
  // units, not silently mixed).
  options["aim"] = j.flag("aimed");
  options["skip_unreachable_lights"] = j.flag("skip_unreachable_lights");
  options["trim_spectrum"] = j.flag("trim_spectrum");
  options["trim_pixels"] = j.flag("trim_pixels");
  options["exact_colour"] = f.exactColour || f.colourFromBins;
  options["colour_from_bins"] = f.colourFromBins;
  options["connect"] = true;
  options["brute_force_objects"] = false;
  options["light_paths"] = true;
  options["camera_paths"] = false;
  return options;
}

FilmFingerprint fingerprintFromJson(const HeaderFields& j, uint32_t version) {
  FilmFingerprint f;
  f.sceneFile = j.text("scene_file");
  f.sceneSha256 = j.text("scene_sha256");
  if (jf::find(j.object, "referenced_files_sha256")) f.referencedFilesSha256 = j.text("referenced_files_sha256");
  f.observer = j.text("observer");
  f.lambdaMinNm = j.number("spectrum_min_nm");
  f.lambdaMaxNm = j.number("spectrum_max_nm");
  f.bins = j.u32("bins");
  f.pixelsX = j.u32("pixels_x");
  f.pixelsY = j.u32("pixels_y");
  f.window = windowOf(j);
  f.firstStoredBin = j.u32("first_stored_bin");
  f.storedBins = j.u32("stored_bins");
  f.exactColour = j.flag("exact_colour");
  f.colourFromBins = jf::find(j.object, "colour_from_bins") && j.flag("colour_from_bins");
  f.weightUnits = j.u64("weight_units");
  f.seed = j.u64("seed");
  f.specialisation = j.u32("specialisation");
  f.compileOptions = compileOptionsOf(j, f, version);
  if (jf::find(j.object, "wavelengths_per_beam")) {
    f.wavelengthsPerBeam = j.u32("wavelengths_per_beam");
    const uint32_t k = f.wavelengthsPerBeam;
    if (k == 0 || k > device::kMaxWavelengthsPerPath || (k & (k - 1)) != 0)
      j.source.fail(j.where("wavelengths_per_beam"), fmt::format("must be 1, 2 or 4 (got {})", k));
  }
  return f;
}

// Sorted by first beam.
std::vector<BeamRange> sortedRanges(std::vector<BeamRange> ranges) {
  std::sort(ranges.begin(), ranges.end(), [](const BeamRange& a, const BeamRange& b) { return a.first < b.first; });
  return ranges;
}

std::string rangeText(const BeamRange& r) { return fmt::format("[{}, +{})", r.first, r.count); }

std::string overlap(const std::vector<BeamRange>& a, const std::vector<BeamRange>& b) {
  for (const BeamRange& x : a)
    for (const BeamRange& y : b) {
      // Ranges may end at 2^64 exactly: compare without overflow.
      const uint64_t start = std::max(x.first, y.first);
      const bool xCovers = start - x.first < x.count, yCovers = start - y.first < y.count;
      if (x.count && y.count && xCovers && yCovers)
        return fmt::format("/ranges: their beam ranges overlap: {} and {} share beam {}", rangeText(x), rangeText(y),
                           start);
    }
  return "";
}

// The beams of all the ranges, or nullopt when they pass 2^64 - 1.
std::optional<uint64_t> beamsOf(const std::vector<BeamRange>& ranges, uint64_t total = 0) {
  for (const BeamRange& r : ranges)
    if (__builtin_add_overflow(total, r.count, &total)) return std::nullopt;
  return total;
}

// Writing.

// zstd level 1, its fastest ordinary level: a state is rewritten at every
// checkpoint and at the end while the render waits for it, and a film's
// runs of zeros and small counts shrink well at any level.
constexpr int kZstdLevel = 1;

// One zstd frame, fed part by part straight from the bundle and the film
// (no uncompressed copy of the film is made).
class BodyDeflater {
 public:
  explicit BodyDeflater(uint64_t inflatedBytes) : context_(ZSTD_createCCtx()) {
    if (!context_) throw FilmStateError("cannot start zstd compression (out of memory)");
    ZSTD_CCtx_setParameter(context_, ZSTD_c_compressionLevel, kZstdLevel);
    // The frame header then records the size, so a reader (Python's
    // zstandard.decompress) knows it.
    ZSTD_CCtx_setPledgedSrcSize(context_, inflatedBytes);
  }
  ~BodyDeflater() { ZSTD_freeCCtx(context_); }
  BodyDeflater(const BodyDeflater&) = delete;
  BodyDeflater& operator=(const BodyDeflater&) = delete;

  void add(const void* data, size_t bytes) { run(data, bytes, ZSTD_e_continue); }
  std::vector<unsigned char> finish() {
    run(nullptr, 0, ZSTD_e_end);
    return std::move(out_);
  }

 private:
  void run(const void* data, size_t bytes, ZSTD_EndDirective mode) {
    ZSTD_inBuffer input{data, bytes, 0};
    for (;;) {
      const size_t at = out_.size();
      out_.resize(at + ZSTD_CStreamOutSize());
      ZSTD_outBuffer output{out_.data() + at, ZSTD_CStreamOutSize(), 0};
      const size_t left = ZSTD_compressStream2(context_, &output, &input, mode);
      out_.resize(at + output.pos);
      if (ZSTD_isError(left)) throw FilmStateError(fmt::format("zstd compression failed: {}", ZSTD_getErrorName(left)));
      if (mode == ZSTD_e_end ? left == 0 : input.pos == input.size) return;
    }
  }

  ZSTD_CCtx* context_;
  std::vector<unsigned char> out_;
};

uint64_t inflatedBytesOf(const FilmState& state) {
  uint64_t bytes = 0;
  if (state.bundle) {
    bytes += state.bundle->sceneText.size();
    for (const auto& [path, content] : state.bundle->files) bytes += content.size();
  }
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) bytes += state.histogram.channel(c).size() * sizeof(uint64_t);
  return bytes;
}

// The bundle (the scene's text, then each file in path order) and the three
// arrays, compressed as one stream.
std::vector<unsigned char> compressedBody(const FilmState& state) {
  BodyDeflater body(inflatedBytesOf(state));
  if (state.bundle) {
    body.add(state.bundle->sceneText.data(), state.bundle->sceneText.size());
    for (const auto& [path, content] : state.bundle->files) body.add(content.data(), content.size());
  }
  // Little-endian on every machine we build for (x86-64, arm64).
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c)
    body.add(state.histogram.channel(c).data(), state.histogram.channel(c).size() * sizeof(uint64_t));
  return body.finish();
}

json headerOf(const FilmState& state, uint64_t compressedBytes) {
  const SpectralHistogram& h = state.histogram;
  json header = {{"fingerprint", toJson(state.fingerprint)},
                 {"ranges", json::array()},
                 {"counted_beams", h.countedBeams},
                 {"units_per_beam", h.unitsPerBeam},
                 {"irradiance_per_count", state.irradiancePerCount},
                 {"compression", "zstd"},
                 {"compressed_bytes", compressedBytes}};
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) header[filmChannelName(c)] = h.channel(c).size();
  for (const BeamRange& r : state.ranges) header["ranges"].push_back({r.first, r.count});
  if (state.bundle) {
    json files = json::array();
    for (const auto& [path, content] : state.bundle->files) files.push_back({{"path", path}, {"bytes", content.size()}});
    header["bundle"] = {{"scene_bytes", state.bundle->sceneText.size()}, {"files", std::move(files)}};
  }
  return header;
}

// Reading. Everything the header says is checked before the arrays are
// read: a file is refused by its size, not after reading gigabytes.

// Refuses a range that cannot be beams of one render: one that runs past
// 2^64 (beam numbers never wrap to 0), or an empty one beside others (a
// render writes one empty range only when it stopped before its first beam).
void checkRange(const jf::Source& source, const std::vector<BeamRange>& ranges, size_t i) {
  const BeamRange& r = ranges[i];
  const std::string at = jf::child("/ranges", i);
  if (r.count != 0 && r.count - 1 > UINT64_MAX - r.first)  // its last beam, first + count - 1, wraps
    source.fail(at, fmt::format("{} runs past beam 2^64 - 1; beam numbers do not wrap to 0", rangeText(r)));
  if (r.count == 0 && ranges.size() > 1)
    source.fail(at, fmt::format("{} holds no beams; only a state of no beams at all has an empty range", rangeText(r)));
}

// Refuses two ranges of one state that share beams: they would be counted twice.
void checkDisjoint(const jf::Source& source, const std::vector<BeamRange>& ranges) {
  std::vector<size_t> order(ranges.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return ranges[a].first < ranges[b].first; });
  // Sorted by first beam, two ranges share beams only if two neighbours do.
  for (size_t k = 1; k < order.size(); ++k) {
    const BeamRange &a = ranges[order[k - 1]], &b = ranges[order[k]];
    if (b.first - a.first >= a.count) continue;
    const size_t early = std::min(order[k - 1], order[k]), late = std::max(order[k - 1], order[k]);
    source.fail(jf::child("/ranges", late), fmt::format("{} and /ranges/{} {} share beam {}", rangeText(ranges[late]),
                                                        early, rangeText(ranges[early]), b.first));
  }
}

// The beams the ranges hold, after refusing ranges no render writes.
uint64_t checkRanges(const jf::Source& source, const std::vector<BeamRange>& ranges) {
  for (size_t i = 0; i < ranges.size(); ++i) checkRange(source, ranges, i);
  checkDisjoint(source, ranges);
  const auto beams = beamsOf(ranges);
  if (!beams) source.fail("/ranges", "the ranges hold more than 2^64 - 1 beams in all, the most a state counts");
  return *beams;
}

std::vector<BeamRange> rangesOf(const HeaderFields& header) {
  const json& list = header.at("ranges");
  if (!list.is_array()) header.source.fail("/ranges", fmt::format("must be an array (got {})", jf::describe(list)));
  std::vector<BeamRange> ranges;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string at = jf::child("/ranges", i);
    if (!list[i].is_array() || list[i].size() != 2)
      header.source.fail(at, fmt::format("must be [first, count] (got {})", jf::describe(list[i])));
    ranges.push_back({jf::getU64(header.source, list[i][0], jf::child(at, 0), 0),
                      jf::getU64(header.source, list[i][1], jf::child(at, 1), 0)});
  }
  return ranges;
}

// The 16 bytes before the header.
struct StatePrefix {
  std::array<unsigned char, kPrefixBytes> bytes{};
  uint32_t version = 0, headerBytes = 0;
};

// A header holds a fingerprint and ranges: far below this, even for a merge of
// many states, and reading a bigger one would cost memory before its checks.
constexpr uint32_t kMaxHeaderBytes = uint32_t(kMaxInputFileBytes);

StatePrefix readPrefix(const InputFile& in) {
  StatePrefix p;
  const size_t got = in.readUpTo(0, p.bytes.data(), kPrefixBytes);
  if (got < sizeof kMagic || std::memcmp(p.bytes.data(), kMagic, sizeof kMagic) != 0)
    throw in.fail("not a spectrace state file (no SPCTRSTA magic)");
  if (in.size() < kPrefixBytes + kDigestBytes)
    throw in.fail(fmt::format("the file ends after {} bytes, before its header", in.size()));
  std::memcpy(&p.version, p.bytes.data() + 8, 4);
  std::memcpy(&p.headerBytes, p.bytes.data() + 12, 4);
  if (p.version < 1 || p.version > kVersion)
    throw in.fail(fmt::format("format version {} (this spectrace reads 1 to {})", p.version, kVersion));
  if (p.headerBytes > kMaxHeaderBytes)
    throw in.fail(fmt::format("header length {} bytes: more than the {} MiB a header may have", p.headerBytes,
                              kMaxHeaderBytes >> 20));
  if (kPrefixBytes + p.headerBytes + kDigestBytes > in.size())
    throw in.fail(fmt::format("header length {} bytes runs past the end of the file ({} bytes)", p.headerBytes,
                              in.size()));
  return p;
}

// The bundle as the header lays it out: its parts' lengths, in the order
// the compressed stream holds them (the scene's text, then each file).
struct BundleLayout {
  uint64_t sceneBytes = 0;
  std::vector<std::pair<std::string, uint64_t>> files;  // path, bytes
};

// A bundled scene file is at most as big as a scene file may be, and a
// bundled file as big as the scene loader reads one it names (its digest).
constexpr uint64_t kMaxBundledSceneBytes = kMaxInputFileBytes;
constexpr uint64_t kMaxBundledFileBytes = uint64_t(1) << 30;

struct StateHeader {
  uint32_t version = 0;
  std::string text;  // as in the file, padding and all: the digest covers it
  FilmFingerprint fingerprint;
  std::vector<BeamRange> ranges;
  uint64_t countedBeams = 0;
  std::array<uint64_t, device::kFilmChannelCount> lengths{};  // values in each array
  // Version 4 on.
  double irradiancePerCount = 0.0;
  uint64_t compressedBytes = 0;
  std::optional<BundleLayout> bundle;

  bool compressed() const { return version >= kFirstCompressedVersion; }
  // The bytes the compressed stream inflates to: the bundle, then the arrays.
  unsigned __int128 inflatedBytes() const {
    unsigned __int128 bytes = 0;
    for (uint64_t words : lengths) bytes += (unsigned __int128)words * sizeof(uint64_t);
    if (bundle) {
      bytes += bundle->sceneBytes;
      for (const auto& file : bundle->files) bytes += file.second;
    }
    return bytes;
  }
};

BundleLayout bundleLayoutOf(const HeaderFields& j) {
  BundleLayout layout;
  layout.sceneBytes = j.u64("scene_bytes");
  if (layout.sceneBytes > kMaxBundledSceneBytes)
    j.source.fail(j.where("scene_bytes"), fmt::format("{} bytes: more than the {} MiB a scene file may have",
                                                      layout.sceneBytes, kMaxBundledSceneBytes >> 20));
  const json& files = j.at("files");
  if (!files.is_array())
    j.source.fail(j.where("files"), fmt::format("must be an array (got {})", jf::describe(files)));
  std::set<std::string> seen;
  for (size_t i = 0; i < files.size(); ++i) {
    if (!files[i].is_object())
      j.source.fail(jf::child(j.where("files"), i), fmt::format("must be an object (got {})", jf::describe(files[i])));
    const HeaderFields file{j.source, files[i], jf::child(j.where("files"), i)};
    std::string path = file.text("path");
    const uint64_t bytes = file.u64("bytes");
    if (path.empty()) j.source.fail(file.where("path"), "must name a file");
    if (!seen.insert(path).second) j.source.fail(file.where("path"), fmt::format("{} is bundled twice", path));
    if (bytes > kMaxBundledFileBytes)
      j.source.fail(file.where("bytes"), fmt::format("{} bytes: more than the {} MiB a file named by a scene may have",
                                                     bytes, kMaxBundledFileBytes >> 20));
    layout.files.emplace_back(std::move(path), bytes);
  }
  return layout;
}

// The fields version 4 added: the irradiance scale, the compressed stream
// and the bundle (none when the header has no "bundle").
void readCompressionFields(const HeaderFields& fields, StateHeader& h) {
  h.irradiancePerCount = fields.number("irradiance_per_count");
  if (!(h.irradiancePerCount >= 0.0) || !std::isfinite(h.irradiancePerCount))
    fields.source.fail("/irradiance_per_count", fmt::format("must be a finite number >= 0 (got {})",
                                                            h.irradiancePerCount));
  if (const std::string method = fields.text("compression"); method != "zstd")
    fields.source.fail("/compression", fmt::format("{} (this spectrace reads \"zstd\")", jf::jsonQuoted(method)));
  h.compressedBytes = fields.u64("compressed_bytes");
  if (jf::find(fields.object, "bundle")) h.bundle = bundleLayoutOf(fields.child("bundle"));
}

StateHeader readHeader(const InputFile& in, const jf::Source& source, const StatePrefix& prefix) {
  StateHeader h;
  h.version = prefix.version;
  h.text.resize(prefix.headerBytes);
  in.readAt(kPrefixBytes, h.text.data(), h.text.size());
  const json root = jf::parseJson(source, h.text);
  if (!root.is_object()) source.fail("", fmt::format("the header must be an object (got {})", jf::describe(root)));
  const HeaderFields fields{source, root, ""};
  h.fingerprint = fingerprintFromJson(fields.child("fingerprint"), h.version);
  if (const uint64_t units = h.fingerprint.weightUnits; units != 1 && units != device::kWeightUnitsFractional)
    source.fail("/fingerprint/weight_units",
                fmt::format("{} {}", units,
                            h.version < 3 ? "is a weighted film of an older spectrace (one-word counters), which this "
                                            "one cannot merge or resume: render it again"
                                          : fmt::format("is neither 1 nor {} (2^63)", device::kWeightUnitsFractional)));
  h.ranges = rangesOf(fields);
  h.countedBeams = fields.u64("counted_beams");
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) h.lengths[c] = fields.u64(filmChannelName(c));
  if (h.compressed()) readCompressionFields(fields, h);
  return h;
}

// A beam is counted at most once (on the sensor, or not at all).
void checkCountedBeams(const jf::Source& source, const StateHeader& h, uint64_t beams) {
  if (h.countedBeams > beams)
    source.fail("/counted_beams", fmt::format("{} beams counted, more than the {} beams of /ranges", h.countedBeams,
                                              beams));
}

// Each array has the length of its film, compared in 128 bits before
// anything is allocated: a header cannot ask for more than its film.
void checkLengths(const jf::Source& source, const StateHeader& h) {
  const FilmFingerprint& f = h.fingerprint;
  const uint32_t held = device::filmChannelSetOf(f.exactColour, f.weightUnits != 1);
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) {
    const unsigned __int128 expected =
        device::filmStoresChannel(held, c)
            ? (unsigned __int128)f.pixelsX * f.pixelsY * device::filmChannelCounters(c, f.bins) *
                  device::filmCounterWords(held)
            : 0;
    if (h.lengths[c] != expected)
      source.fail(std::string("/") + filmChannelName(c),
                  fmt::format("{} values, but its film ({} x {} pixels, {} bins) has {}", h.lengths[c], f.pixelsX,
                              f.pixelsY, f.bins, expected));
  }
}

// The file's size is what the header implies, checked before the arrays
// are read: a truncated file, or one with bytes after its end, is refused
// by its size alone.
void checkCompressedFileSize(const InputFile& in, const jf::Source& source, const StateHeader& h);

void checkFileSize(const InputFile& in, const jf::Source& source, const StateHeader& h) {
  if (h.compressed()) return checkCompressedFileSize(in, source, h);
  unsigned __int128 words = 0;
  std::string arrays;
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) {
    words += h.lengths[c];
    arrays += fmt::format("{}{} /{}", c ? " + " : "", h.lengths[c], filmChannelName(c));
  }
  const unsigned __int128 expected = kPrefixBytes + h.text.size() + words * sizeof(uint64_t) + kDigestBytes;
  if (expected != in.size())
    throw in.fail(fmt::format("the file is {} bytes, but its header implies {}: {} (magic, version, header length) + "
                              "{} (header) + 8 x ({}) + {} (SHA-256); it is truncated or has bytes after its end",
                              in.size(), expected, kPrefixBytes, h.text.size(), arrays, kDigestBytes));
}

// No zstd stream inflates more than this many bytes a byte: a block yields
// at most 128 KiB and takes at least 4 bytes (an RLE block: a 3-byte header
// and its byte). A header may not declare more than its stream can hold, so
// a small file cannot make the reader allocate a huge film.
constexpr uint64_t kZstdMostBytesPerByte = 32768;

// Version 4: the file holds the prefix, the header, the compressed stream
// and the digest, and the stream can inflate to what the header declares.
void checkCompressedFileSize(const InputFile& in, const jf::Source& source, const StateHeader& h) {
  const unsigned __int128 expected =
      (unsigned __int128)kPrefixBytes + h.text.size() + h.compressedBytes + kDigestBytes;
  if (expected != in.size())
    throw in.fail(fmt::format("the file is {} bytes, but its header implies {}: {} (magic, version, header length) + "
                              "{} (header) + {} (/compressed_bytes) + {} (SHA-256); it is truncated or has bytes after "
                              "its end",
                              in.size(), expected, kPrefixBytes, h.text.size(), h.compressedBytes, kDigestBytes));
  if (h.inflatedBytes() > (unsigned __int128)h.compressedBytes * kZstdMostBytesPerByte)
    source.fail("/compressed_bytes",
                fmt::format("{} bytes of zstd cannot inflate to the {} bytes the header declares (the bundle and 8 x "
                            "the arrays' lengths)",
                            h.compressedBytes, h.inflatedBytes()));
}

class Sha256 {
 public:
  Sha256() : context_(EVP_MD_CTX_new()) { EVP_DigestInit_ex(context_, EVP_sha256(), nullptr); }
  ~Sha256() { EVP_MD_CTX_free(context_); }
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void add(const void* data, size_t size) { EVP_DigestUpdate(context_, data, size); }
  std::array<unsigned char, kDigestBytes> finish() {
    std::array<unsigned char, kDigestBytes> digest{};
    unsigned int length = 0;
    EVP_DigestFinal_ex(context_, digest.data(), &length);
    return digest;
  }

 private:
  EVP_MD_CTX* context_;
};

// The arrays, read straight into the film, and the SHA-256 of every byte
// before the last 32 compared with those 32.
SpectralHistogram readRawArrays(const InputFile& in, const StatePrefix& prefix, const StateHeader& h) {
  const FilmFingerprint& f = h.fingerprint;
  SpectralHistogram film(f.pixelsX, f.pixelsY, f.bins, f.exactColour, f.weightUnits);
  film.countedBeams = h.countedBeams;
  Sha256 digest;
  digest.add(prefix.bytes.data(), prefix.bytes.size());
  digest.add(h.text.data(), h.text.size());
  uint64_t offset = kPrefixBytes + h.text.size();
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) {
    std::vector<uint64_t>& words = film.channel(c);
    // Little-endian on every machine we build for (x86-64, arm64).
    in.readAt(offset, words.data(), words.size() * sizeof(uint64_t));
    digest.add(words.data(), words.size() * sizeof(uint64_t));
    offset += words.size() * sizeof(uint64_t);
  }
  std::array<unsigned char, kDigestBytes> stored{};
  in.readAt(offset, stored.data(), stored.size());
  if (digest.finish() != stored)
    throw in.fail("checksum mismatch: the SHA-256 in its last 32 bytes is not that of the bytes before; the file is "
                  "corrupted");
  return film;
}

// Version 4: the SHA-256 of the prefix, the header and the compressed stream
// (read in pieces) against the last 32 bytes, before anything is inflated,
// so the decompressor only ever sees the bytes the writer wrote.
void checkDigest(const InputFile& in, const StatePrefix& prefix, const StateHeader& h) {
  Sha256 digest;
  digest.add(prefix.bytes.data(), prefix.bytes.size());
  digest.add(h.text.data(), h.text.size());
  std::vector<unsigned char> piece(std::min<uint64_t>(h.compressedBytes, kReadPieceBytes));
  const uint64_t start = kPrefixBytes + h.text.size();
  for (uint64_t done = 0; done < h.compressedBytes;) {
    const size_t size = size_t(std::min<uint64_t>(h.compressedBytes - done, piece.size()));
    in.readAt(start + done, piece.data(), size);
    digest.add(piece.data(), size);
    done += size;
  }
  std::array<unsigned char, kDigestBytes> stored{};
  in.readAt(start + h.compressedBytes, stored.data(), stored.size());
  if (digest.finish() != stored)
    throw in.fail("checksum mismatch: the SHA-256 in its last 32 bytes is not that of the bytes before; the file is "
                  "corrupted");
}

// The version 4 body: one zstd stream, read from the file in pieces and
// inflated straight into each part's place (the bundle's texts, the film's
// arrays), so a big film is never held twice. A stream that is corrupt,
// ends before the bytes the header declares or holds more is refused,
// naming the file and the part.
class BodyInflater {
 public:
  BodyInflater(const InputFile& in, uint64_t offset, uint64_t bytes)
      : in_(in), next_(offset), end_(offset + bytes), context_(ZSTD_createDCtx()) {
    if (!context_) throw in_.fail("cannot start zstd decompression (out of memory)");
  }
  ~BodyInflater() { ZSTD_freeDCtx(context_); }
  BodyInflater(const BodyInflater&) = delete;
  BodyInflater& operator=(const BodyInflater&) = delete;

  // `out` (a std::string or std::vector<uint64_t>) holds the stream's next
  // `bytes` bytes; it grows as they come, so memory follows the stream.
  template <class Container>
  void fill(Container& out, uint64_t bytes, const std::string& part) {
    using Element = typename Container::value_type;
    out.clear();
    try {
      out.reserve(size_t(bytes / sizeof(Element)));
    } catch (const std::exception&) {  // bad_alloc, length_error
      throw in_.fail(fmt::format("{} of {} bytes does not fit in memory", part, bytes));
    }
    for (uint64_t done = 0; done < bytes;) {
      const uint64_t step = std::min<uint64_t>(bytes - done, kInflateStepBytes);
      out.resize(size_t((done + step) / sizeof(Element)));
      inflateInto(reinterpret_cast<unsigned char*>(out.data()) + done, size_t(step), part);
      done += step;
    }
  }

  // Refuses a stream that holds more than the parts filled, whose frame is
  // cut short after them, or with bytes after its frame.
  void finish() {
    unsigned char extra = 0;
    while (lastResult_ != 0) {  // the frame has not ended
      const bool more = input_.pos < input_.size || refill();
      ZSTD_outBuffer output{&extra, 1, 0};
      decompress(output, "the end of the stream");
      if (output.pos != 0)
        throw in_.fail("the compressed stream inflates past the bytes its header declares (the bundle and 8 x the "
                       "arrays' lengths)");
      if (!more && lastResult_ != 0)
        throw in_.fail("the compressed stream ends before its zstd frame does; it is truncated");
    }
    if (input_.pos != input_.size || next_ != end_)
      throw in_.fail("the compressed stream has bytes after its zstd frame");
  }

 private:
  static constexpr uint64_t kInflateStepBytes = uint64_t(16) << 20;  // a multiple of 8: whole words a step

  void inflateInto(unsigned char* out, size_t bytes, const std::string& part) {
    ZSTD_outBuffer output{out, bytes, 0};
    while (output.pos < output.size) {
      if (input_.pos == input_.size) refill();
      const size_t produced = output.pos, consumed = input_.pos;
      decompress(output, part);
      if (output.pos == produced && input_.pos == consumed)
        throw in_.fail(fmt::format("the compressed stream ends within {}, before the bytes its header declares; it "
                                   "is truncated",
                                   part));
    }
  }

  void decompress(ZSTD_outBuffer& output, const std::string& part) {
    lastResult_ = ZSTD_decompressStream(context_, &output, &input_);
    if (ZSTD_isError(lastResult_))
      throw in_.fail(fmt::format("the compressed stream is corrupt within {}: {}", part,
                                 ZSTD_getErrorName(lastResult_)));
  }

  // The next piece of the compressed bytes; false after the last.
  bool refill() {
    if (next_ == end_) return false;
    piece_.resize(size_t(std::min<uint64_t>(end_ - next_, kReadPieceBytes)));
    in_.readAt(next_, piece_.data(), piece_.size());
    next_ += piece_.size();
    input_ = {piece_.data(), piece_.size(), 0};
    return true;
  }

  const InputFile& in_;
  uint64_t next_, end_;  // the compressed bytes not yet read
  ZSTD_DCtx* context_;
  std::vector<unsigned char> piece_;
  ZSTD_inBuffer input_{nullptr, 0, 0};
  size_t lastResult_ = 1;  // ZSTD_decompressStream's last: 0 when a frame has ended
};

// The bundle and the film, inflated from the version 4 body in the order
// the header lists them.
void readCompressedBody(const InputFile& in, const StateHeader& h, FilmState& state) {
  BodyInflater body(in, kPrefixBytes + h.text.size(), h.compressedBytes);
  if (h.bundle) {
    SceneBundle bundle;
    body.fill(bundle.sceneText, h.bundle->sceneBytes, "the bundled scene");
    for (const auto& [path, bytes] : h.bundle->files)
      body.fill(bundle.files[path], bytes, "the bundled file " + path);
    state.bundle = std::move(bundle);
  }
  const FilmFingerprint& f = h.fingerprint;
  SpectralHistogram& film = state.histogram;
  film.pixelsX = f.pixelsX;
  film.pixelsY = f.pixelsY;
  film.bins = f.bins;
  film.unitsPerBeam = f.weightUnits;
  film.countedBeams = h.countedBeams;
  // Little-endian on every machine we build for (x86-64, arm64).
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c)
    body.fill(film.channel(c), h.lengths[c] * sizeof(uint64_t), std::string("/") + filmChannelName(c));
  body.finish();
}

}  // namespace

uint64_t FilmState::beams() const {
  uint64_t total = 0;
  for (const BeamRange& r : ranges) total += r.count;
  return total;
}

FilmFingerprint fingerprintOf(const FilmLayout& film, const std::string& sceneFile, const std::string& sceneSha256,
                              const std::string& observer, uint64_t seed, uint32_t specialisation,
                              const std::map<std::string, bool>& compileOptions) {
  FilmFingerprint f;
  f.sceneFile = sceneFile;
  f.sceneSha256 = sceneSha256;
  f.observer = observer;
  f.lambdaMinNm = film.lambdaMinNm;
  f.lambdaMaxNm = film.lambdaMaxNm;
  f.bins = film.bins;
  f.pixelsX = film.pixelsX;
  f.pixelsY = film.pixelsY;
  f.window = film.window;
  f.firstStoredBin = film.firstStoredBin;
  f.storedBins = film.storedBins;
  f.exactColour = film.exactColour;
  f.colourFromBins = film.colourFromBins;
  f.weightUnits = film.weightUnits;
  f.seed = seed;
  f.specialisation = specialisation;
  f.compileOptions = compileOptions;
  return f;
}

void writeFilmState(const std::filesystem::path& file, const FilmState& state) {
  if (!std::isfinite(state.irradiancePerCount) || state.irradiancePerCount < 0.0)
    throw FilmStateError(fmt::format("{}: irradiance_per_count {} is not a finite number >= 0", file.string(),
                                     state.irradiancePerCount));
  const std::vector<unsigned char> body = compressedBody(state);
  std::string text = headerOf(state, body.size()).dump();
  text.append((8 - (kPrefixBytes + text.size()) % 8) % 8, ' ');  // the body starts 8-byte aligned

  std::vector<unsigned char> head(std::begin(kMagic), std::end(kMagic));
  const uint32_t prefix[2] = {kVersion, uint32_t(text.size())};
  head.insert(head.end(), reinterpret_cast<const unsigned char*>(prefix),
              reinterpret_cast<const unsigned char*>(prefix) + sizeof prefix);
  head.insert(head.end(), text.begin(), text.end());
  Sha256 digest;
  digest.add(head.data(), head.size());
  digest.add(body.data(), body.size());
  const auto sum = digest.finish();

  try {
    io_detail::AtomicFile out(file, "state");
    int err = io_detail::pwriteAll(out.fd(), head.data(), head.size(), 0);
    if (!err) err = io_detail::pwriteAll(out.fd(), body.data(), body.size(), head.size());
    if (!err) err = io_detail::pwriteAll(out.fd(), sum.data(), sum.size(), head.size() + body.size());
    if (err) out.fail("write: " + io_detail::errnoText(err));
    out.commit();
  } catch (const std::exception& e) {
    throw FilmStateError(e.what());
  }
}

FilmState readFilmState(const std::filesystem::path& file) {
  try {
    const InputFile in(file, "state file");
    const jf::Source source = sourceOf(file);
    const StatePrefix prefix = readPrefix(in);
    StateHeader header = readHeader(in, source, prefix);
    const uint64_t beams = checkRanges(source, header.ranges);
    checkCountedBeams(source, header, beams);
    checkLengths(source, header);
    checkFileSize(in, source, header);
    FilmState state;
    if (header.compressed()) {
      checkDigest(in, prefix, header);
      readCompressedBody(in, header, state);
      state.irradiancePerCount = header.irradiancePerCount;
    } else {
      state.histogram = readRawArrays(in, prefix, header);
    }
    state.fingerprint = std::move(header.fingerprint);
    state.ranges = sortedRanges(std::move(header.ranges));
    return state;
  } catch (const InputFileError& e) {
    throw FilmStateError(e.what());
  }
}

std::string fingerprintText(const FilmFingerprint& fingerprint) { return toJson(fingerprint).dump(); }

FilmFingerprint fingerprintOfText(const std::string& text) {
  jf::Source source;
  source.file = "a film fingerprint";
  source.raise = raiseStateError;
  const json root = jf::parseJson(source, text);
  if (!root.is_object()) source.fail("", fmt::format("must be an object (got {})", jf::describe(root)));
  return fingerprintFromJson(HeaderFields{source, root, ""}, kVersion);
}

std::string fingerprintDifference(const FilmFingerprint& a, const FilmFingerprint& b) {
  const json fa = toJson(a), fb = toJson(b);
  for (auto it = fa.begin(); it != fa.end(); ++it) {
    if (it.key() == "scene_file") continue;  // the same scene may be named by two paths; its hash decides
    const json& other = fb.at(it.key());
    if (it.value().is_object() && other.is_object()) {  // compile_options: name the option
      for (const json* side : {&it.value(), &other})
        for (auto option = side->begin(); option != side->end(); ++option)
          if (it.value().value(option.key(), json()) != other.value(option.key(), json()))
            return fmt::format("{}/{}: {} against {}", it.key(), option.key(),
                               it.value().value(option.key(), json()).dump(), other.value(option.key(), json()).dump());
      continue;
    }
    if (other != it.value()) return fmt::format("{}: {} against {}", it.key(), it.value().dump(), other.dump());
  }
  return "";
}

std::string mergeRefusal(const FilmState& a, const FilmState& b) {
  if (std::string field = fingerprintDifference(a.fingerprint, b.fingerprint); !field.empty())
    return "they differ in " + field;
  if (std::string shared = overlap(a.ranges, b.ranges); !shared.empty()) return shared;
  if (!beamsOf(b.ranges, a.beams()))
    return fmt::format("/ranges: {} + {} beams pass 2^64 - 1, the most a state counts", a.beams(), b.beams());
  return "";
}

FilmState mergeStates(const FilmState& a, const FilmState& b) {
  if (std::string why = mergeRefusal(a, b); !why.empty()) throw FilmStateError(why);
  FilmState out = a;
  try {
    out.histogram.merge(b.histogram);
  } catch (const CounterOverflow& e) {
    throw FilmStateError(e.what());
  }
  out.ranges.insert(out.ranges.end(), b.ranges.begin(), b.ranges.end());
  // An empty range (a render stopped before its first beam) says nothing
  // beside others, and a reader refuses it there.
  std::erase_if(out.ranges, [](const BeamRange& r) { return r.count == 0; });
  out.ranges = sortedRanges(std::move(out.ranges));
  // Equal fingerprints mean equal scene and file digests, so any bundle
  // serves the merge; a state from before bundles (version 3) takes one
  // from the state it merges with, with the scene path its keys resolve from.
  if (!out.bundle && b.bundle) {
    out.bundle = b.bundle;
    out.fingerprint.sceneFile = b.fingerprint.sceneFile;
  }
  out.irradiancePerCount = 0.0;
  return out;
}

FilmState mergeStateFiles(const std::vector<std::filesystem::path>& files) {
  FilmState merged = readFilmState(files.at(0));
  std::string before = files[0].string();
  for (size_t i = 1; i < files.size(); ++i) {
    const FilmState next = readFilmState(files[i]);
    try {
      merged = mergeStates(merged, next);
    } catch (const FilmStateError& e) {
      throw FilmStateError(fmt::format("cannot merge {} with {}: {}", files[i].string(), before, e.what()));
    }
    before += ", " + files[i].string();
  }
  return merged;
}

}  // namespace spectrace
