// roadload analyze: CRR per pavement cell from a recording (the force balance in an EKF, then a
// fixed-interval smoother), written as RESULTS/cells.csv and RESULTS/trip.json.
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "command.hpp"
#include "options.hpp"
#include "roadload/definitions.hpp"
#include "roadload/drive_analyzer.hpp"
#include "roadload/recording/csv.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/recording/writer.hpp"
#include "roadload/route_file.hpp"

namespace roadload::cli {
namespace {

constexpr const char* kHelp =
    "usage: roadload analyze <recording> --route ROUTE --out RESULTS [options]\n\n"
    "Estimates the coefficient of rolling resistance (CRR) along the drive and per pavement cell:\n"
    "the J1939 force balance (EEC1, EEC3, EC1, ETC2, CCVS1) in an EKF over speed, CRR and CdA, with\n"
    "grade from the route's survey, air from the weather station, position from GNSS and odometry,\n"
    "then a fixed-interval smoother so each cell uses data on both sides of it.\n\n"
    "  --route R       route file or built-in route name (config/routes): geometry, grade and cells\n"
    "  --out DIR       write DIR/cells.csv (cell,crr,crr_lo,crr_hi,... 90 % interval) and DIR/trip.json\n"
    "  --truth DIR     a simulation's ground truth: print the true CRR beside each cell, RMSE and coverage\n"
    "  --mass KG       vehicle mass (default: meta.toml vehicle.mass_kg, else 36152)\n"
    "  --dbc FILE      load FILE after the built-in definitions; repeatable\n"
    "  -q, --quiet     no table on standard output\n"
    "  -h, --help      this text\n";

std::string resolve_route(const std::string& r) {
  if (std::filesystem::exists(r)) return r;
  return data_dir() + "/routes/" + r + ".toml";
}

// The true CRR per cell of a simulation's truth/cells.csv. A bad row makes the comparison
// meaningless, so it stops the read with its file, line and field.
Parsed<std::map<std::string, double>> read_truth(const std::string& dir) {
  constexpr std::string_view kColumns[] = {"cell", "crr"};
  auto csv = recording::CsvReader::open(dir + "/cells.csv", kColumns);
  if (!csv) return csv.error();
  std::map<std::string, double> crr;
  std::span<const std::string_view> row;
  for (recording::CsvReader::Status st; (st = csv.value().next(row)) != recording::CsvReader::Status::end;) {
    if (st == recording::CsvReader::Status::bad_row) return *csv.value().error();
    const auto value = recording::parse_f64(row[1]);
    if (!value) return csv.value().field_error(1, "expected a number");
    crr[std::string(row[0])] = *value;
  }
  if (csv.value().error()) return *csv.value().error();
  return crr;
}

}  // namespace

int run_analyze(Args args) {
  OptionParser opt("analyze", args);
  std::string recording, route_name, out, truth_dir;
  std::optional<double> mass;
  std::vector<std::string> dbcs;
  bool quiet = false;
  while (opt.more()) {
    if (opt.flag("-h", "--help")) {
      std::fputs(kHelp, stdout);
      return kExitOk;
    }
    if (opt.flag("-q", "--quiet")) {
      quiet = true;
    } else if (auto r = opt.value("--route")) {
      route_name = *r;
    } else if (auto o = opt.value("--out")) {
      out = *o;
    } else if (auto t = opt.value("--truth")) {
      truth_dir = *t;
    } else if (auto m = opt.real("--mass", 1000, 200000)) {
      mass = *m;
    } else if (auto d = opt.value("--dbc")) {
      dbcs.emplace_back(*d);
    } else if (auto p = opt.positional()) {
      recording = *p;
    } else if (!opt.failed()) {
      return opt.fail_unknown();
    }
  }
  if (opt.failed()) return kExitUsage;
  if (recording.empty()) return opt.fail("a recording is required");
  if (route_name.empty()) return opt.fail("--route is required");
  if (out.empty()) return opt.fail("--out is required");

  j1939::Database db;
  dbcs.insert(dbcs.begin(), core_dbc_path());
  for (const std::string& path : dbcs) {
    if (auto err = load_dbc_file(db, path)) {
      std::fprintf(stderr, "roadload analyze: %s\n", err->to_string().c_str());
      return kExitNoInput;
    }
  }
  auto route = load_route_file(resolve_route(route_name));
  if (!route) {
    std::fprintf(stderr, "roadload analyze: %s\n", route.error().to_string().c_str());
    return kExitNoInput;
  }
  auto geometry = RouteGeometry::build(route.value().points);
  if (!geometry) {
    std::fprintf(stderr, "roadload analyze: %s: point: fewer than two distinct points\n", route.value().source_file.c_str());
    return kExitDataErr;
  }
  auto reader = recording::RecordingReader::open(recording);
  if (!reader) {
    std::fprintf(stderr, "roadload analyze: %s\n", reader.error().to_string().c_str());
    return kExitNoInput;
  }
  AnalyzerConfig cfg;
  const auto& vehicle = reader.value().metadata().vehicle;
  if (mass) {
    cfg.filter.truck.mass_kg = *mass;
  } else if (auto it = vehicle.find("mass_kg"); it != vehicle.end()) {
    cfg.filter.truck.mass_kg = it->second;
  }
  // Place the centre of gravity and the GNSS antenna from the recorded axle layout when given.
  double moment = 0, load = 0;
  std::vector<AxleLoad> axles;
  for (const char* axle : {"front", "drive1", "drive2", "trailer1", "trailer2"}) {
    const auto l = vehicle.find(std::string(axle) + "_load_kg");
    const auto x = vehicle.find(std::string(axle) + "_position_m");
    if (l != vehicle.end() && x != vehicle.end()) {
      moment += l->second * x->second;
      load += l->second;
      axles.push_back({x->second, l->second});
    }
  }
  if (load > 0) {
    cfg.cg_behind_front_m = moment / load;
    cfg.axles = axles;
  }
  if (auto it = vehicle.find("gnss_antenna_behind_front_axle_m"); it != vehicle.end()) cfg.antenna_behind_front_m = it->second;

  std::vector<CellSpan> cells;
  for (const CellDef& c : route.value().cells) cells.push_back({c.id, c.start_m, c.end_m});
  DriveAnalyzer analyzer(db, std::move(*geometry), cells, cfg);
  while (const recording::Record* r = reader.value().next()) {
    std::visit([&](const auto& s) {
      using T = std::decay_t<decltype(s)>;
      if constexpr (!std::is_same_v<T, AccelSample>) analyzer.push(s);
    }, *r);
  }
  for (const auto& e : reader.value().errors().kept()) std::fprintf(stderr, "roadload analyze: %s\n", e.to_string().c_str());
  analyzer.finish();
  const std::vector<CellResult> results = analyzer.cells();
  const TripResult trip = analyzer.trip();

  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  auto csv = recording::OutputFile::create(out + "/cells.csv");
  if (!csv) {
    std::fprintf(stderr, "roadload analyze: %s\n", csv.error().to_string().c_str());
    return kExitNoInput;
  }
  csv.value().write("cell,start_m,end_m,samples,crr,crr_lo,crr_hi,crr_sigma,identified,speed_mps,roll_force_n,reason\n");
  recording::LineBuilder line;
  for (const CellResult& c : results) {
    line.clear();
    line.text(c.id).sep().num(c.start_m, 1).sep().num(c.end_m, 1).sep().num(static_cast<std::int64_t>(c.samples)).sep();
    const double nan = std::nan("");
    const bool have = c.samples > 0;
    line.num(have ? c.crr : nan, 6).sep().num(have ? c.crr_lo : nan, 6).sep().num(have ? c.crr_hi : nan, 6).sep();
    line.num(have ? c.crr_sigma : nan, 6).sep().num(std::int64_t{c.identified ? 1 : 0}).sep();
    line.num(have ? c.speed_mps : nan, 3).sep().num(have ? c.roll_force_n : nan, 1).sep().text(c.reason);
    csv.value().write(line.finish());
  }
  if (auto e = csv.value().close()) {
    std::fprintf(stderr, "roadload analyze: %s\n", e->to_string().c_str());
    return kExitDataErr;
  }
  std::ofstream json(out + "/trip.json");
  json << "{\n  \"crr\": " << trip.crr << ",\n  \"crr_sigma\": " << trip.crr_sigma << ",\n  \"crr_identified\": "
       << (trip.identified ? "true" : "false") << ",\n  \"cda_m2\": " << trip.cda_m2 << ",\n  \"ticks\": " << trip.ticks
       << ",\n  \"usable_ticks\": " << trip.usable_ticks << ",\n  \"unusable\": {";
  for (std::size_t i = 1; i < trip.unusable.size(); ++i) {
    json << (i > 1 ? ", " : "") << "\"" << to_string(static_cast<Unusable>(i)) << "\": " << trip.unusable[i];
  }
  json << "},\n  \"gnss_used\": " << trip.gnss_used << ",\n  \"gnss_off_route\": " << trip.gnss_off_route
       << ",\n  \"speed_outliers\": " << trip.filter.outliers << ",\n  \"mean_nis\": " << trip.filter.mean_nis()
       << ",\n  \"torque_bias_nm\": " << trip.torque_bias_nm << ",\n  \"torque_bias_sigma_nm\": " << trip.torque_bias_sigma_nm
       << "\n}\n";

  std::map<std::string, double> truth;
  if (!truth_dir.empty()) {
    auto t = read_truth(truth_dir);
    if (!t) {
      std::fprintf(stderr, "roadload analyze: %s\n", t.error().to_string().c_str());
      return t.error().line > 0 ? kExitDataErr : kExitNoInput;
    }
    truth = std::move(t.value());
  }
  double se = 0;
  std::size_t n = 0, covered = 0;
  if (!quiet) std::printf("%-6s %9s %9s %9s %7s%s\n", "cell", "crr", "crr_lo", "crr_hi", "samples", truth.empty() ? "" : "     truth  inside");
  for (const CellResult& c : results) {
    const auto t = truth.find(c.id);
    if (!quiet) {
      if (c.samples == 0) {
        std::printf("%-6s %9s %9s %9s %7zu  %s\n", c.id.c_str(), "-", "-", "-", c.samples, c.reason.c_str());
        continue;
      }
      std::printf("%-6s %9.5f %9.5f %9.5f %7zu", c.id.c_str(), c.crr, c.crr_lo, c.crr_hi, c.samples);
      if (t != truth.end()) std::printf("   %7.5f  %s", t->second, t->second >= c.crr_lo && t->second <= c.crr_hi ? "yes" : "no");
      std::printf("\n");
    }
    if (t != truth.end() && c.samples > 0) {
      se += (c.crr - t->second) * (c.crr - t->second);
      covered += t->second >= c.crr_lo && t->second <= c.crr_hi ? 1 : 0;
      ++n;
    }
  }
  std::fprintf(stderr, "analyze: trip CRR %.5f +- %.5f (%s), CdA %.2f m^2, %zu of %zu ticks usable\n", trip.crr,
               trip.crr_sigma, trip.identified ? "identified" : "NOT identified", trip.cda_m2, trip.usable_ticks, trip.ticks);
  if (n > 0) {
    std::fprintf(stderr, "analyze: against the truth: RMSE %.5f over %zu cells, 90 %% intervals cover %zu (%.0f %%)\n",
                 std::sqrt(se / static_cast<double>(n)), n, covered, 100.0 * static_cast<double>(covered) / static_cast<double>(n));
  }
  return kExitOk;
}

}  // namespace roadload::cli
