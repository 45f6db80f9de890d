#include "cli/progress_line.h"

#include <cstdio>
#include <cstdlib>
#include <gtest/gtest.h>
#include <string>

namespace spectrace::cli {
namespace {

// What a ProgressLine writes, through an in-memory FILE.
class Captured {
 public:
  Captured() : file_(open_memstream(&data_, &size_)) {}
  ~Captured() {
    std::fclose(file_);
    std::free(data_);
  }
  std::FILE* file() { return file_; }
  std::string text() {
    std::fflush(file_);
    return std::string(data_, size_);
  }

 private:
  char* data_ = nullptr;
  size_t size_ = 0;
  std::FILE* file_;
};

size_t countOf(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(ProgressLine, FieldsGiveRateElapsedAndEta) {
  // 2^20 beams of 4 * 2^20 in 2 s: 0.524 Mbeam/s, 6 s left.
  EXPECT_EQ(progressFields(1 << 20, 4 << 20, 0, 2.0),
            " 25.0%, 1048576 of 4194304 beams, 0.524 Mbeam/s, 0:02 elapsed, ETA 0:06");
  // Resumed at 2^21: the rate counts this run's 2^20 beams only.
  EXPECT_EQ(progressFields(3 << 20, 4 << 20, 2 << 20, 2.0),
            " 75.0%, 3145728 of 4194304 beams, 0.524 Mbeam/s, 0:02 elapsed, ETA 0:02");
  EXPECT_EQ(progressFields(10, 10, 0, 3725.0), "100.0%, 10 of 10 beams, 2.68e-09 Mbeam/s, 1:02:05 elapsed");
  EXPECT_EQ(progressFields(0, 10, 0, 0.0), "  0.0%, 0 of 10 beams, 0:00 elapsed");
}

TEST(ProgressLine, DurationsReadAsAClock) {
  EXPECT_EQ(clockDuration(7.4), "0:07");
  EXPECT_EQ(clockDuration(750.0), "12:30");
  EXPECT_EQ(clockDuration(10935.0), "3:02:15");
  EXPECT_EQ(clockDuration(356535.0), "4d 3:02:15");
  EXPECT_EQ(clockDuration(-1.0), "?");
}

TEST(ProgressLine, OffATerminalPlainLinesAtMostEveryIntervalAndNoCarriageReturn) {
  Captured out;
  ProgressLine progress(out.file(), false, 10.0);
  progress.start(100, 0, "job: ");
  progress.update(10, 1.0);   // within the first interval: nothing
  progress.update(20, 10.5);  // a line
  progress.update(30, 15.0);  // 4.5 s later: nothing
  progress.notice("checkpoint: 30 beams -> a.exr");
  progress.update(40, 20.6);  // a line
  progress.update(100, 21.0); // the end: a line
  progress.finish();
  const std::string text = out.text();
  EXPECT_EQ(text.find('\r'), std::string::npos) << text;
  EXPECT_EQ(countOf(text, "\n"), 4u) << text;
  EXPECT_EQ(countOf(text, "spectrace: job: "), 3u) << text;
  EXPECT_NE(text.find("spectrace: job:  20.0%"), std::string::npos) << text;
  EXPECT_NE(text.find("\nspectrace: checkpoint: 30 beams -> a.exr\nspectrace: job:  40.0%"), std::string::npos) << text;
  EXPECT_NE(text.find("spectrace: job: 100.0%, 100 of 100 beams"), std::string::npos) << text;
  EXPECT_EQ(countOf(text, "ETA"), 2u) << text;  // none once finished
}

TEST(ProgressLine, OnATerminalOneLineRewrittenAndNoticesOnTheirOwn) {
  Captured out;
  ProgressLine progress(out.file(), true);
  progress.start(100, 0);
  progress.update(10, 0.5);
  progress.notice("note: x");
  progress.update(100, 1.0);
  const std::string text = out.text();
  const std::string first = "spectrace:  10.0%, 10 of 100 beams, 2e-05 Mbeam/s, 0:01 elapsed, ETA 0:05";
  // The live line is cleared before the notice, which ends in a newline,
  // and drawn again after it; the last update ends the line.
  EXPECT_EQ(text, "\r\033[K" + first + "\r\033[Kspectrace: note: x\n" + first + "\r\033[K" +
                      "spectrace: 100.0%, 100 of 100 beams, 0.0001 Mbeam/s, 0:01 elapsed\n");
}

}  // namespace
}  // namespace spectrace::cli
