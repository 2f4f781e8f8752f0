// SPDX-License-Identifier: MIT
#include "mirage/io/csv_reader.h"

#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "mirage/io/input_error.h"

namespace mirage::io {
namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> Split(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = line.find(',', begin);
    fields.push_back(Trim(line.substr(begin, comma == std::string_view::npos ? std::string_view::npos : comma - begin)));
    if (comma == std::string_view::npos) break;
    begin = comma + 1;
  }
  return fields;
}

// Messages quote values; a value from a fuzzed file may hold anything, so print it escaped and short.
std::string Quote(std::string_view value) {
  std::string out = "'";
  for (const char c : value.substr(0, 40)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u >= 0x20 && u < 0x7f) ? std::string(1, c) : fmt::format("\\x{:02x}", u);
  }
  if (value.size() > 40) out += "...";
  return out + "'";
}

}  // namespace

CsvReader::CsvReader(std::string_view text, std::string file, std::vector<CsvColumn> columns)
    : text_(text), file_(std::move(file)), columns_(std::move(columns)) {
  // A UTF-8 byte-order mark (spreadsheet exports) is not part of the first column's name.
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);
  std::string_view header;
  if (!ReadLine(header)) throw InputError(file_ + ": empty file (expected a header row)");
  line_ = next_line_ - 1;
  index_of_column_.assign(columns_.size(), -1);
  const auto names = Split(header);
  for (std::size_t i = 0; i < names.size(); ++i) {
    header_.emplace_back(names[i]);
    int known = -1;
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      if (columns_[c].name == names[i]) known = static_cast<int>(c);
    }
    std::string accepted;
    for (const auto& c : columns_) accepted += (accepted.empty() ? "" : ",") + c.name;
    if (known < 0) FailRow(fmt::format("unknown column {} in the header (accepted: {})", Quote(names[i]), accepted));
    if (index_of_column_[static_cast<std::size_t>(known)] >= 0) {
      FailRow(fmt::format("duplicate column {} in the header", Quote(names[i])));
    }
    index_of_column_[static_cast<std::size_t>(known)] = static_cast<int>(i);
  }
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (columns_[c].required && index_of_column_[c] < 0) {
      FailRow(fmt::format("the header lacks the required column '{}'", columns_[c].name));
    }
  }
}

bool CsvReader::ReadLine(std::string_view& out) {
  while (pos_ < text_.size()) {
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    std::string_view line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++next_line_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (Trim(line).empty()) continue;
    out = line;
    return true;
  }
  return false;
}

bool CsvReader::Next() {
  std::string_view row;
  if (!ReadLine(row)) return false;
  line_ = next_line_ - 1;
  fields_ = Split(row);
  if (fields_.size() != header_.size()) {
    std::string header;
    for (const auto& h : header_) header += (header.empty() ? "" : ",") + h;
    FailRow(fmt::format("expected {} fields ({}), got {}", header_.size(), header, fields_.size()));
  }
  for (std::size_t i = 0; i < fields_.size(); ++i) {
    if (fields_[i].find('"') != std::string_view::npos) {
      Fail(header_[i], "quoted fields are not supported (ids are plain names without commas or quotes)");
    }
  }
  return true;
}

int CsvReader::Index(const std::string& column) const {
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (columns_[c].name == column) return index_of_column_[c];
  }
  return -1;
}

bool CsvReader::Has(const std::string& column) const { return Index(column) >= 0; }

std::string_view CsvReader::Field(const std::string& column) const {
  const int i = Index(column);
  if (i < 0 || fields_.empty()) return {};
  return fields_[static_cast<std::size_t>(i)];
}

double CsvReader::Number(const std::string& column) const {
  const std::string_view text = Field(column);
  if (text.empty()) Fail(column, "missing value (expected a number)");
  double value = 0.0;
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec == std::errc::result_out_of_range) Fail(column, "number out of range");
  if (ec != std::errc() || ptr != end) Fail(column, "not a number");
  if (!std::isfinite(value)) Fail(column, "must be finite");
  return value;
}

void CsvReader::Fail(const std::string& column, const std::string& message) const {
  throw InputError(fmt::format("{}:{}: {} {}: {}", file_, line_, column, Quote(Field(column)), message));
}

void CsvReader::FailRow(const std::string& message) const {
  throw InputError(fmt::format("{}:{}: {}", file_, line_, message));
}

}  // namespace mirage::io
