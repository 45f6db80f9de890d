// libFuzzer target: SPD CSV files (parseCsvTable, loadCsvSpd with and
// without a column name). Bad input must end in SpdError (exit code 2); an
// accepted file must give a valid Spd: finite, strictly increasing
// wavelengths, finite non-negative values and a finite integral.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_support.h"
#include "spectrum/cie_data.h"
#include "spectrum/spd.h"

using namespace spectrace;

namespace {

void checkSpd(const Spd& spd) {
  fuzz::require(!spd.lambdaNm.empty() && spd.lambdaNm.size() == spd.value.size(), "an accepted SPD has no nodes");
  for (size_t i = 0; i < spd.lambdaNm.size(); ++i) {
    fuzz::requireFinite(spd.lambdaNm[i], "a wavelength");
    fuzz::requireFinite(spd.value[i], "a value");
    fuzz::require(spd.value[i] >= 0.0, "a negative value was accepted");
    fuzz::require(i == 0 || spd.lambdaNm[i] > spd.lambdaNm[i - 1], "wavelengths are not increasing");
  }
  fuzz::requireFinite(spd.integral(), "the integral");
  fuzz::requireFinite(spd.fullIntegral, "fullIntegral");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::string column;
  try {
    const CsvTable table = parseCsvTable(text, "fuzz.csv");
    fuzz::require(table.lambdaNm.size() == table.line.size(), "rows and line numbers differ in count");
    for (const auto& values : table.data)
      fuzz::require(values.size() == table.lambdaNm.size(), "a column's length differs from the row count");
    if (!table.columns.empty()) column = table.columns.front();
  } catch (const SpdError&) {
  }
  const auto file = fuzz::scratchDir() / "spd.csv";
  fuzz::writeBytes(file, data, size);
  try {
    checkSpd(loadCsvSpd(file));
  } catch (const SpdError&) {
  }
  if (!column.empty()) {
    try {
      checkSpd(loadCsvSpd(file, column));
    } catch (const SpdError&) {
    }
  }
  return 0;
}
