// Reading the comma-separated data tables in data/ (see csv_table.hpp).
#include "base/csv_table.hpp"

#include <cmath>
#include <locale>
#include <sstream>

#include "skyspec/error.hpp"

namespace skyspec {
namespace {

Error table_error(std::string_view file_name, int line_number, const std::string& why) {
  return Error(std::string(file_name) + ":" + std::to_string(line_number) + ": " + why);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();  // a trailing empty field
  return fields;
}

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (size_t i = 0; i < names.size(); ++i) s += (i ? "," : "") + names[i];
  return s;
}

}  // namespace

std::vector<CsvRow> parse_csv(std::string_view file_name, std::string_view text,
                              const std::vector<std::string>& expected_header) {
  std::vector<CsvRow> rows;
  std::istringstream in{std::string(text)};
  std::string line;
  bool header_seen = false;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields = split_fields(line);
    if (!header_seen) {
      header_seen = true;
      if (fields != expected_header)
        throw table_error(file_name, line_number, "expected the header '" + join(expected_header) + "'");
      continue;
    }
    if (fields.size() != expected_header.size())
      throw table_error(file_name, line_number,
                        "expected " + std::to_string(expected_header.size()) + " comma-separated fields");
    rows.push_back({line_number, std::move(fields)});
  }
  if (!header_seen) throw table_error(file_name, line_number, "no header line");
  return rows;
}

double csv_number(std::string_view file_name, const CsvRow& row, size_t column) {
  const std::string& text = row.fields.at(column);
  std::istringstream in(text);
  in.imbue(std::locale::classic());
  double value = 0.0;
  in >> value;
  if (in.fail() || !(in >> std::ws).eof() || !std::isfinite(value))
    throw table_error(file_name, row.line_number, "'" + text + "' is not a number");
  return value;
}

}  // namespace skyspec
