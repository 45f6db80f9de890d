#include "spectrum/alias_table.h"

#include <algorithm>
#include <bit>
#include <stdexcept>

namespace spectrace {

using u128 = unsigned __int128;

AliasTable buildAliasTable(std::span<const uint64_t> cdfLows) {
  if (cdfLows.empty() || cdfLows[0] != 0) throw std::invalid_argument("buildAliasTable: not an integer CDF");
  const size_t n = cdfLows.size();
  AliasTable table;
  table.bits = uint32_t(std::bit_width(n - 1));  // 2^bits >= n
  const size_t columns = size_t(1) << table.bits;
  const u128 capacity = u128(1) << (64 - table.bits);  // values of u per column
  // Integer Vose: every mass is an exact count of values of u, so the
  // columns fill exactly and nothing is lost to rounding.
  std::vector<u128> mass(columns, 0);
  for (size_t j = 0; j < n; ++j) {
    const u128 high = j + 1 < n ? u128(cdfLows[j + 1]) : u128(1) << 64;
    if (high < cdfLows[j]) throw std::invalid_argument("buildAliasTable: CDF lower ends decrease");
    mass[j] = high - cdfLows[j];
  }
  std::vector<uint32_t> small, large;
  for (size_t j = columns; j-- > 0;) (mass[j] < capacity ? small : large).push_back(uint32_t(j));
  table.columns.assign(columns, device::AliasColumn{});
  // A column's threshold is compared with u << bits, so it is stored
  // scaled by 2^bits; a full column (never aliased) has itself as alias.
  auto setColumn = [&](uint32_t c, u128 primary, uint32_t alias) {
    const bool full = primary == capacity;
    table.columns[c].threshold = full ? UINT64_MAX : uint64_t(primary << table.bits);
    table.columns[c].alias = full ? c : alias;
  };
  while (!small.empty() && !large.empty()) {
    const uint32_t s = small.back();
    small.pop_back();
    const uint32_t l = large.back();
    setColumn(s, mass[s], l);
    mass[l] -= capacity - mass[s];
    if (mass[l] < capacity) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // With exact counts the leftovers hold exactly one column's worth each.
  for (uint32_t l : large) {
    if (mass[l] != capacity) throw std::logic_error("buildAliasTable: masses do not fill the columns");
    setColumn(l, capacity, l);
  }
  if (!small.empty()) throw std::logic_error("buildAliasTable: masses do not fill the columns");
  return table;
}

std::vector<u128> aliasMasses(const AliasTable& table, size_t entries) {
  const u128 capacity = u128(1) << (64 - table.bits);
  std::vector<u128> total(std::max<size_t>(entries, table.columns.size()), 0);
  for (uint32_t c = 0; c < table.columns.size(); ++c) {
    const auto& column = table.columns[c];
    // The kernel's rule: c when (r << bits) < threshold for the column's
    // low bits r, else the alias (which may be c itself).
    u128 primary = (u128(column.threshold) + (u128(1) << table.bits) - 1) >> table.bits;
    if (primary > capacity) primary = capacity;
    total[c] += primary;
    if (column.alias >= total.size()) throw std::logic_error("aliasMasses: alias out of range");
    total[column.alias] += capacity - primary;
  }
  total.resize(entries);
  return total;
}

}  // namespace spectrace
