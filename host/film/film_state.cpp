#include "film/film_state.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <openssl/evp.h>

#include "io/atomic_file.h"
#include "json/input_file.h"
#include "json/json_fields.h"

namespace spectrace {
namespace {

using nlohmann::json;

constexpr char kMagic[8] = {'S', 'P', 'C', 'T', 'R', 'S', 'T', 'A'};
// 3: weighted films in two-word counters (kWeightUnitsFractional, 2^63);
// 2: the fingerprint's compile_options object; 1: four of the options as
// fields of their own. 1 and 2 are still read, except their weighted films
// (2^24 units in one word), which are refused by name.
constexpr uint32_t kVersion = 3;
constexpr size_t kPrefixBytes = 16;  // magic, version, header length
constexpr size_t kDigestBytes = 32;  // SHA-256

std::array<unsigned char, kDigestBytes> sha256(const unsigned char* data, size_t size) {
  std::array<unsigned char, kDigestBytes> digest{};
  unsigned int length = 0;
  EVP_Digest(data, size, digest.data(), &length, EVP_sha256(), nullptr);
  return digest;
}

json toJson(const FilmFingerprint& f) {
  return {{"scene_file", f.sceneFile},
          {"scene_sha256", f.sceneSha256},
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
          {"compile_options", f.compileOptions}};
}

FilmFingerprint fingerprintFromJson(const json& j, uint32_t version) {
  FilmFingerprint f;
  f.sceneFile = j.at("scene_file").get<std::string>();
  f.sceneSha256 = j.at("scene_sha256").get<std::string>();
  f.observer = j.at("observer").get<std::string>();
  f.lambdaMinNm = j.at("spectrum_min_nm").get<double>();
  f.lambdaMaxNm = j.at("spectrum_max_nm").get<double>();
  f.bins = j.at("bins").get<uint32_t>();
  f.pixelsX = j.at("pixels_x").get<uint32_t>();
  f.pixelsY = j.at("pixels_y").get<uint32_t>();
  const auto& w = j.at("window");
  f.window = {w.at(0).get<uint32_t>(), w.at(1).get<uint32_t>(), w.at(2).get<uint32_t>(), w.at(3).get<uint32_t>()};
  f.firstStoredBin = j.at("first_stored_bin").get<uint32_t>();
  f.storedBins = j.at("stored_bins").get<uint32_t>();
  f.exactColour = j.at("exact_colour").get<bool>();
  f.colourFromBins = j.value("colour_from_bins", false);
  f.weightUnits = j.at("weight_units").get<uint64_t>();
  f.seed = j.at("seed").get<uint64_t>();
  f.specialisation = j.at("specialisation").get<uint32_t>();
  if (version >= 2) {
    for (const auto& [name, value] : j.at("compile_options").items()) f.compileOptions[name] = value.get<bool>();
  } else {
    // Version 1 recorded four options and the film's colour; the other two
    // options it did not record are taken at their defaults (a version 1
    // state of a --no-connect render is refused on resume by its weight
    // units, not silently mixed).
    f.compileOptions["aim"] = j.at("aimed").get<bool>();
    f.compileOptions["skip_unreachable_lights"] = j.at("skip_unreachable_lights").get<bool>();
    f.compileOptions["trim_spectrum"] = j.at("trim_spectrum").get<bool>();
    f.compileOptions["trim_pixels"] = j.at("trim_pixels").get<bool>();
    f.compileOptions["exact_colour"] = f.exactColour || f.colourFromBins;
    f.compileOptions["colour_from_bins"] = f.colourFromBins;
    f.compileOptions["connect"] = true;
    f.compileOptions["brute_force_objects"] = false;
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

void appendWords(std::vector<unsigned char>& out, const std::vector<uint64_t>& words) {
  const size_t at = out.size();
  out.resize(at + words.size() * sizeof(uint64_t));
  // Little-endian on every machine we build for (x86-64, arm64).
  if (!words.empty()) std::memcpy(out.data() + at, words.data(), words.size() * sizeof(uint64_t));
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
  const SpectralHistogram& h = state.histogram;
  json header = {{"fingerprint", toJson(state.fingerprint)},
                 {"ranges", json::array()},
                 {"counted_beams", h.countedBeams},
                 {"units_per_beam", h.unitsPerBeam}};
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) header[filmChannelName(c)] = h.channel(c).size();
  for (const BeamRange& r : state.ranges) header["ranges"].push_back({r.first, r.count});
  std::string text = header.dump();
  text.append((8 - (kPrefixBytes + text.size()) % 8) % 8, ' ');  // the arrays start 8-byte aligned

  std::vector<unsigned char> bytes(std::begin(kMagic), std::end(kMagic));
  const uint32_t prefix[2] = {kVersion, uint32_t(text.size())};
  bytes.insert(bytes.end(), reinterpret_cast<const unsigned char*>(prefix),
               reinterpret_cast<const unsigned char*>(prefix) + sizeof prefix);
  bytes.insert(bytes.end(), text.begin(), text.end());
  for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) appendWords(bytes, h.channel(c));
  const auto digest = sha256(bytes.data(), bytes.size());
  bytes.insert(bytes.end(), digest.begin(), digest.end());

  try {
    io_detail::AtomicFile out(file, "state");
    if (int err = io_detail::pwriteAll(out.fd(), bytes.data(), bytes.size(), 0))
      out.fail("write: " + io_detail::errnoText(err));
    out.commit();
  } catch (const std::exception& e) {
    throw FilmStateError(e.what());
  }
}

FilmState readFilmState(const std::filesystem::path& file) {
  auto fail = [&](const std::string& what) -> FilmStateError {
    return FilmStateError(fmt::format("{}: {}", file.string(), what));
  };
  std::string text;
  try {
    // A state holds the whole film, so no size bound but the film's; a
    // device node or pipe is still refused before it is read.
    text = readInputFile(file, "state file", UINT64_MAX);
  } catch (const InputFileError& e) {
    throw FilmStateError(e.what());
  }
  const std::basic_string_view<unsigned char> bytes(reinterpret_cast<const unsigned char*>(text.data()), text.size());
  if (bytes.size() < kPrefixBytes + kDigestBytes || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw fail("not a spectrace state file (no SPCTRSTA magic)");
  const size_t body = bytes.size() - kDigestBytes;
  if (sha256(bytes.data(), body) != *reinterpret_cast<const std::array<unsigned char, kDigestBytes>*>(bytes.data() + body))
    throw fail("checksum mismatch: the file is truncated or corrupted");
  uint32_t prefix[2];
  std::memcpy(prefix, bytes.data() + sizeof kMagic, sizeof prefix);
  if (prefix[0] < 1 || prefix[0] > kVersion)
    throw fail(fmt::format("format version {} (this spectrace reads 1 to {})", prefix[0], kVersion));
  if (kPrefixBytes + size_t(prefix[1]) > body) throw fail("the header runs past the end of the file");
  FilmState state;
  size_t offset = kPrefixBytes + prefix[1];
  try {
    // The header is a few fields deep; a deeper one is not ours (and would cost memory).
    const json header = json::parse(bytes.begin() + kPrefixBytes, bytes.begin() + long(offset),
                                    [&fail](int depth, json::parse_event_t, json&) {
                                      if (depth > json_fields::kMaxJsonDepth) throw fail("bad header: it nests too deep");
                                      return true;
                                    });
    state.fingerprint = fingerprintFromJson(header.at("fingerprint"), prefix[0]);
    if (const uint64_t units = state.fingerprint.weightUnits; units != 1 && units != device::kWeightUnitsFractional)
      throw fail(fmt::format(
          "/fingerprint/weight_units: {} {}", units,
          prefix[0] < 3 ? "is a weighted film of an older spectrace (one-word counters), which this one cannot merge "
                          "or resume: render it again"
                        : fmt::format("is neither 1 nor {} (2^63)", device::kWeightUnitsFractional)));
    for (const auto& r : header.at("ranges")) state.ranges.push_back({r.at(0).get<uint64_t>(), r.at(1).get<uint64_t>()});
    const FilmFingerprint& f = state.fingerprint;
    // The header's film shape sizes the arrays: checked against the bytes
    // that follow before anything is allocated, so a header cannot ask for
    // more memory than its file holds.
    const uint64_t pixels = uint64_t(f.pixelsX) * f.pixelsY;
    const uint64_t wordsPerPixel =
        device::countersPerPixelOf(f.bins, device::filmChannelSetOf(f.exactColour, f.weightUnits != 1));
    if (wordsPerPixel != 0 && pixels > (body - offset) / sizeof(uint64_t) / wordsPerPixel)
      throw fail(fmt::format("its film ({} x {} pixels, {} bins) needs more values than the file holds", f.pixelsX,
                             f.pixelsY, f.bins));
    SpectralHistogram& h = state.histogram;
    h = SpectralHistogram(f.pixelsX, f.pixelsY, f.bins, f.exactColour, f.weightUnits);
    h.countedBeams = header.at("counted_beams").get<uint64_t>();
    for (uint32_t c = 0; c < device::kFilmChannelCount; ++c) {
      const char* key = filmChannelName(c);
      std::vector<uint64_t>* words = &h.channel(c);
      const size_t n = header.at(key).get<size_t>();
      if (n != words->size())
        throw fail(fmt::format("{} holds {} values where its film has {}", key, n, words->size()));
      if (n * sizeof(uint64_t) > body - offset) throw fail(fmt::format("{} runs past the end of the file", key));
      if (n) std::memcpy(words->data(), bytes.data() + offset, n * sizeof(uint64_t));
      offset += n * sizeof(uint64_t);
    }
  } catch (const json::exception& e) {
    throw fail(fmt::format("bad header: {}", e.what()));
  }
  if (offset != body) throw fail("unexpected bytes after the arrays");
  return state;
}

std::string fingerprintText(const FilmFingerprint& fingerprint) { return toJson(fingerprint).dump(); }

FilmFingerprint fingerprintOfText(const std::string& text) {
  try {
    return fingerprintFromJson(json::parse(text), kVersion);
  } catch (const json::exception& e) {
    throw FilmStateError(fmt::format("not a film fingerprint: {}", e.what()));
  }
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
