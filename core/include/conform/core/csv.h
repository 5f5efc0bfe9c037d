#pragma once
// Tables in comma-separated files whose first line names the columns: the trajectory, edge, feature, grid and
// tool-path files of the jobs. Reading checks the shape (every row as wide as the header) and, cell by cell, the
// numbers, with messages that name the file, the line and the column. Writing is byte-for-byte deterministic: fixed
// decimals, '.' as the decimal point whatever the locale, "\n" line ends, and the file appears whole or not at all.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace conform {

struct CsvTable {
  std::string path;                              // the file read, for messages
  std::vector<std::string> columns;              // header names, trimmed
  std::vector<std::vector<std::string>> cells;   // rows x columns, trimmed
  std::vector<std::size_t> line_numbers;         // 1-based line of each row in the file

  std::size_t rows() const { return cells.size(); }
  bool has_column(std::string_view name) const;
  // The index of a column. Throws conform::Error "<path>: no column 'name' (the header has: ...)".
  std::size_t column(std::string_view name) const;

  const std::string& text(std::size_t row, std::size_t column) const;
  // A finite number within +-kMaxMagnitude (core/constants.h). Throws conform::Error
  // "<path>:<line>: column 'name': 'abc' is not a number" (or not finite, or beyond that bound).
  double number(std::size_t row, std::size_t column) const;
  // A whole number (no decimals). Throws conform::Error like number().
  std::int64_t integer(std::size_t row, std::size_t column) const;
  // The named columns as numbers, one matrix row per table row (rows x names.size()).
  Eigen::MatrixXd numbers(const std::vector<std::string>& names) const;
};

// Reads `path`: lines starting with '#' and blank lines are skipped; the first other line is the header; fields are
// separated by commas (by semicolons when the header has semicolons and no comma) and may be surrounded by spaces (a
// field in double quotes has them removed); a UTF-8 byte-order mark is skipped; column names are looked up whatever
// their case. Throws
// conform::Error naming the file when it cannot be read, has no header, has a duplicated or empty column name, or a
// row whose field count differs from the header's (naming the line).
CsvTable read_csv(const std::string& path);
// The same rules and messages for text already in memory; `path` names it in messages.
CsvTable parse_csv(std::string_view text, const std::string& path);
// As above, and every column of `required` must be present (the message lists the missing ones).
CsvTable read_csv(const std::string& path, const std::vector<std::string>& required);

class CsvWriter {
 public:
  // `decimals`: digits after the decimal point of every floating-point cell (6 = nanometres for millimetre columns).
  explicit CsvWriter(std::vector<std::string> columns, int decimals = 6);

  CsvWriter& cell(double value);
  CsvWriter& cell(std::int64_t value);
  CsvWriter& cell(int value) { return cell(static_cast<std::int64_t>(value)); }
  // Text without commas, quotes or line breaks (throws conform::Error otherwise).
  CsvWriter& cell(std::string_view value);
  // Ends the row; throws std::logic_error if it does not have one cell per column.
  void end_row();

  std::size_t rows() const { return rows_; }
  // The header line and every finished row.
  const std::string& text() const { return text_; }
  // Writes text() to `path` atomically; throws conform::Error naming the path when it cannot, or if a row is unfinished.
  void write(const std::string& path) const;

 private:
  void separator();

  std::size_t column_count_;
  int decimals_;
  std::size_t cells_in_row_ = 0;
  std::size_t rows_ = 0;
  std::string text_;
};

// `value` with `decimals` fixed decimals, '.' as the decimal point, and no sign on zero ("-0.000" becomes "0.000").
std::string format_fixed(double value, int decimals);

}  // namespace conform
