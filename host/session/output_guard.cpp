#include "session/output_guard.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <string_view>
#include <system_error>

#include <fmt/format.h>

namespace spectrace {
namespace fs = std::filesystem;

namespace {

std::string errnoText(int err) { return std::error_code(err, std::generic_category()).message(); }

fs::path folderOf(const fs::path& p) { return p.parent_path().empty() ? fs::path(".") : p.parent_path(); }

// The pid written in a lock file, or "an unknown process".
std::string holderOf(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  long pid = 0;
  if (n > 0 && std::from_chars(text, text + n, pid).ec == std::errc() && pid > 0) return fmt::format("pid {}", pid);
  return "an unknown process";
}

bool processIsAlive(long pid) { return ::kill(pid_t(pid), 0) == 0 || errno == EPERM; }

// The pid after `marker` when `name` is `prefix + marker + digits`.
bool tempPid(std::string_view name, std::string_view prefix, std::string_view marker, long& pid) {
  if (name.size() <= prefix.size() + marker.size() || name.substr(0, prefix.size()) != prefix ||
      name.substr(prefix.size(), marker.size()) != marker)
    return false;
  const std::string_view digits = name.substr(prefix.size() + marker.size());
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), pid);
  return ec == std::errc() && end == digits.data() + digits.size() && pid > 0;
}

}  // namespace

fs::path outputLockPath(const fs::path& output) {
  return folderOf(output) / fmt::format(".{}.lock", output.filename().string());
}

OutputLock::OutputLock(const fs::path& output) : path_(outputLockPath(output)) {
  // A lock file removed by its releaser between our open() and flock() is
  // no lock at all: retry until the locked file is the one at the path.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
      throw OutputError(fmt::format("cannot write {}: cannot create the lock file {}: {}", output.string(),
                                    path_.string(), errnoText(errno)));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      const std::string holder = err == EWOULDBLOCK ? holderOf(fd) : std::string();
      ::close(fd);
      if (err == EWOULDBLOCK)
        throw OutputLockedError(fmt::format(
            "output {} is being written by another spectrace ({}, lock file {}); wait for it or choose another -o",
            output.string(), holder, path_.string()));
      throw OutputError(fmt::format("cannot lock {}: {}", path_.string(), errnoText(err)));
    }
    struct stat held{}, named{};
    if (::fstat(fd, &held) == 0 && ::stat(path_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev) {
      const std::string pid = std::to_string(::getpid());
      if (::ftruncate(fd, 0) == 0) (void)!::pwrite(fd, pid.data(), pid.size(), 0);  // for the other's message only
      fd_ = fd;
      return;
    }
    ::close(fd);
  }
  throw OutputError(fmt::format("cannot lock {}: it keeps being replaced", path_.string()));
}

OutputLock::~OutputLock() {
  // Unlink while still holding the lock, so a waiter that opened this file
  // sees it is gone (the inode check above) and makes a new one.
  ::unlink(path_.c_str());
  ::close(fd_);
}

std::vector<fs::path> removeStaleTemporaries(const fs::path& target) {
  std::vector<fs::path> removed;
  const std::string name = target.filename().string();
  std::error_code ec;
  for (fs::directory_iterator it(folderOf(target), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    long pid = 0;
    // io/atomic_file.h's temporaries and checkOutputPath's probe.
    if (!tempPid(entry, name, ".tmp-", pid) && !tempPid(entry, "." + name, ".probe-", pid)) continue;
    if (pid != long(::getpid()) && processIsAlive(pid)) continue;
    std::error_code removeError;
    if (fs::remove(it->path(), removeError)) removed.push_back(it->path());
  }
  return removed;
}

}  // namespace spectrace
