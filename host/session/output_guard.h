#pragma once
// What keeps renders from harming each other's outputs: a lock per output
// (two renders to one path: the second is refused) and the clean-up of
// temporary files a killed render left behind. docs/reliability.md.
#include <filesystem>
#include <string>
#include <vector>

#include "session/session.h"

namespace spectrace {

// Another live process is writing the same output.
struct OutputLockedError : OutputError {
  using OutputError::OutputError;
};

// Holds `.NAME.lock` beside `output` (flock, with this process's pid in it)
// from construction to destruction; the file is removed on release. Throws
// OutputLockedError naming the other process's pid when it holds the lock,
// OutputError when the lock file cannot be created.
class OutputLock {
 public:
  explicit OutputLock(const std::filesystem::path& output);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

// The lock file of `output`: `.NAME.lock` in its folder.
std::filesystem::path outputLockPath(const std::filesystem::path& output);

// Removes the temporary files of `target` (`NAME.tmp-PID`, `.NAME.probe-PID`)
// whose process is gone (or has our pid, so is an earlier process's: call it
// only while holding the output's lock). Returns what it removed.
std::vector<std::filesystem::path> removeStaleTemporaries(const std::filesystem::path& target);

}  // namespace spectrace
