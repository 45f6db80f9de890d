#pragma once
// A render's progress on stderr, and the notices printed while it runs.
// On a terminal: one line rewritten in place (percent, beams, rate, elapsed,
// ETA), cleared before each notice so a notice gets a line of its own. Off
// a terminal (a log file): the same fields as plain lines, at most one per
// `plainIntervalSeconds` and one at the end, so a log never holds '\r'.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>

namespace spectrace::cli {

// "42.0%, 1048576 of 2500000 beams, 3.1 Mbeam/s, 0:12 elapsed, ETA 0:17":
// the rate is of the beams traced since `firstDone` (a resumed render's
// earlier beams are not this run's work), the ETA at that rate.
std::string progressFields(uint64_t done, uint64_t total, uint64_t firstDone, double elapsedSeconds);
// "0:07", "12:30", "3:02:15", "4d 3:02:15".
std::string clockDuration(double seconds);

class ProgressLine {
 public:
  static constexpr double kPlainIntervalSeconds = 10.0;

  // `prefix` begins every progress line ("", "[2/5] lamp.json: ", "rank 0: ").
  ProgressLine(std::FILE* out, bool live, double plainIntervalSeconds = kPlainIntervalSeconds);
  // Live when stderr is a terminal.
  static ProgressLine forStderr();

  // A render of `total` beams starts, `firstDone` of them already done.
  void start(uint64_t total, uint64_t firstDone, std::string prefix = {});
  void update(uint64_t done) { update(done, secondsSinceStart()); }
  void update(uint64_t done, double elapsedSeconds);  // the clock given, for tests
  // A line of its own ("spectrace: " is added); the progress line, when
  // live, is redrawn below it.
  void notice(const std::string& line);
  // Ends the live line (nothing off a terminal).
  void finish();
  bool live() const { return live_; }

 private:
  double secondsSinceStart() const;
  void clearLive();

  std::FILE* out_;
  bool live_;
  double plainInterval_;
  std::string prefix_;
  uint64_t total_ = 0, firstDone_ = 0;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  double lastPlain_ = 0.0;  // when the last plain line was written (the start: none yet)
  std::string shown_;         // the live line on screen, "" when none
};

}  // namespace spectrace::cli
