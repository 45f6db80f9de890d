#pragma once
// Alias tables over integer CDFs (quantizeCdf): an O(1) draw with the very
// same probabilities. A table has 2^bits columns, where 2^bits is the
// smallest power of two >= the number of entries; the top `bits` of a 64-bit
// uniform u pick column c, and the remaining bits, compared with the
// column's threshold, pick c itself or its alias (device_shared.h,
// AliasColumn; the kernel's aliasLookup in shaders/emit.h). Each column
// covers exactly 2^(64 - bits) values of u, so every entry's probability is
// still an exact integer / 2^64, equal to its CDF width: zero-width entries
// are never drawn, positive ones always can be (aliasMasses checks it).
#include <cstdint>
#include <span>
#include <vector>

#include "device_shared.h"

namespace spectrace {

struct AliasTable {
  uint32_t bits = 0;                        // log2 of the column count
  std::vector<device::AliasColumn> columns;  // 2^bits
};

// The alias table of the integer CDF with these lower ends (cdfLow of
// quantizeCdf: first 0, widths summing to 2^64).
AliasTable buildAliasTable(std::span<const uint64_t> cdfLows);

// How many of the 2^64 values of u draw each of the first `entries`
// entries: exact, for tests against the CDF widths.
std::vector<unsigned __int128> aliasMasses(const AliasTable& table, size_t entries);

}  // namespace spectrace
