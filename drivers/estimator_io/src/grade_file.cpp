#include "roadload/grade_file.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "roadload/recording/csv.hpp"
#include "roadload/recording/writer.hpp"

namespace roadload {
namespace {

constexpr std::string_view kGradeColumns[] = {"s_m", "elevation_m", "elevation_sigma_m", "grade_pct", "grade_sigma_pct", "passes"};

constexpr std::string_view kBaseKey = "# slope_base_m = ";
constexpr std::string_view kCorrelationKey = "# error_correlation_m = ";

// A value from the file's leading comments; files written before a key existed carry none.
std::optional<double> header_value(const std::string& path, std::string_view key) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && !line.empty() && line[0] == '#') {
    if (line.rfind(key, 0) != 0) continue;
    const auto v = recording::parse_f64(std::string_view(line).substr(key.size()));
    if (v && *v > 0 && *v < 1e4) return *v;
  }
  return std::nullopt;
}

std::optional<double> field(std::string_view text) {
  if (text.empty()) return std::numeric_limits<double>::quiet_NaN();
  return recording::parse_f64(text);
}

}  // namespace

Parsed<GradeProfile> load_grade_file(const std::string& path, double route_length_m) {
  auto csv = recording::CsvReader::open(path, kGradeColumns);
  if (!csv) return csv.error();
  std::vector<GradeBin> bins;
  std::span<const std::string_view> row;
  for (recording::CsvReader::Status st; (st = csv.value().next(row)) != recording::CsvReader::Status::end;) {
    if (st == recording::CsvReader::Status::bad_row) return *csv.value().error();
    std::optional<double> v[6];
    for (std::size_t i = 0; i < 6; ++i) {
      v[i] = field(row[i]);
      if (!v[i] || (i == 0 && std::isnan(*v[i]))) return csv.value().field_error(i, "expected a number");
    }
    GradeBin b;
    b.s_m = *v[0];
    b.elevation_m = *v[1];
    b.elevation_sigma_m = *v[2];
    b.grade_rad = std::atan(*v[3] / 100.0);
    b.grade_sigma_rad = *v[4] / 100.0;
    b.passes = std::isnan(*v[5]) || *v[5] < 0 ? 0 : static_cast<std::size_t>(*v[5]);
    bins.push_back(b);
  }
  if (csv.value().error()) return *csv.value().error();
  const double base_m = header_value(path, kBaseKey).value_or(GradeConfig{}.base_m);
  const double correlation_m = header_value(path, kCorrelationKey).value_or(std::numeric_limits<double>::quiet_NaN());
  auto profile = GradeProfile::from_bins(route_length_m, std::move(bins), base_m, correlation_m);
  if (!profile) {
    return ParseError{path, 0, "s_m", "bins are not evenly spaced along this route (" + std::to_string(route_length_m) + " m long)"};
  }
  return std::move(*profile);
}

std::optional<ParseError> write_grade_file(const std::string& path, const GradeProfile& profile) {
  auto csv = recording::OutputFile::create(path);
  if (!csv) return csv.error();
  recording::LineBuilder base;
  base.num(profile.config().base_m, 1);
  csv.value().write(std::string(kBaseKey) + std::string(base.finish()));
  if (const double l = profile.measured_error_correlation_m(); std::isfinite(l)) {
    recording::LineBuilder correlation;
    correlation.num(l, 1);
    csv.value().write(std::string(kCorrelationKey) + std::string(correlation.finish()));
  }
  csv.value().write("s_m,elevation_m,elevation_sigma_m,grade_pct,grade_sigma_pct,passes\n");
  recording::LineBuilder line;
  for (const GradeBin& b : profile.bins()) {
    line.clear();
    line.num(b.s_m, 1).sep().num(b.elevation_m, 3).sep().num(b.elevation_sigma_m, 3).sep();
    line.num(100 * std::tan(b.grade_rad), 4).sep().num(100 * b.grade_sigma_rad, 4).sep();
    line.num(static_cast<std::int64_t>(b.passes));
    csv.value().write(line.finish());
  }
  return csv.value().close();
}

}  // namespace roadload
