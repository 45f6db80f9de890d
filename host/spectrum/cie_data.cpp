#include "spectrum/cie_data.h"

#include <algorithm>
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

// The field separators a file may use (one per file), in the order that
// messages name them.
constexpr char kSeparators[] = {',', '\t', ';'};

std::string separatorName(char sep) { return sep == '\t' ? std::string("tab") : fmt::format("'{}'", sep); }

std::string separatorNames(const std::vector<char>& seps) {
  std::string s;
  for (size_t i = 0; i < seps.size(); ++i)
    s += (i == 0 ? "" : i + 1 == seps.size() ? " and " : ", ") + separatorName(seps[i]);
  return s;
}

// Splits a line at `sep` the RFC 4180 way: a field may be enclosed in double
// quotes, inside which "" is one quote and the separator and '#' are plain
// characters. Outside quotes '#' starts a comment. Whitespace around a field
// is dropped, inside its quotes too (a spreadsheet's " value" means
// "value"). Returns what is wrong, or "" when the line splits.
std::string splitFields(std::string_view line, char sep, std::vector<std::string>& out) {
  out.clear();
  const auto isSpace = [sep](char c) {
    return c != sep && (c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f');
  };
  const size_t n = line.size();
  size_t pos = 0;
  while (true) {
    while (pos < n && isSpace(line[pos])) ++pos;
    std::string field;
    if (pos < n && line[pos] == '"') {
      for (++pos;; ++pos) {
        if (pos >= n)
          return fmt::format("field {}: the quote that opens it is never closed (a quoted field ends on its line)",
                             out.size() + 1);
        if (line[pos] == '"') {
          if (pos + 1 < n && line[pos + 1] == '"') {
            field += '"';
            ++pos;
            continue;
          }
          ++pos;
          break;
        }
        field += line[pos];
      }
      while (pos < n && isSpace(line[pos])) ++pos;
      if (pos < n && line[pos] != sep && line[pos] != '#')
        return fmt::format("field {}: unexpected '{}' after its closing quote (a quote inside quotes is written \"\")",
                           out.size() + 1, line[pos]);
      field = std::string(trimWhitespace(field));
    } else {
      const size_t start = pos;
      while (pos < n && line[pos] != sep && line[pos] != '#') ++pos;
      field = trimWhitespace(line.substr(start, pos - start));
    }
    out.push_back(std::move(field));
    if (pos < n && line[pos] == sep) {
      ++pos;
      continue;
    }
    return {};
  }
}

// The separators that split `line` into two fields or more. A tab beside a
// ',' or ';' only pads it (the way comma files have always been aligned).
std::vector<char> splittingSeparators(std::string_view line, std::vector<std::string>& scratch) {
  std::vector<char> out;
  for (const char sep : kSeparators) {
    if (!splitFields(line, sep, scratch).empty() || scratch.size() < 2) continue;
    const auto padsAnother = [](const std::string& f) {
      return !f.empty() && (f.front() == ',' || f.front() == ';' || f.back() == ',' || f.back() == ';');
    };
    if (sep == '\t' && std::any_of(scratch.begin(), scratch.end(), padsAnother)) continue;
    out.push_back(sep);
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

// A hint for a field that is not a number but would be with '.' for ','
// (a semicolon or tab file from a locale with decimal commas).
std::string decimalCommaHint(std::string field, char sep) {
  if (sep == ',' || field.find(',') == std::string::npos) return {};
  std::replace(field.begin(), field.end(), ',', '.');
  double v = 0.0;
  return parseNumber(field, v) ? " (a decimal comma? write numbers with '.')" : "";
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
  // The next line with content (not blank, not only a comment) at or after
  // `pos`; false at the end of the text.
  const auto nextLine = [&text](size_t& pos, int& lineNo, std::string_view& line) {
    while (pos <= text.size()) {
      size_t nl = text.find('\n', pos);
      if (nl == std::string_view::npos) nl = text.size();
      line = text.substr(pos, nl - pos);
      pos = nl + 1;
      ++lineNo;
      const std::string_view content = trimWhitespace(line);
      if (!content.empty() && content.front() != '#') return true;
    }
    return false;
  };
  size_t nFields = 0;  // 0 until the header or first data row fixes it
  bool sawHeaderOrData = false;
  char sep = 0;  // fixed by the header or first data row
  int sepLine = 0;
  std::vector<std::string> fields, scratch;
  int lineNo = 0;
  size_t pos = 0;
  std::string_view line;
  while (nextLine(pos, lineNo, line)) {
    const auto where = [&] { return fmt::format("{}:{}: ", source, lineNo); };

    if (sep == 0) {
      // The one separator that splits this line. Where several do, a
      // header is settled by the first data row: the separator must split
      // both alike (so "nm,power; W/nm" over "500,1" stays a comma file).
      std::vector<char> seps = splittingSeparators(line, scratch);
      if (seps.size() > 1) {
        bool header = true;
        for (const char s : seps) {
          splitFields(line, s, scratch);
          double x = 0.0;
          if (parseNumber(scratch[0], x)) header = false;
        }
        std::string alsoLine;
        size_t nextPos = pos;
        int nextNo = lineNo;
        std::string_view next;
        if (header && nextLine(nextPos, nextNo, next)) {
          std::vector<char> fit;
          for (const char s : seps) {
            splitFields(line, s, scratch);
            const size_t headerFields = scratch.size();
            if (splitFields(next, s, scratch).empty() && scratch.size() == headerFields) fit.push_back(s);
          }
          if (!fit.empty()) seps = fit;
          alsoLine = fmt::format(" and line {}", nextNo);
        } else if (header) {
          seps.resize(1);  // no data rows: that is the error worth reporting
        }
        if (seps.size() > 1)
          throw SpdError(where() + fmt::format("the separator is unclear: {} each split this line{} into fields; a file "
                                               "has one separator, ',', tab or ';' (quote a field that holds another)",
                                               separatorNames(seps), alsoLine));
      }
      sep = seps.empty() ? ',' : seps[0];
      sepLine = lineNo;
    }
    if (const std::string error = splitFields(line, sep, fields); !error.empty()) throw SpdError(where() + error);
    const char* noSeparator = " (no ',', tab or ';' separates its fields)";

    double first = 0.0;
    if (!sawHeaderOrData && !parseNumber(fields[0], first)) {
      // Header line.
      sawHeaderOrData = true;
      if (fields.size() < 2)
        throw SpdError(where() + "header needs a wavelength column and at least one value column" + noSeparator);
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
        throw SpdError(where() + "expected 'wavelength_nm,value' but the row has only one field" + noSeparator);
      nFields = fields.size();
      t.data.resize(nFields - 1);
    }
    if (fields.size() != nFields) {
      std::string other;
      for (const char s : kSeparators)
        if (s != sep && splitFields(line, s, scratch).empty() && scratch.size() > 1) {
          other = fmt::format(" (the line is split by {}, but this file's separator is {}, set at line {})",
                              separatorName(s), separatorName(sep), sepLine);
          break;
        }
      throw SpdError(where() + fmt::format("expected {} {}-separated fields, got {}{}", nFields,
                                           sep == ',' ? "comma" : sep == ';' ? "semicolon" : "tab", fields.size(),
                                           other));
    }

    double lambda = 0.0;
    if (!parseNumber(fields[0], lambda))
      throw SpdError(where() + fmt::format("wavelength '{}' is not a number{}", fields[0],
                                           decimalCommaHint(fields[0], sep)));
    if (!std::isfinite(lambda)) throw SpdError(where() + fmt::format("non-finite wavelength ({})", fields[0]));
    if (lambda <= 0.0) throw SpdError(where() + fmt::format("wavelength must be positive, got {} nm", lambda));
    if (!t.lambdaNm.empty() && !(lambda > t.lambdaNm.back()))
      throw SpdError(where() + fmt::format("wavelengths must be strictly increasing: {} nm after {} nm (line {})",
                                           lambda, t.lambdaNm.back(), t.line.back()));
    for (size_t c = 1; c < nFields; ++c) {
      double v = 0.0;
      if (!parseNumber(fields[c], v)) {
        const std::string col = t.columns.empty() ? fmt::format("field {}", c + 1) : "column '" + t.columns[c - 1] + "'";
        throw SpdError(where() + fmt::format("{} at {} nm: '{}' is not a number{}", col, lambda, fields[c],
                                             decimalCommaHint(fields[c], sep)));
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
