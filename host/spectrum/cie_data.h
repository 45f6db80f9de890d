#pragma once
// CSV tables of spectral data (wavelength column + value columns), shared by
// the SPD loader and the embedded CIE tables (colour observers, illuminants).
#include <string>
#include <string_view>
#include <vector>

namespace spectrace {

// A parsed "wavelength_nm,col1,col2,..." table. Wavelengths are checked
// (finite, > 0, strictly increasing) while parsing; values are stored as
// read (NaN, inf and negatives included) so that only the column actually
// used is validated (see spdFromCsvColumn).
struct CsvTable {
  std::string source;                     // file path or "embedded <name>", for messages
  std::vector<std::string> columns;       // value column names (empty if no header)
  std::vector<double> lambdaNm;           // one per data row
  std::vector<std::vector<double>> data;  // data[column][row]
  std::vector<int> line;                  // 1-based source line of each row
};

// Parses CSV text: an optional header line (recognised by a first field that
// is not a number), '#' comments (whole line or trailing), blank lines, CRLF
// or LF. Fields are separated by ',', tab or ';', one for the whole file,
// taken from the header or first data row; a field may be quoted (RFC 4180:
// "" is a quote, a separator or '#' inside quotes is text; one line per
// field). Every data row must have as many fields as the first row/header.
// Throws SpdError whose message starts with "<source>:<line>: ".
CsvTable parseCsvTable(std::string_view text, const std::string& source);

// `s` without leading and trailing whitespace (the CSV readers' field rule).
std::string_view trimWhitespace(std::string_view s);

// Index of the named value column; throws SpdError
// ("column 'X' not found in <source>; columns are: ...") otherwise.
size_t csvColumnIndex(const CsvTable& table, std::string_view column);

// The embedded CIE CSV tables (data/cie/*.csv), parsed once.
const CsvTable& cie1931Table();      // xbar, ybar, zbar
const CsvTable& cie1964Table();      // xbar10, ybar10, zbar10
// The illuminant tables, in the order A, D50, D65, F, F3, LED.
const std::vector<const CsvTable*>& cieIlluminantTables();
// The 24 ColorChecker patches' reflectance (0-1), Ohta 1997, 380-780 nm at
// 5 nm; the columns are the patch names in chart order ("dark_skin", ...,
// "white_9.5", ..., "black_2").
const CsvTable& colorCheckerTable();

}  // namespace spectrace
