// CSV tables: see csv.h.

#include "conform/core/csv.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "conform/core/atomic_file.h"
#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "file_bytes.h"
#include "text_scanner.h"

namespace conform {

namespace {

using detail::trim;

std::string unquote(std::string_view field) {
  field = trim(field);
  if (field.size() >= 2 && field.front() == '"' && field.back() == '"') field = field.substr(1, field.size() - 2);
  return std::string(field);
}

std::vector<std::string> split(std::string_view line, char separator) {
  std::vector<std::string> fields;
  while (true) {
    const std::size_t end = line.find(separator);
    fields.push_back(unquote(line.substr(0, end)));
    if (end == std::string_view::npos) return fields;
    line.remove_prefix(end + 1);
  }
}

bool skipped(std::string_view line) {
  const std::string_view body = trim(line);
  return body.empty() || body.front() == '#';
}

std::string header_list(const std::vector<std::string>& columns) {
  std::string list;
  for (const std::string& name : columns) list += (list.empty() ? "" : ",") + name;
  return list;
}

// Column names match whatever their case (X_MM is x_mm: spreadsheets and other tools write either).
bool same_name(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  }
  return true;
}

}  // namespace

bool CsvTable::has_column(std::string_view name) const {
  for (const std::string& c : columns) {
    if (same_name(c, name)) return true;
  }
  return false;
}

std::size_t CsvTable::column(std::string_view name) const {
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (same_name(columns[c], name)) return c;
  }
  throw Error(path + ": no column '" + std::string(name) + "' (the header has: " + header_list(columns) + ")");
}

const std::string& CsvTable::text(std::size_t row, std::size_t column_index) const {
  return cells.at(row).at(column_index);
}

double CsvTable::number(std::size_t row, std::size_t column_index) const {
  const std::string& token = text(row, column_index);
  double value = 0.0;
  const std::string where =
      path + ":" + std::to_string(line_numbers[row]) + ": column '" + columns[column_index] + "': ";
  if (!detail::parse_number(token, value)) throw Error(where + detail::describe_bad_number(token));
  if (!std::isfinite(value)) throw Error(where + "'" + token + "' is not a finite number");
  if (std::abs(value) > kMaxMagnitude) {
    throw Error(where + "'" + token + "' is beyond +-1e7, more than any length (mm), angle or time a job reads");
  }
  return value;
}

std::int64_t CsvTable::integer(std::size_t row, std::size_t column_index) const {
  const std::string& token = text(row, column_index);
  std::int64_t value = 0;
  if (!detail::parse_number(token, value)) {
    throw Error(path + ":" + std::to_string(line_numbers[row]) + ": column '" + columns[column_index] +
                "': " + detail::describe_bad_number(token, true));
  }
  return value;
}

Eigen::MatrixXd CsvTable::numbers(const std::vector<std::string>& names) const {
  std::vector<std::size_t> indices;
  for (const std::string& name : names) indices.push_back(column(name));
  Eigen::MatrixXd values(static_cast<Eigen::Index>(rows()), static_cast<Eigen::Index>(names.size()));
  for (std::size_t r = 0; r < rows(); ++r) {
    for (std::size_t k = 0; k < indices.size(); ++k) {
      values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) = number(r, indices[k]);
    }
  }
  return values;
}

CsvTable read_csv(const std::string& path) {
  const detail::FileBytes bytes = detail::read_file_bytes(path);
  return parse_csv(bytes.view(), path);
}

CsvTable parse_csv(std::string_view text, const std::string& path) {
  CsvTable table;
  table.path = path;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // a UTF-8 byte-order mark (spreadsheet exports)
  detail::LineScanner lines(text);
  std::string_view line;
  bool have_header = false;
  char separator = ',';
  while (lines.next(line)) {
    if (skipped(line)) continue;
    // A header with semicolons and no comma: the whole file is separated by semicolons (European spreadsheets).
    if (!have_header && line.find(',') == std::string_view::npos && line.find(';') != std::string_view::npos) {
      separator = ';';
    }
    std::vector<std::string> fields = split(line, separator);
    if (!have_header) {
      for (std::size_t c = 0; c < fields.size(); ++c) {
        if (fields[c].empty()) {
          throw Error(path + ":" + std::to_string(lines.line_number()) + ": the header's column " +
                      std::to_string(c + 1) + " has no name");
        }
        for (std::size_t d = 0; d < c; ++d) {
          if (fields[d] == fields[c]) {
            throw Error(path + ":" + std::to_string(lines.line_number()) + ": column '" + fields[c] +
                        "' appears twice in the header");
          }
        }
      }
      table.columns = std::move(fields);
      have_header = true;
      continue;
    }
    if (fields.size() != table.columns.size()) {
      throw Error(path + ":" + std::to_string(lines.line_number()) + ": " + std::to_string(fields.size()) +
                  " fields, but the header names " + std::to_string(table.columns.size()) + " (" +
                  header_list(table.columns) + ")");
    }
    table.cells.push_back(std::move(fields));
    table.line_numbers.push_back(lines.line_number());
  }
  if (!have_header) throw Error(path + ": no header line (a CSV file must start with the column names)");
  return table;
}

CsvTable read_csv(const std::string& path, const std::vector<std::string>& required) {
  CsvTable table = read_csv(path);
  std::string missing;
  for (const std::string& name : required) {
    if (!table.has_column(name)) missing += (missing.empty() ? "" : ", ") + name;
  }
  if (!missing.empty()) {
    throw Error(path + ": missing column(s) " + missing + " (the header has: " + header_list(table.columns) +
                "; expected: " + header_list(required) + ")");
  }
  return table;
}

std::string format_fixed(double value, int decimals) {
  char buffer[512];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
  if (result.ec != std::errc()) throw std::logic_error("format_fixed: number too long");
  std::string text(buffer, result.ptr);
  if (text.front() == '-' && text.find_first_not_of("0.", 1) == std::string::npos) text.erase(0, 1);
  return text;
}

CsvWriter::CsvWriter(std::vector<std::string> columns, int decimals)
    : column_count_(columns.size()), decimals_(decimals) {
  text_ = header_list(columns) + "\n";
}

void CsvWriter::separator() {
  if (cells_in_row_ >= column_count_) throw std::logic_error("CsvWriter: more cells than columns");
  if (cells_in_row_ > 0) text_ += ',';
  ++cells_in_row_;
}

CsvWriter& CsvWriter::cell(double value) {
  separator();
  text_ += format_fixed(value, decimals_);
  return *this;
}

CsvWriter& CsvWriter::cell(std::int64_t value) {
  separator();
  text_ += std::to_string(value);
  return *this;
}

CsvWriter& CsvWriter::cell(std::string_view value) {
  if (value.find_first_of(",\"\r\n") != std::string_view::npos) {
    throw Error("CSV cell '" + std::string(value) + "' holds a comma, quote or line break");
  }
  separator();
  text_ += value;
  return *this;
}

void CsvWriter::end_row() {
  if (cells_in_row_ != column_count_) throw std::logic_error("CsvWriter: row with too few cells");
  text_ += '\n';
  cells_in_row_ = 0;
  ++rows_;
}

void CsvWriter::write(const std::string& path) const {
  if (cells_in_row_ != 0) throw Error(path + ": unfinished CSV row");
  write_file_atomically(path, text_);
}

}  // namespace conform
