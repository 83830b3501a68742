#include "roadload/results/results_dir.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>

#include "roadload/recording/csv.hpp"

namespace roadload::results {
namespace {

// RFC 4180 fields, as LineBuilder::field writes them: a field holding a comma or a quote is in
// quotes, its quotes doubled. Nothing when a quote is left open.
std::optional<std::vector<std::string>> split(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t at = 0;
  while (true) {
    std::string field;
    if (at < line.size() && line[at] == '"') {
      for (++at;; ++at) {
        if (at >= line.size()) return std::nullopt;
        if (line[at] != '"') {
          field += line[at];
        } else if (at + 1 < line.size() && line[at + 1] == '"') {
          field += '"';
          ++at;
        } else {
          ++at;
          break;
        }
      }
      if (at < line.size() && line[at] != ',') return std::nullopt;
    } else {
      const std::size_t comma = std::min(line.find(',', at), line.size());
      field = line.substr(at, comma - at);
      at = comma;
    }
    fields.push_back(std::move(field));
    if (at >= line.size()) return fields;
    ++at;
  }
}

Parsed<Spectrum> read_spectrum(const std::string& path, std::string group) {
  auto table = NumberTable::read(path, {});
  if (!table) return table.error();
  const NumberTable& t = table.value();
  if (t.columns().size() < 2) return ParseError{path, 1, "header", "expected an abscissa and at least one sensor column"};
  Spectrum s{std::move(group), t.columns()[0], t.values(t.columns()[0]), {}, {}};
  for (std::size_t c = 1; c < t.columns().size(); ++c) {
    s.sensors.push_back(t.columns()[c]);
    s.psd.push_back(t.values(t.columns()[c]));
  }
  return s;
}

}  // namespace

Parsed<NumberTable> NumberTable::read(const std::string& path, std::span<const std::string_view> text_columns) {
  std::ifstream in(path);
  if (!in) return ParseError{path, 0, "", "cannot be opened"};
  NumberTable t;
  t.path_ = path;
  std::string line;
  long number = 0;
  std::vector<bool> is_text;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    auto split_line = split(line);
    if (!split_line) return ParseError{path, number, "", "a quoted field is not closed"};
    std::vector<std::string> fields = std::move(*split_line);
    if (t.columns_.empty()) {
      t.columns_ = std::move(fields);
      for (const std::string& c : t.columns_) {
        is_text.push_back(std::find(text_columns.begin(), text_columns.end(), c) != text_columns.end());
      }
      continue;
    }
    if (fields.size() != t.columns_.size()) {
      return ParseError{path, number, "",
                        std::to_string(fields.size()) + " fields where the header names " + std::to_string(t.columns_.size())};
    }
    for (std::size_t c = 0; c < fields.size(); ++c) {
      double v = std::nan("");
      if (is_text[c]) {
        t.texts_.push_back(std::move(fields[c]));
        t.numbers_.push_back(v);
        continue;
      }
      if (!fields[c].empty() && fields[c] != "nan") {
        const auto parsed = recording::parse_f64(fields[c]);
        if (!parsed) return ParseError{path, number, t.columns_[c], "expected a number, got '" + fields[c] + "'"};
        v = *parsed;
      }
      t.numbers_.push_back(v);
      t.texts_.emplace_back();
    }
    t.lines_.push_back(number);
  }
  if (in.bad()) return ParseError{path, number, "", "could not be read"};
  if (t.columns_.empty()) return ParseError{path, 0, "header", "the file is empty"};
  return t;
}

std::optional<std::size_t> NumberTable::column(std::string_view name) const {
  const auto it = std::find(columns_.begin(), columns_.end(), name);
  if (it == columns_.end()) return std::nullopt;
  return static_cast<std::size_t>(it - columns_.begin());
}

std::vector<double> NumberTable::values(std::string_view name) const {
  std::vector<double> v;
  const auto c = column(name);
  if (!c) return v;
  for (std::size_t r = 0; r < rows(); ++r) v.push_back(at(r, *c));
  return v;
}

Parsed<ResultsDir> read_results_dir(const std::string& dir) {
  constexpr std::string_view kText[] = {"cell",         "surface",    "recording_id",    "vin",
                                        "vehicle_hash", "route_hash", "drive_start_utc", "reason"};
  auto cells = NumberTable::read(dir + "/cells.csv", kText);
  if (!cells) return cells.error();
  if (!cells.value().column("cell") || !cells.value().column("crr")) {
    return ParseError{dir + "/cells.csv", 1, "header", "needs the columns cell and crr"};
  }
  auto trip = read_json_file(dir + "/trip.json");
  if (!trip) return trip.error();
  ResultsDir r{dir, std::move(cells.value()), std::move(trip.value()), {}, {}, {}};
  for (auto [name, slot] : {std::pair{"/gap.json", &r.gap}, std::pair{"/gap-tables.json", &r.gap_tables}}) {
    std::error_code exists_ec;
    if (!std::filesystem::exists(dir + name, exists_ec)) continue;
    auto json = read_json_file(dir + name);
    if (!json) return json.error();
    *slot = std::move(json.value());
  }
  std::vector<std::pair<std::string, std::string>> psd_files;  // group, path
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name == "psd.csv") psd_files.emplace_back("trip", entry.path().string());
    if (name.starts_with("psd-") && !name.starts_with("psd-spatial-") && name.ends_with(".csv")) {
      psd_files.emplace_back(name.substr(4, name.size() - 8), entry.path().string());
    }
  }
  std::sort(psd_files.begin(), psd_files.end(), [](const auto& a, const auto& b) {
    return (a.first != "trip") < (b.first != "trip") || ((a.first != "trip") == (b.first != "trip") && a.first < b.first);
  });
  for (auto& [group, path] : psd_files) {
    auto s = read_spectrum(path, group);
    if (!s) return s.error();
    r.spectra.push_back(std::move(s.value()));
  }
  return r;
}

}  // namespace roadload::results
