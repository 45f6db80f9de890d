#pragma once
// Strict parsing of the CLI's numeric options. A value that is out of range
// or not a number is a UsageError (exit code 2), never silently wrapped.
#include <cstdint>
#include <stdexcept>
#include <string>

namespace spectrace::cli {

// Bad input on the command line (exit code 2); the message names the option.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The most CPU reference threads --threads accepts.
inline constexpr unsigned kMaxThreads = 1024;

// An unsigned 64-bit integer: digits only (no sign, no spaces), or a
// decimal/exponent form such as 1e8 that is exactly an integer; no overflow.
// `minimum` is the smallest value accepted (0 or 1).
uint64_t parseU64(const std::string& option, const std::string& text, uint64_t minimum);

// A finite number >= 0 (for --checkpoint-seconds).
double parseNonNegativeSeconds(const std::string& option, const std::string& text);

// 1..kMaxThreads.
unsigned parseThreads(const std::string& option, const std::string& text);

// first + count must not pass 2^64 (the beam indices must fit in 64 bits).
void checkBeamRange(uint64_t first, uint64_t count);

}  // namespace spectrace::cli
