#include "roadload/results/truth_files.hpp"

#include <array>
#include <span>
#include <string_view>

#include "roadload/recording/csv.hpp"
#include "roadload/toml_fields.hpp"

namespace roadload::results {
namespace {

Parsed<Truth> read_truth_cells(const std::string& path) {
  constexpr std::string_view kColumns[] = {"cell", "crr", "damper_power_w", "tire_power_w", "time_s"};
  auto csv = recording::CsvReader::open(path, kColumns);
  if (!csv) return csv.error();
  Truth t;
  std::span<const std::string_view> row;
  for (recording::CsvReader::Status st; (st = csv.value().next(row)) != recording::CsvReader::Status::end;) {
    if (st == recording::CsvReader::Status::bad_row) return *csv.value().error();
    std::array<double, 4> v{};
    for (std::size_t i = 0; i < v.size(); ++i) {
      const auto value = recording::parse_f64(row[i + 1]);
      if (!value) return csv.value().field_error(i + 1, "expected a number");
      v[i] = *value;
    }
    const std::string cell(row[0]);
    t.crr[cell] = v[0];
    t.damper_w[cell] = v[1];
    t.tire_w[cell] = v[2];
    t.time_s[cell] = v[3];
  }
  if (csv.value().error()) return *csv.value().error();
  return t;
}

Parsed<std::map<std::string, double>> read_truth_energy(const std::string& path) {
  std::map<std::string, double> energy;
  auto parsed = detail::parse_toml_file(path);
  if (!parsed) return parsed.error();
  const toml::table* section = parsed.value()["fuel_breakdown"].as_table();
  if (section == nullptr) return energy;
  const detail::TomlFields f(path);
  try {
    for (const auto& [key, node] : *section)
      energy[std::string(key.str())] = f.required_number(*section, key.str(), "fuel_breakdown.");
  } catch (const detail::TomlFailure& e) {
    return e.error;
  }
  return energy;
}

}  // namespace

Parsed<Truth> read_truth(const std::string& dir) {
  auto cells = read_truth_cells(dir + "/cells.csv");
  if (!cells) return cells.error();
  Truth t = std::move(cells.value());
  auto energy = read_truth_energy(dir + "/truth.toml");
  if (!energy) return energy.error();
  t.energy_j = std::move(energy.value());
  return t;
}

}  // namespace roadload::results
