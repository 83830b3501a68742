#pragma once
// The CSV layout of sensor streams: a header naming the columns, then one sample per line,
// comma-separated numbers, '#' comment lines. Columns are found by name, so a stream may carry
// extra columns that an older reader skips.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "roadload/parse_error.hpp"
#include "roadload/recording/line_reader.hpp"

namespace roadload::recording {

class CsvReader {
 public:
  static constexpr std::size_t kMaxColumns = 32;

  // `optional` columns may be missing from the header: their fields then read as empty.
  static Parsed<CsvReader> open(const std::string& path, std::span<const std::string_view> required,
                                std::span<const std::string_view> optional = {});

  enum class Status : std::uint8_t { row, bad_row, end };
  // Fills `row` with the next data row's fields in the order of `required`, then `optional`. A bad row is reported
  // (error()) and the next call goes on with the following line; `end` with error() set means the
  // file could not be read.
  Status next(std::span<const std::string_view>& row);
  long line_number() const { return lines_.line_number(); }
  const std::string& path() const { return lines_.path(); }
  // The last bad row's error, or the reader's I/O error.
  const std::optional<ParseError>& error() const { return error_; }
  ParseError field_error(std::size_t column, std::string message) const;

 private:
  CsvReader(LineReader lines, std::vector<std::string> names, std::vector<std::size_t> map)
      : lines_(std::move(lines)), names_(std::move(names)), map_(std::move(map)) {}

  LineReader lines_;
  std::vector<std::string> names_;  // required, then optional column names
  std::vector<std::size_t> map_;    // column -> position in the file (kAbsent: not in it)
  static constexpr std::size_t kAbsent = kMaxColumns;
  std::size_t file_columns_ = 0;
  std::array<std::string_view, kMaxColumns> split_{};
  std::array<std::string_view, kMaxColumns> row_{};
  std::optional<ParseError> error_;
};

std::optional<std::int64_t> parse_i64(std::string_view s);
std::optional<double> parse_f64(std::string_view s);

}  // namespace roadload::recording
