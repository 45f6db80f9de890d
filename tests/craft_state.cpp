// craft_state IN OUT [ranges=FIRST:COUNT,...] [counted_beams=N] [counts_wrapping=OTHER] [drop_bundle]
// Writes OUT as the render state IN with the given header fields, signed by
// writeFilmState, so the CLI tests can hand spectrace states that pass the
// checksum but are wrong in one field. counts_wrapping: each count c > 0 of
// the state OTHER becomes 2^64 - c here, and every other count 0, so that a
// merge with OTHER sums every count to exactly 2^64, which wraps to 0.
// drop_bundle: the state without its scene bundle, as states were before
// they carried one (it develops from the scene file it names).
#include <charconv>
#include <cstdio>
#include <string>
#include <string_view>

#include "film/film_state.h"

using namespace spectrace;

namespace {

uint64_t numberOf(std::string_view text) {
  uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size())
    throw std::invalid_argument("not a number: " + std::string(text));
  return value;
}

std::vector<BeamRange> rangesOf(std::string_view text) {
  std::vector<BeamRange> ranges;
  while (!text.empty()) {
    const std::string_view range = text.substr(0, text.find(','));
    const size_t colon = range.find(':');
    if (colon == std::string_view::npos) throw std::invalid_argument("not FIRST:COUNT: " + std::string(range));
    ranges.push_back({numberOf(range.substr(0, colon)), numberOf(range.substr(colon + 1))});
    text.remove_prefix(std::min(text.size(), range.size() + 1));
  }
  return ranges;
}

std::vector<uint64_t> wrapping(const FilmState& state, const FilmState& other) {
  if (!other.histogram.sameShape(state.histogram)) throw std::invalid_argument("counts_wrapping: another film");
  std::vector<uint64_t> counts = other.histogram.counts();
  for (uint64_t& c : counts) c = c ? 0 - c : 0;  // 2^64 - c
  return counts;
}

void apply(FilmState& state, std::string_view edit) {
  const size_t eq = edit.find('=');
  const std::string_view key = edit.substr(0, eq), value = eq == edit.npos ? "" : edit.substr(eq + 1);
  if (key == "ranges") state.ranges = rangesOf(value);
  else if (key == "counted_beams") state.histogram.countedBeams = numberOf(value);
  else if (key == "counts_wrapping") state.histogram.counts() = wrapping(state, readFilmState(std::string(value)));
  else if (key == "drop_bundle") state.bundle.reset();
  else throw std::invalid_argument("unknown edit: " + std::string(edit));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: craft_state IN OUT [ranges=FIRST:COUNT,...] [counted_beams=N] [counts_wrapping=OTHER] "
                 "[drop_bundle]\n");
    return 2;
  }
  try {
    FilmState state = readFilmState(argv[1]);
    for (int i = 3; i < argc; ++i) apply(state, argv[i]);
    writeFilmState(argv[2], state);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "craft_state: %s\n", e.what());
    return 1;
  }
  return 0;
}
