#pragma once
// Shared by the libFuzzer targets: a scratch folder per process and the
// checks that turn a quiet wrong answer into a finding (abort with the
// reason, so libFuzzer saves the input).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace spectrace::fuzz {

// /tmp/spectrace-fuzz-<pid>/ (TMPDIR respected), created on first use and
// removed when the process exits normally.
const std::filesystem::path& scratchDir();
// Writes the input's bytes to `file` (replacing it); aborts if it cannot.
void writeBytes(const std::filesystem::path& file, const uint8_t* data, size_t size);
// Aborts with "<what> is not finite" when x is NaN or infinite: an accepted
// input must never produce one.
void requireFinite(double x, const std::string& what);
// Aborts with `what` when `ok` is false.
void require(bool ok, const std::string& what);

}  // namespace spectrace::fuzz
