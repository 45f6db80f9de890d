#pragma once
// The exact render state: a film's integer counters with the fingerprint of
// what was traced, so partial renders merge exactly and an interrupted
// render resumes bit-identically. The file format is docs/state-format.md:
// a magic, a version, a JSON header (the fingerprint, the beam ranges, the
// arrays' and the bundle's lengths), one zstd stream of the scene bundle and
// the uint64 arrays, and a SHA-256 of all before it.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "film/film_layout.h"
#include "film/spectral_histogram.h"

namespace spectrace {

// A state file that cannot be read or used: names the file and what is wrong.
struct FilmStateError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Beams [first, first + count) of the render's stream.
struct BeamRange {
  uint64_t first = 0;
  uint64_t count = 0;
  bool operator==(const BeamRange&) const = default;
};

// What was traced: two states merge only when every field matches.
struct FilmFingerprint {
  std::string sceneFile;     // as given, for messages and for developing a merge
  std::string sceneSha256;   // of the scene file's bytes
  // Of the files the scene names (Scene::referencedFilesSha256; empty when
  // none, as in states written before it).
  std::string referencedFilesSha256;
  std::string observer;
  double lambdaMinNm = 0.0, lambdaMaxNm = 0.0;
  uint32_t bins = 0;
  uint32_t pixelsX = 0, pixelsY = 0;
  PixelWindow window;
  uint32_t firstStoredBin = 0, storedBins = 0;
  bool exactColour = true;
  bool colourFromBins = false;  // exact colour developed from the bins (FilmLayout)
  uint64_t weightUnits = 1;
  uint64_t seed = 0;
  uint32_t specialisation = 0;  // SpecialisedFeature bits of the trace pipeline
  // Every option the scene was compiled with, by name
  // (compile/compile_scene.h, namedCompileOptions), so a merge or resume
  // compiles it the same way and no option can be left out.
  std::map<std::string, bool> compileOptions;
  // The wavelengths each beam and camera path carried (1 in states written
  // before them).
  uint32_t wavelengthsPerBeam = 1;
};

// What developing or merging a state needs besides its film, carried in the
// state so it needs no other file: the scene's exact bytes (those whose
// SHA-256 is the fingerprint's scene_sha256) and the bytes of every file the
// scene names (CSV spectra and reflectances, OBJ meshes), keyed by the path
// the scene loader resolved for it (relative paths stay relative: the same
// key comes back when the text is parsed again under the fingerprint's
// sceneFile in another working folder).
struct SceneBundle {
  std::string sceneText;
  std::map<std::string, std::string> files;
  bool operator==(const SceneBundle&) const = default;
};

struct FilmState {
  FilmFingerprint fingerprint;
  std::vector<BeamRange> ranges;  // sorted, disjoint, none past 2^64, at most 2^64 - 1 beams in all
  SpectralHistogram histogram;    // the whole sensor and spectrum
  // None in states written before version 4 (they develop from the scene
  // file the fingerprint names) or written without one.
  std::optional<SceneBundle> bundle;
  // W/m^2 per bin carried by one count (CompiledScene::irradiancePerCount
  // of beams()), so a reader gets physical units from the state alone; 0
  // when unknown (states before version 4) or when the state holds no beams.
  double irradiancePerCount = 0.0;

  uint64_t beams() const;  // the ranges' beams (readers and merges refuse a sum past 2^64 - 1)
};

// The fingerprint of a film traced with `seed` from a scene file.
FilmFingerprint fingerprintOf(const FilmLayout& film, const std::string& sceneFile, const std::string& sceneSha256,
                              const std::string& observer, uint64_t seed, uint32_t specialisation,
                              const std::map<std::string, bool>& compileOptions);

// Writes atomically (temporary file, fsync, rename). Throws FilmStateError.
void writeFilmState(const std::filesystem::path& file, const FilmState& state);
// Reads and checks a state (docs/state-format.md, "What a reader checks"):
// the magic, version and header first, then the file's size against the
// one the header implies, and only then the arrays and the checksum (for
// version 4 the checksum first, then the bundle and arrays, decompressed
// straight into their places). Never returns half a state. Throws FilmStateError naming the file and the
// header field ("a.state: /ranges/2: ...").
FilmState readFilmState(const std::filesystem::path& file);

// The fingerprint as the JSON text of a state's header, and back (throws
// FilmStateError): how processes that share no file compare their films
// (render --mpi).
std::string fingerprintText(const FilmFingerprint& fingerprint);
FilmFingerprint fingerprintOfText(const std::string& text);

// The first field in which two fingerprints differ, as "<field>: <a> against
// <b>", or "" when they match (the scene file's path is not compared: its
// SHA-256 is).
std::string fingerprintDifference(const FilmFingerprint& a, const FilmFingerprint& b);
// Why `a` and `b` cannot be merged ("" when they can): the first fingerprint
// field that differs, the beams their ranges share, or more beams in all
// than 2^64 - 1.
std::string mergeRefusal(const FilmState& a, const FilmState& b);
// a + b, exactly. Throws FilmStateError with mergeRefusal's reason, or the
// counter whose sum would pass 2^64 - 1 (channel, pixel, bin). The bundle is
// the first one of a and b that has one, with that state's sceneFile (its
// keys resolve from it); irradiancePerCount is left 0, for the caller to
// compute from the compiled scene for the merged beams.
FilmState mergeStates(const FilmState& a, const FilmState& b);
// The states of `files` (at least one) read and merged in order. A refusal
// names the files: "cannot merge c.state with a.state, b.state: <why>".
FilmState mergeStateFiles(const std::vector<std::filesystem::path>& files);

}  // namespace spectrace
