#include "json/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

#include <fmt/format.h>

namespace spectrace {
namespace {

std::string errnoText(int err) { return std::error_code(err, std::generic_category()).message(); }

const char* kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a pipe (FIFO)";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Closes the descriptor on every path out.
struct FdCloser {
  int fd;
  ~FdCloser() { ::close(fd); }
};

}  // namespace

std::string readInputFile(const std::filesystem::path& file, const char* what, uint64_t maxBytes) {
  auto fail = [&](const std::string& why, bool missing = false) {
    return InputFileError(fmt::format("{}: {}", file.string(), why), why, missing);
  };
  struct stat st{};
  if (::stat(file.c_str(), &st) != 0) {
    const int err = errno;
    if (err == ENOENT) throw fail(fmt::format("{} not found", what), true);
    throw fail(fmt::format("cannot read the {}: {}", what, errnoText(err)));
  }
  // Checked before open(): opening a FIFO for reading blocks until a writer comes.
  if (!S_ISREG(st.st_mode)) throw fail(fmt::format("is {}, not a {}", kindOf(st.st_mode), what));
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw fail(fmt::format("cannot open the {}: {}", what, errnoText(errno)));
  const FdCloser closer{fd};
  // fstat again: the path may have been replaced between stat() and open().
  if (::fstat(fd, &st) != 0) throw fail(fmt::format("cannot read the {}: {}", what, errnoText(errno)));
  if (!S_ISREG(st.st_mode)) throw fail(fmt::format("is {}, not a {}", kindOf(st.st_mode), what));
  if (uint64_t(st.st_size) > maxBytes)
    throw fail(fmt::format("the {} is {} bytes; at most {} bytes ({} MiB) are read", what, uint64_t(st.st_size),
                           maxBytes, maxBytes >> 20));
  // One byte more than the size: reading it means the file grew while read.
  const size_t size = size_t(st.st_size);
  std::string bytes(size + 1, '\0');
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw fail(fmt::format("error while reading the {}: {}", what, errnoText(errno)));
    }
    if (n == 0) break;
    done += size_t(n);
  }
  if (done > size) throw fail(fmt::format("the {} grew while it was read; refusing a file that is still being written", what));
  bytes.resize(done);
  return bytes;
}

}  // namespace spectrace
