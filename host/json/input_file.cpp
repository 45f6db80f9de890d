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

}  // namespace

InputFile::InputFile(const std::filesystem::path& file, const char* what) : file_(file), what_(what) {
  struct stat st{};
  if (::stat(file.c_str(), &st) != 0) {
    const int err = errno;
    if (err == ENOENT) throw fail(fmt::format("{} not found", what), true);
    throw fail(fmt::format("cannot read the {}: {}", what, errnoText(err)));
  }
  // Checked before open(): opening a FIFO for reading blocks until a writer comes.
  if (!S_ISREG(st.st_mode)) throw fail(fmt::format("is {}, not a {}", kindOf(st.st_mode), what));
  fd_ = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd_ < 0) throw fail(fmt::format("cannot open the {}: {}", what, errnoText(errno)));
  // fstat again: the path may have been replaced between stat() and open().
  const bool statted = ::fstat(fd_, &st) == 0;
  const int err = errno;
  if (!statted || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw fail(statted ? fmt::format("is {}, not a {}", kindOf(st.st_mode), what)
                       : fmt::format("cannot read the {}: {}", what, errnoText(err)));
  }
  size_ = uint64_t(st.st_size);
}

InputFile::~InputFile() { ::close(fd_); }

InputFileError InputFile::fail(const std::string& why, bool missing) const {
  return InputFileError(fmt::format("{}: {}", file_.string(), why), why, missing);
}

size_t InputFile::readUpTo(uint64_t offset, void* out, size_t bytes) const {
  size_t done = 0;
  while (done < bytes) {
    const ssize_t n = ::pread(fd_, static_cast<char*>(out) + done, bytes - done, off_t(offset + done));
    if (n < 0) {
      if (errno == EINTR) continue;
      throw fail(fmt::format("error while reading the {}: {}", what_, errnoText(errno)));
    }
    if (n == 0) break;
    done += size_t(n);
  }
  return done;
}

void InputFile::readAt(uint64_t offset, void* out, size_t bytes) const {
  if (readUpTo(offset, out, bytes) != bytes)
    throw fail(fmt::format("the {} ended before byte {}; refusing a file that shrank while it was read", what_,
                           offset + bytes));
}

namespace {
thread_local const BundledInputFiles* bundledOnThisThread = nullptr;
}  // namespace

BundledInputFiles::BundledInputFiles(const InputFileBundle& files, std::string origin)
    : files_(files), origin_(std::move(origin)) {
  if (bundledOnThisThread) throw std::logic_error("BundledInputFiles nested");
  bundledOnThisThread = this;
}

BundledInputFiles::~BundledInputFiles() { bundledOnThisThread = nullptr; }

bool BundledInputFiles::active() { return bundledOnThisThread != nullptr; }

std::string BundledInputFiles::read(const std::filesystem::path& file, const char* what, uint64_t maxBytes) {
  const BundledInputFiles& self = *bundledOnThisThread;
  const auto found = self.files_.find(file.string());
  if (found == self.files_.end()) {
    const std::string why = fmt::format("{} not in {}", what, self.origin_);
    throw InputFileError(fmt::format("{}: {}", file.string(), why), why, true);
  }
  if (found->second.size() > maxBytes) {
    const std::string why = fmt::format("the {} is {} bytes; at most {} bytes ({} MiB) are read", what,
                                        found->second.size(), maxBytes, maxBytes >> 20);
    throw InputFileError(fmt::format("{}: {}", file.string(), why), why);
  }
  return found->second;
}

std::string readInputFile(const std::filesystem::path& file, const char* what, uint64_t maxBytes) {
  if (BundledInputFiles::active()) return BundledInputFiles::read(file, what, maxBytes);
  const InputFile in(file, what);
  if (in.size() > maxBytes)
    throw in.fail(fmt::format("the {} is {} bytes; at most {} bytes ({} MiB) are read", what, in.size(), maxBytes,
                              maxBytes >> 20));
  // One byte more than the size: reading it means the file grew while read.
  const size_t size = size_t(in.size());
  std::string bytes(size + 1, '\0');
  const size_t done = in.readUpTo(0, bytes.data(), bytes.size());
  if (done > size)
    throw in.fail(fmt::format("the {} grew while it was read; refusing a file that is still being written", what));
  bytes.resize(done);
  return bytes;
}

}  // namespace spectrace
