#pragma once
// What went wrong, as an exit code and a message: the one place that maps
// exceptions to exit codes (README "Exit codes", docs/reliability.md).
#include <exception>
#include <string>

namespace spectrace::cli {

inline constexpr int kExitRuntime = 1;   // Vulkan, I/O during the render, out of memory
inline constexpr int kExitBadInput = 2;  // CLI arguments, scene file, CSV, job file, output path, state file

struct Failure {
  int code = kExitRuntime;
  std::string message;
};

// The exit code and message of a thrown exception.
Failure failureOf(const std::exception_ptr& error);

}  // namespace spectrace::cli
