// SPDX-License-Identifier: MIT
// A strict reader of the recorded-data CSV files: a header row naming the columns (any order),
// then one row per line with exactly one field per column. Unknown, duplicate or missing
// columns, short or long rows, quoted fields and non-finite numbers are errors naming the file,
// line, column and value; empty lines are skipped. No quoting: ids are plain names.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace mirage::io {

/// One column the reader accepts.
struct CsvColumn {
  std::string name;
  bool required = true;
};

class CsvReader {
 public:
  /// Reads the header; throws InputError on a bad one.
  /// @param text    the whole file
  /// @param file    the name used in messages
  /// @param columns the accepted columns
  CsvReader(std::string_view text, std::string file, std::vector<CsvColumn> columns);

  /// Advances to the next non-empty row; false at the end. Throws on a row with a wrong field count.
  bool Next();

  /// 1-based line number of the current row.
  [[nodiscard]] int line() const { return line_; }
  [[nodiscard]] const std::string& file() const { return file_; }
  /// Whether the header has this column.
  [[nodiscard]] bool Has(const std::string& column) const;
  /// The trimmed text of a column of the current row.
  [[nodiscard]] std::string_view Field(const std::string& column) const;
  /// A finite number; throws on anything else.
  [[nodiscard]] double Number(const std::string& column) const;

  /// Throws InputError "file:line: column 'value': message".
  [[noreturn]] void Fail(const std::string& column, const std::string& message) const;
  /// Throws InputError "file:line: message".
  [[noreturn]] void FailRow(const std::string& message) const;

 private:
  bool ReadLine(std::string_view& out);
  [[nodiscard]] int Index(const std::string& column) const;

  std::string_view text_;
  std::size_t pos_ = 0;
  std::string file_;
  std::vector<CsvColumn> columns_;
  std::vector<int> index_of_column_;  // column (as given) -> field index, -1 when absent
  std::vector<std::string> header_;
  std::vector<std::string_view> fields_;
  int line_ = 0;
  int next_line_ = 1;
};

}  // namespace mirage::io
