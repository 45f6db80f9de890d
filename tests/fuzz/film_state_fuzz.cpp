// libFuzzer target: render-state files (readFilmState). The input is the
// file without its magic and trailing SHA-256 (version, header length,
// JSON header, arrays or compressed body); the target adds both, so the
// fuzzer reaches the header and body instead of failing the checksum. Bad input must end in
// FilmStateError; an accepted state must be self-consistent.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <openssl/evp.h>

#include "film/film_state.h"
#include "fuzz_support.h"

using namespace spectrace;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<uint8_t> bytes = {'S', 'P', 'C', 'T', 'R', 'S', 'T', 'A'};
  bytes.insert(bytes.end(), data, data + size);
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_Digest(bytes.data(), bytes.size(), digest, &length, EVP_sha256(), nullptr);
  bytes.insert(bytes.end(), digest, digest + length);
  const auto file = fuzz::scratchDir() / "state.bin";
  fuzz::writeBytes(file, bytes.data(), bytes.size());
  try {
    const FilmState state = readFilmState(file);
    const SpectralHistogram& h = state.histogram;
    fuzz::require(h.counts().size() == size_t(h.pixelsX) * h.pixelsY * h.bins * h.counterWords(), "counts do not match the film's shape");
    fuzz::require(fingerprintDifference(state.fingerprint, state.fingerprint).empty(), "a fingerprint differs from itself");
    (void)state.beams();
    (void)mergeRefusal(state, state);
  } catch (const FilmStateError&) {
  }
  return 0;
}
