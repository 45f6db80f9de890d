#pragma once
// Internal to host/io: write-to-temp-then-rename plumbing shared by the EXR
// and PNG writers.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

#include "io/image.h"

namespace spectrace::io_detail {

inline std::string errnoText(int err) { return std::error_code(err, std::generic_category()).message(); }

// pwrite() the whole buffer at `offset`; returns 0 or the errno of the failure.
// Loops because pwrite may write less than asked (signals, pipes, quotas).
inline int pwriteAll(int fd, const void* data, std::size_t size, std::uint64_t offset) noexcept {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::pwrite(fd, p, size, static_cast<off_t>(offset));
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    if (n == 0) return EIO;  // no progress and no error: don't spin forever
    p += n;
    size -= static_cast<std::size_t>(n);
    offset += static_cast<std::uint64_t>(n);
  }
  return 0;
}

// A file at `<target>.tmp-<pid>` that becomes `target` only on commit().
// Until then the destructor deletes it, so an exception (or a crash, which
// leaves only the .tmp file) never leaves a truncated image under the real name.
class AtomicFile {
 public:
  // `what` names the format in messages ("EXR", "PNG").
  AtomicFile(const std::filesystem::path& target, const char* what) : target_(target), what_(what) {
    if (target.empty()) fail("empty output path");
    const std::filesystem::path parent = target.parent_path();
    if (!parent.empty()) {
      std::error_code ec;
      std::filesystem::create_directories(parent, ec);
      if (ec) fail("cannot create directory " + parent.string() + ": " + ec.message());
    }
    temp_ = target;
    temp_ += ".tmp-" + std::to_string(::getpid());
    // O_TRUNC, not O_EXCL: a stale temp from a crashed process that had our
    // pid is garbage and may be overwritten.
    fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd_ < 0) fail("cannot create temporary file " + temp_.string() + ": " + errnoText(errno));
  }
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_) {
      std::error_code ignored;
      std::filesystem::remove(temp_, ignored);
    }
  }

  int fd() const { return fd_; }
  const std::filesystem::path& tempPath() const { return temp_; }

  // fsync before rename: otherwise after a power loss the rename can be
  // durable while the data is not, i.e. a truncated file under the real name.
  void commit() {
    if (::fsync(fd_) != 0) fail("cannot write " + temp_.string() + ": fsync: " + errnoText(errno));
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("cannot write " + temp_.string() + ": close: " + errnoText(errno));
    std::error_code ec;
    std::filesystem::rename(temp_, target_, ec);  // atomically replaces an existing file
    if (ec) fail("cannot rename " + temp_.string() + " to it: " + ec.message());
    committed_ = true;
    // Make the rename itself durable; best effort, the image is complete either way.
    const std::filesystem::path parent = target_.parent_path().empty() ? "." : target_.parent_path();
    const int dirFd = ::open(parent.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dirFd >= 0) {
      ::fsync(dirFd);
      ::close(dirFd);
    }
  }

  [[noreturn]] void fail(const std::string& why) const {
    throw ImageIoError(std::string("cannot write ") + what_ + " " + target_.string() + ": " + why);
  }

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  const char* what_;
  int fd_ = -1;
  bool committed_ = false;
};

}  // namespace spectrace::io_detail
