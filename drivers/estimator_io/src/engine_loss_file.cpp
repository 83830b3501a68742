#include "roadload/engine_loss_file.hpp"

#include <cmath>
#include <limits>
#include <span>
#include <string_view>

#include "roadload/recording/csv.hpp"
#include "roadload/recording/writer.hpp"

namespace roadload {
namespace {

constexpr std::string_view kLossColumns[] = {"rpm", "loss_nm", "sigma_nm", "friction_nm"};

}  // namespace

Parsed<model::EngineLossMap> load_engine_loss_file(const std::string& path) {
  auto csv = recording::CsvReader::open(path, kLossColumns);
  if (!csv) return csv.error();
  model::EngineLossMap map;
  std::span<const std::string_view> row;
  for (recording::CsvReader::Status st; (st = csv.value().next(row)) != recording::CsvReader::Status::end;) {
    if (st == recording::CsvReader::Status::bad_row) return *csv.value().error();
    double v[4];
    for (std::size_t i = 0; i < 4; ++i) {
      // An empty friction: the calibration could not separate it from the accessories.
      if (i == 3 && row[i].empty()) {
        v[i] = std::numeric_limits<double>::quiet_NaN();
        continue;
      }
      const auto x = recording::parse_f64(row[i]);
      if (!x || !std::isfinite(*x)) return csv.value().field_error(i, "expected a number");
      v[i] = *x;
    }
    if (v[0] < 100 || v[0] > 5000) return csv.value().field_error(0, "outside 100-5000 rpm");
    // An engine's friction and accessories lie within its reference torque (at most 64,255 N m,
    // SPN 544's range), and so does what is known of them.
    if (std::abs(v[1]) > 64255) return csv.value().field_error(1, "outside -64255..64255 N m");
    if (v[2] < 0 || v[2] > 64255) return csv.value().field_error(2, "a standard error must lie in 0..64255 N m");
    if (std::isfinite(v[3]) && std::abs(v[3]) > 64255) return csv.value().field_error(3, "outside -64255..64255 N m");
    if (map.size() == model::EngineLossMap::kCapacity) {
      return csv.value().field_error(0, "more than " + std::to_string(model::EngineLossMap::kCapacity) + " engine speeds");
    }
    if (!map.add({v[0], v[1], v[2], v[3]})) return csv.value().field_error(0, "engine speeds must increase line by line");
  }
  if (csv.value().error()) return *csv.value().error();
  if (map.empty()) return ParseError{path, 0, "rpm", "no engine speed in the table"};
  return map;
}

std::optional<ParseError> write_engine_loss_file(const std::string& path, const std::vector<EngineLossHold>& holds) {
  auto out = recording::OutputFile::create(path);
  if (!out) return out.error();
  out.value().write("# Engine losses (friction + accessories) measured standing in neutral: roadload calibrate\n");
  out.value().write("rpm,loss_nm,sigma_nm,friction_nm,eec3_loss_nm,eec3_friction_nm,hold_s,samples\n");
  recording::LineBuilder line;
  for (const EngineLossHold& h : holds) {
    line.clear();
    line.num(h.point.rpm, 1).sep().num(h.point.loss_nm, 3).sep().num(h.point.sigma_nm, 3).sep();
    line.num(h.point.friction_nm, 3).sep().num(h.eec3_loss_nm, 3).sep().num(h.eec3_friction_nm, 3).sep();
    line.num(h.duration_s, 1).sep().num(static_cast<std::int64_t>(h.samples));
    out.value().write(line.finish());
  }
  return out.value().close();
}

}  // namespace roadload
