// Writes a seed for film_state_fuzz: a small valid render-state file
// without its magic and SHA-256 (the form the target takes), so no binary
// corpus is committed. Usage: make_state_seed OUT_FILE
#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

#include "film/film_state.h"

using namespace spectrace;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_state_seed OUT_FILE\n");
    return 2;
  }
  FilmState state;
  FilmFingerprint& f = state.fingerprint;
  f.sceneFile = "scene.json";
  f.sceneSha256 = std::string(64, '0');
  f.observer = "CIE1931_2";
  f.lambdaMinNm = 360.0;
  f.lambdaMaxNm = 830.0;
  f.bins = 4;
  f.pixelsX = 3;
  f.pixelsY = 2;
  f.window = {0, 0, 3, 2};
  f.storedBins = 4;
  f.weightUnits = spectrace::device::kWeightUnitsFractional;
  state.ranges = {{0, 10}, {20, 5}};
  state.histogram = SpectralHistogram(f.pixelsX, f.pixelsY, f.bins, f.exactColour, f.weightUnits);
  for (size_t i = 0; i < state.histogram.counts().size(); ++i) state.histogram.counts()[i] = i * 7;
  // A bundle and a scale, so the fuzzer starts from every part of the format.
  state.bundle = SceneBundle{"{\"lights\": []}", {{"a.csv", "wavelength_nm,value\n380,1\n"}, {"m.obj", "v 0 0 0\n"}}};
  state.irradiancePerCount = 1.5e-9;
  const std::filesystem::path full = std::string(argv[1]) + ".full";
  writeFilmState(full, state);
  std::ifstream in(full, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::filesystem::remove(full);
  if (bytes.size() < 8 + 32) return 1;
  std::ofstream out(argv[1], std::ios::binary);
  out.write(bytes.data() + 8, std::streamsize(bytes.size() - 8 - 32));
  return out ? 0 : 1;
}
