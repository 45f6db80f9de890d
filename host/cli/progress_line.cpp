#include "cli/progress_line.h"

#include <cmath>
#include <fmt/format.h>
#include <unistd.h>

namespace spectrace::cli {

std::string clockDuration(double seconds) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds)) return "?";
  const uint64_t s = uint64_t(std::llround(std::min(seconds, 1e15)));
  const uint64_t days = s / 86400, hours = s / 3600 % 24, minutes = s / 60 % 60, secs = s % 60;
  if (days) return fmt::format("{}d {}:{:02}:{:02}", days, hours, minutes, secs);
  if (hours) return fmt::format("{}:{:02}:{:02}", hours, minutes, secs);
  return fmt::format("{}:{:02}", minutes, secs);
}

std::string progressFields(uint64_t done, uint64_t total, uint64_t firstDone, double elapsedSeconds) {
  const double percent = total ? 100.0 * double(done) / double(total) : 100.0;
  std::string text = fmt::format("{:5.1f}%, {} of {} beams", percent, done, total);
  const uint64_t thisRun = done > firstDone ? done - firstDone : 0;
  if (thisRun == 0 || !(elapsedSeconds > 0.0)) return text + fmt::format(", {} elapsed", clockDuration(elapsedSeconds));
  const double rate = double(thisRun) / elapsedSeconds;
  text += fmt::format(", {:.3g} Mbeam/s, {} elapsed", rate * 1e-6, clockDuration(elapsedSeconds));
  if (done < total) text += fmt::format(", ETA {}", clockDuration(double(total - done) / rate));
  return text;
}

ProgressLine::ProgressLine(std::FILE* out, bool live, double plainIntervalSeconds)
    : out_(out), live_(live), plainInterval_(plainIntervalSeconds) {}

ProgressLine ProgressLine::forStderr() { return ProgressLine(stderr, ::isatty(STDERR_FILENO) == 1); }

void ProgressLine::start(uint64_t total, uint64_t firstDone, std::string prefix) {
  clearLive();
  prefix_ = std::move(prefix);
  total_ = total;
  firstDone_ = firstDone;
  started_ = std::chrono::steady_clock::now();
  lastPlain_ = 0.0;
}

double ProgressLine::secondsSinceStart() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
}

void ProgressLine::update(uint64_t done, double elapsedSeconds) {
  const std::string line = "spectrace: " + prefix_ + progressFields(done, total_, firstDone_, elapsedSeconds);
  if (live_) {
    std::fprintf(out_, "\r\033[K%s", line.c_str());
    shown_ = line;
    if (done >= total_) finish();
  } else if (done >= total_ || elapsedSeconds - lastPlain_ >= plainInterval_) {
    // The first plain line waits one interval too: a short render's log
    // gets its final line only.
    std::fprintf(out_, "%s\n", line.c_str());
    lastPlain_ = elapsedSeconds;
  }
  std::fflush(out_);
}

void ProgressLine::clearLive() {
  if (live_ && !shown_.empty()) std::fprintf(out_, "\r\033[K");
}

void ProgressLine::notice(const std::string& line) {
  clearLive();
  std::fprintf(out_, "spectrace: %s\n", line.c_str());
  if (live_ && !shown_.empty()) std::fprintf(out_, "%s", shown_.c_str());
  std::fflush(out_);
}

void ProgressLine::finish() {
  if (live_ && !shown_.empty()) std::fprintf(out_, "\n");
  shown_.clear();
  std::fflush(out_);
}

}  // namespace spectrace::cli
