// Reading the comma-separated data tables in data/ (internal).
//
// Format: lines starting with '#' and blank lines are comments; the first other line is the header
// (column names, compared exactly with what the caller expects); every further line is one row
// with as many comma-separated fields as the header. Numbers are read in the C locale, whatever the
// user's locale. A malformed embedded table is a defect of the build, so failures throw
// skyspec::Error naming the file and line, not InputError.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace skyspec {

struct CsvRow {
  int line_number;                  ///< 1-based line in the file, for messages
  std::vector<std::string> fields;  ///< one per header column
};

/// Parses `text` (the content of `file_name`). Throws Error if the header differs from
/// `expected_header` or a row has the wrong number of fields.
std::vector<CsvRow> parse_csv(std::string_view file_name, std::string_view text,
                              const std::vector<std::string>& expected_header);

/// Field `column` of `row` as a finite number; throws Error("<file>:<line>: ...") otherwise.
double csv_number(std::string_view file_name, const CsvRow& row, size_t column);

}  // namespace skyspec
