#include "cli/cli_numbers.h"

#include <cctype>
#include <cmath>
#include <fmt/format.h>

namespace spectrace::cli {
namespace {

[[noreturn]] void bad(const std::string& option, const std::string& text, const std::string& why) {
  throw UsageError(fmt::format("{} {}: {}", option, text.empty() ? "''" : text, why));
}

}  // namespace

uint64_t parseU64(const std::string& option, const std::string& text, uint64_t minimum) {
  const std::string want =
      minimum ? "must be a whole number from 1 to 18446744073709551615"
              : "must be a whole number from 0 to 18446744073709551615";
  if (text.empty()) bad(option, text, want);
  if (text[0] == '-') bad(option, text, want + " (no sign)");
  bool digits = true;
  for (char c : text) digits = digits && std::isdigit(static_cast<unsigned char>(c));
  uint64_t value = 0;
  if (digits) {
    for (char c : text) {
      const uint64_t d = uint64_t(c - '0');
      if (value > (UINT64_MAX - d) / 10) bad(option, text, want + " (too large)");
      value = value * 10 + d;
    }
  } else {
    // 1e8, 2.5e3: accepted only when exactly an integer in range. Parse the
    // mantissa's digits and the exponent ourselves so there is no rounding.
    size_t i = 0;
    std::string mantissa;
    int fraction = 0;
    bool dot = false;
    for (; i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.'); ++i) {
      if (text[i] == '.') {
        if (dot) bad(option, text, want);
        dot = true;
      } else {
        mantissa += text[i];
        if (dot) ++fraction;
      }
    }
    if (mantissa.empty() || i >= text.size() || (text[i] != 'e' && text[i] != 'E')) bad(option, text, want);
    ++i;
    if (i < text.size() && text[i] == '+') ++i;
    if (i >= text.size() || text.size() - i > 3) bad(option, text, want);
    int exponent = 0;
    for (; i < text.size(); ++i) {
      if (!std::isdigit(static_cast<unsigned char>(text[i]))) bad(option, text, want);
      exponent = exponent * 10 + (text[i] - '0');
    }
    int shift = exponent - fraction;
    // trailing zeros of the mantissa may absorb a negative shift
    while (shift < 0 && mantissa.size() > 1 && mantissa.back() == '0') {
      mantissa.pop_back();
      ++shift;
    }
    if (shift < 0) bad(option, text, want + " (not an integer)");
    for (char c : mantissa) {
      const uint64_t d = uint64_t(c - '0');
      if (value > (UINT64_MAX - d) / 10) bad(option, text, want + " (too large)");
      value = value * 10 + d;
    }
    for (int k = 0; k < shift; ++k) {
      if (value == 0) break;
      if (value > UINT64_MAX / 10) bad(option, text, want + " (too large)");
      value *= 10;
    }
  }
  if (value < minimum) bad(option, text, want);
  return value;
}

double parseNonNegativeSeconds(const std::string& option, const std::string& text) {
  const std::string want = "must be a finite number of seconds >= 0 (0: never)";
  size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    bad(option, text, want);
  }
  if (used != text.size() || !std::isfinite(value) || value < 0) bad(option, text, want);
  return value;
}

unsigned parseThreads(const std::string& option, const std::string& text) {
  const uint64_t value = parseU64(option, text, 1);
  if (value > kMaxThreads) bad(option, text, fmt::format("must be from 1 to {}", kMaxThreads));
  return unsigned(value);
}

void checkBeamRange(uint64_t first, uint64_t count) {
  if (count > 0 && first > UINT64_MAX - (count - 1))
    throw UsageError(fmt::format("--first-beam {} plus --beams {} passes 2^64 beams (the beam index would wrap)",
                                 first, count));
}

}  // namespace spectrace::cli
