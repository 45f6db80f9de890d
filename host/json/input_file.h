#pragma once
// Reading an input file (scene, job file, CSV spectrum, render state) with
// bounds: only a regular file is read (never /dev/zero, a FIFO or a folder,
// which could block or never end), and never more than a limit, checked
// before the bytes are read. docs/reliability.md "Input limits".
#include <cstdint>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace spectrace {

// Text inputs (scene files, job files, CSV spectra) are at most this big:
// far above any real scene or table, far below what would exhaust memory.
inline constexpr uint64_t kMaxInputFileBytes = uint64_t(64) << 20;  // 64 MiB

// The file cannot be read or breaks a bound. The message is "<path>: <why>";
// callers turn it into their own error type (SceneError, SpdError, ...).
struct InputFileError : std::runtime_error {
  InputFileError(const std::string& message, std::string why, bool isMissing = false)
      : std::runtime_error(message), reason(std::move(why)), missing(isMissing) {}
  std::string reason;  // the message without the path
  bool missing;        // there is no such file (callers may say where they looked)
};

// A regular file opened for reading: refused (a device, a pipe, a folder,
// missing) before anything is read, so a reader may look at its size and
// read only the parts it needs (a render state checks its header first).
class InputFile {
 public:
  // `what` names the kind of file in messages ("scene file", "state file").
  InputFile(const std::filesystem::path& file, const char* what);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  const std::filesystem::path& path() const { return file_; }
  uint64_t size() const { return size_; }  // when it was opened
  // Up to `bytes` bytes from `offset`; fewer only where the file ends.
  size_t readUpTo(uint64_t offset, void* out, size_t bytes) const;
  // Exactly `bytes` bytes from `offset`; a file that ends before is refused.
  void readAt(uint64_t offset, void* out, size_t bytes) const;
  // "<path>: <why>", as readInputFile's errors.
  InputFileError fail(const std::string& why, bool missing = false) const;

 private:
  std::filesystem::path file_;
  const char* what_;
  int fd_ = -1;
  uint64_t size_ = 0;
};

// The whole file, when it is a regular file of at most `maxBytes` bytes.
// `what` names the kind of file in messages ("scene file", "SPD file").
// While a BundledInputFiles lives on this thread, from its files instead.
std::string readInputFile(const std::filesystem::path& file, const char* what,
                          uint64_t maxBytes = kMaxInputFileBytes);

// Files by path (as the scene loader resolved it, not made absolute).
using InputFileBundle = std::map<std::string, std::string>;

// While one lives, readInputFile on this thread serves `files` in place of
// the disk, and refuses any path not among them ("<path>: not in <origin>"):
// a scene developed from a render state reads its CSV spectra and meshes
// from the state, and the parsers that read them sit several calls deep.
// Scoped, so no read outside it is redirected; never nested.
class BundledInputFiles {
 public:
  BundledInputFiles(const InputFileBundle& files, std::string origin);
  ~BundledInputFiles();
  BundledInputFiles(const BundledInputFiles&) = delete;
  BundledInputFiles& operator=(const BundledInputFiles&) = delete;

  // Whether one is in effect on this thread (callers that look at the disk
  // before reading skip that look).
  static bool active();
  // The bytes of `file`, or an InputFileError naming it when it is not
  // bundled or breaks `maxBytes`.
  static std::string read(const std::filesystem::path& file, const char* what, uint64_t maxBytes);

 private:
  const InputFileBundle& files_;
  std::string origin_;
};

}  // namespace spectrace
