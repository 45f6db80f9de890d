#include "spectrum/cie_data.h"

#include <charconv>
#include <cmath>
#include <system_error>

#include <fmt/format.h>

#include "embedded_cie.h"
#include "spectrum/spd.h"

namespace spectrace {

std::string_view trimWhitespace(std::string_view s) {
  const char* ws = " \t\r\v\f";
  const size_t b = s.find_first_not_of(ws);
  if (b == std::string_view::npos) return {};
  const size_t e = s.find_last_not_of(ws);
  return s.substr(b, e - b + 1);
}

namespace {

std::vector<std::string_view> splitFields(std::string_view line) {
  std::vector<std::string_view> out;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    out.push_back(trimWhitespace(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

// Whole-field number parse (a leading '+' allowed). nan/inf parse, so that
// the caller can report them as non-finite rather than as "not a number".
bool parseNumber(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && ptr == s.data() + s.size();
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) {
    if (!s.empty()) s += ", ";
    s += n;
  }
  return s;
}

CsvTable parseEmbedded(std::span<const unsigned char> bytes, const char* name) {
  return parseCsvTable(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                       std::string("embedded ") + name);
}

}  // namespace

CsvTable parseCsvTable(std::string_view text, const std::string& source) {
  CsvTable t;
  t.source = source;
  // A UTF-8 byte-order mark (spreadsheets write one) is not part of the
  // first field: left there, it made a first data row look like a header,
  // silently dropped.
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  size_t nFields = 0;  // 0 until the header or first data row fixes it
  bool sawHeaderOrData = false;
  int lineNo = 0;
  size_t pos = 0;
  while (pos <= text.size()) {
    size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    std::string_view line = text.substr(pos, nl - pos);
    pos = nl + 1;
    ++lineNo;
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    line = trimWhitespace(line);
    if (line.empty()) continue;
    const auto where = [&] { return fmt::format("{}:{}: ", source, lineNo); };
    const std::vector<std::string_view> fields = splitFields(line);

    double first = 0.0;
    if (!sawHeaderOrData && !parseNumber(fields[0], first)) {
      // Header line.
      sawHeaderOrData = true;
      if (fields.size() < 2)
        throw SpdError(where() + "header needs a wavelength column and at least one value column");
      nFields = fields.size();
      for (size_t i = 1; i < fields.size(); ++i) {
        if (fields[i].empty()) throw SpdError(where() + fmt::format("header column {} has no name", i + 1));
        t.columns.emplace_back(fields[i]);
      }
      t.data.resize(nFields - 1);
      continue;
    }
    if (!sawHeaderOrData) {
      sawHeaderOrData = true;
      if (fields.size() < 2)
        throw SpdError(where() + "expected 'wavelength_nm,value' but the row has only one field");
      nFields = fields.size();
      t.data.resize(nFields - 1);
    }
    if (fields.size() != nFields)
      throw SpdError(where() + fmt::format("expected {} comma-separated fields, got {}", nFields, fields.size()));

    double lambda = 0.0;
    if (!parseNumber(fields[0], lambda))
      throw SpdError(where() + fmt::format("wavelength '{}' is not a number", fields[0]));
    if (!std::isfinite(lambda)) throw SpdError(where() + fmt::format("non-finite wavelength ({})", fields[0]));
    if (lambda <= 0.0) throw SpdError(where() + fmt::format("wavelength must be positive, got {} nm", lambda));
    if (!t.lambdaNm.empty() && !(lambda > t.lambdaNm.back()))
      throw SpdError(where() + fmt::format("wavelengths must be strictly increasing: {} nm after {} nm (line {})",
                                           lambda, t.lambdaNm.back(), t.line.back()));
    for (size_t c = 1; c < nFields; ++c) {
      double v = 0.0;
      if (!parseNumber(fields[c], v)) {
        const std::string col = t.columns.empty() ? fmt::format("field {}", c + 1) : "column '" + t.columns[c - 1] + "'";
        throw SpdError(where() + fmt::format("{} at {} nm: '{}' is not a number", col, lambda, fields[c]));
      }
      t.data[c - 1].push_back(v);
    }
    t.lambdaNm.push_back(lambda);
    t.line.push_back(lineNo);
    if (t.lambdaNm.size() > kMaxSpdPoints)
      throw SpdError(where() + fmt::format("more than {} data rows, the most a spectrum may have", kMaxSpdPoints));
  }
  if (t.lambdaNm.empty()) throw SpdError(fmt::format("{}: no data rows", source));
  return t;
}

size_t csvColumnIndex(const CsvTable& table, std::string_view column) {
  if (table.columns.empty())
    throw SpdError(fmt::format("{}: column '{}' requested, but the file has no header line naming its columns",
                               table.source, column));
  for (size_t i = 0; i < table.columns.size(); ++i)
    if (table.columns[i] == column) return i;
  throw SpdError(fmt::format("{}: column '{}' not found; columns are: {}", table.source, column,
                             joinNames(table.columns)));
}

const CsvTable& cie1931Table() {
  static const CsvTable t = parseEmbedded(embedded::cie1931_2deg_xyz(), "cie1931_2deg_xyz.csv");
  return t;
}

const CsvTable& cie1964Table() {
  static const CsvTable t = parseEmbedded(embedded::cie1964_10deg_xyz(), "cie1964_10deg_xyz.csv");
  return t;
}

const std::vector<const CsvTable*>& cieIlluminantTables() {
  static const CsvTable a = parseEmbedded(embedded::illuminant_a(), "illuminant_a.csv");
  static const CsvTable d50 = parseEmbedded(embedded::illuminant_d50(), "illuminant_d50.csv");
  static const CsvTable d65 = parseEmbedded(embedded::illuminant_d65(), "illuminant_d65.csv");
  static const CsvTable f = parseEmbedded(embedded::illuminants_f(), "illuminants_f.csv");
  static const CsvTable f3 = parseEmbedded(embedded::illuminants_f3(), "illuminants_f3.csv");
  static const CsvTable led = parseEmbedded(embedded::illuminants_led(), "illuminants_led.csv");
  static const std::vector<const CsvTable*> all{&a, &d50, &d65, &f, &f3, &led};
  return all;
}

const CsvTable& colorCheckerTable() {
  static const CsvTable t = parseEmbedded(embedded::colorchecker24_ohta(), "colorchecker24_ohta.csv");
  return t;
}

}  // namespace spectrace
