#pragma once
// Reads back what `roadload analyze` and roadloadd write into a results folder, for the report:
// cells.csv, trip.json and the PSD files. Every number is checked; an error names file, line and
// column.
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "roadload/parse_error.hpp"
#include "roadload/results/json.hpp"

namespace roadload::results {

// A CSV file read whole: numbers where the text is one, NaN for empty fields and "nan".
class NumberTable {
 public:
  static Parsed<NumberTable> read(const std::string& path, std::span<const std::string_view> text_columns);

  const std::string& path() const { return path_; }
  const std::vector<std::string>& columns() const { return columns_; }
  std::size_t rows() const { return lines_.size(); }
  std::optional<std::size_t> column(std::string_view name) const;
  // The value at (row, column); NaN for a text column.
  double at(std::size_t row, std::size_t column) const { return numbers_[row * columns_.size() + column]; }
  // A whole numeric column by name; empty when there is none.
  std::vector<double> values(std::string_view name) const;
  // A text column's field; empty for a numeric column.
  const std::string& text(std::size_t row, std::size_t column) const { return texts_[row * columns_.size() + column]; }

 private:
  std::string path_;
  std::vector<std::string> columns_;
  std::vector<long> lines_;
  std::vector<double> numbers_;
  std::vector<std::string> texts_;
};

// A spectrum file: the first column is the abscissa (freq_hz or cycles_per_m), each other one
// sensor's PSD.
struct Spectrum {
  std::string group;  // "trip" for psd.csv
  std::string x_name;
  std::vector<double> x;
  std::vector<std::string> sensors;
  std::vector<std::vector<double>> psd;  // per sensor, along x
};

struct ResultsDir {
  std::string dir;
  NumberTable cells;
  JsonValue trip;
  std::vector<Spectrum> spectra;             // psd.csv then psd-<group>.csv, by name
  std::optional<JsonValue> gap, gap_tables;  // gap.json and gap-tables.json when there (roadload gap)
};

Parsed<ResultsDir> read_results_dir(const std::string& dir);

}  // namespace roadload::results
