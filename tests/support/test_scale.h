#pragma once
// The scale of the Monte Carlo tests: one factor s in (0, 1] from the
// environment variable SPECTRACE_TEST_SCALE, default 1 (the full scale, what
// `ctest` in a Release build runs). A sanitizer build makes its default
// smaller (SPECTRACE_DEFAULT_TEST_SCALE, compiled into each test binary from
// CMake's SPECTRACE_TEST_SCALE), so every code path still runs under ASan
// and UBSan at a cost they can afford.
//
// A test scales its beam count with scaledBeams() and, where its tolerance
// is a fixed number chosen to stand k standard errors above the noise of
// the full count, scales that tolerance with ScaledBeams::tolerance(): a
// mean over n beams has a standard error proportional to 1 / sqrt(n), so
// the same k holds at every scale. Tolerances computed from the measured
// variance (5 sigma of the counts, chi-square p-values) need nothing: they
// follow the beam count by themselves. At s = 1 both functions return
// their argument, so no test is weaker at full scale.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace spectrace::testing {

#ifndef SPECTRACE_DEFAULT_TEST_SCALE
#define SPECTRACE_DEFAULT_TEST_SCALE 1
#endif

// s, read once; a value that is not a number in (0, 1] stops the test binary.
inline double testScale() {
  static const double scale = [] {
    const char* text = std::getenv("SPECTRACE_TEST_SCALE");
    if (text == nullptr || *text == '\0') return double(SPECTRACE_DEFAULT_TEST_SCALE);
    char* end = nullptr;
    const double s = std::strtod(text, &end);
    if (end == text || *end != '\0' || !(s > 0.0 && s <= 1.0)) {
      std::fprintf(stderr, "SPECTRACE_TEST_SCALE=%s: must be a number in (0, 1]\n", text);
      std::abort();
    }
    return s;
  }();
  return scale;
}

struct ScaledBeams {
  uint64_t full = 0;   // the count at full scale
  uint64_t beams = 0;  // the count at this scale
  // A tolerance that stands k standard errors above the noise of a mean
  // over `full` beams, at the same k for `beams`.
  double tolerance(double atFullScale) const { return atFullScale * std::sqrt(double(full) / double(beams)); }
  operator uint64_t() const { return beams; }
};

// `full` beams at this scale: rounded, never below `minimum` (a test whose
// statistics need some least count says so) nor above `full`.
inline ScaledBeams scaledBeams(uint64_t full, uint64_t minimum = 10'000) {
  ScaledBeams scaled;
  scaled.full = full;
  const double s = testScale();
  uint64_t beams = s >= 1.0 ? full : uint64_t(std::llround(double(full) * s));
  if (beams < minimum) beams = minimum;
  if (beams > full) beams = full;
  scaled.beams = beams;
  return scaled;
}

}  // namespace spectrace::testing
