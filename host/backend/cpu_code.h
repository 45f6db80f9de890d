#pragma once
#include <optional>
#include <string_view>

namespace spectrace {

// Which machine code runs the CPU reference's beam loop. The loop and the
// whole shared kernel inside it are compiled twice from the same text: for
// the baseline of the build's architecture, and on x86-64 also for
// x86-64-v3 (AVX2, BMI2, three-operand VEX forms), taken when the processor
// has it: baseline : x86-64-v3 = 1.13 in whole-process time on the
// throughput scene (scripts/cpu_code_speed.sh; docs/benchmarks.md).
// Both keep -ffp-contract=off and use only correctly rounded operations,
// so they draw and count the same beams bit for bit; cpu_code_test checks
// that on every light type, the pinhole, exact colour and the profile.
enum class CpuCode { Baseline, X86_64_V3 };
// The fastest code this processor runs.
CpuCode fastestCpuCode();
// Whether this processor runs `code`.
bool cpuRuns(CpuCode code);
// "baseline" or "x86-64-v3", as --cpu-code and device names write them.
const char* cpuCodeName(CpuCode code);
// The code named `name` ("baseline", "x86-64-v3"), or none for another name.
std::optional<CpuCode> cpuCodeNamed(std::string_view name);

}  // namespace spectrace
