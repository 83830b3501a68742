// roadload calibrate: the engine's losses (friction + accessories) by engine speed, from a recording
// of the truck standing in neutral while the engine is held at a series of speeds. Written as the
// table `roadload analyze --engine-losses` uses in place of EEC3's whole percent.
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "calibrate_aero.hpp"
#include "command.hpp"
#include "files.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/cli/values.hpp"
#include "roadload/engine_loss_calibration.hpp"
#include "roadload/engine_loss_file.hpp"
#include "roadload/recording/reader.hpp"

namespace roadload::cli {
namespace {

const HelpText kCalibrateHelp{
    "usage: roadload calibrate RECORDING... --out FILE [options]\n"
    "       roadload calibrate --aero SLOW FAST [SLOW FAST ...] --route ROUTE [--route ROUTE ...]\n"
    "                          --engine-losses FILE [--out FILE]\n"
    "       roadload calibrate --torque-scale POWERED COAST [POWERED COAST ...] --route ROUTE\n"
    "                          [--route ROUTE ...] --engine-losses FILE\n"
    "                          [--cda M2 --cda-sigma M2 --cda-per-torque-scale M2] [--out FILE]",
    "Measures the engine's own losses, friction plus the accessories it drives, at each engine speed\n"
    "the recordings hold steady while the truck stands in neutral (wheel speed below 0.1 m/s; ETC2\n"
    "current gear neutral, or ETC1 driveline disengaged). Nothing then reaches the flywheel, so EEC1's\n"
    "indicated torque (SPN 513 with its 1/8 % fraction, SPN 4154) is those losses. EEC3 states them in\n"
    "whole percent of the reference torque (SPN 514, 2978): at one cruise speed its rounding is a\n"
    "constant flywheel torque error of up to 1 % (24 N m on the MnROAD engine, 0.0005 in CRR in 8th\n"
    "gear), which this table removes. Hold each speed for 10 s or more; the first 3 s of a hold are\n"
    "the governor's approach and are left out. `roadload simulate --scenario engine-losses` drives such\n"
    "a calibration.\n\n"
    "--aero measures the truck's CdA from two drives over the same route's cells at two speeds (the\n"
    "report's Mainline runs at 30 and 64 mph): a pavement's CRR is the same at both, the drag is not, so\n"
    "the CdA that makes each cell's CRR agree is the truck's. At one speed the force balance cannot tell\n"
    "them apart, and CdA's prior (the vehicle file's, the type's spread) is then most of each cell's\n"
    "interval. The engine-loss table is required: EEC3's rounding differs between the two engine speeds\n"
    "and would be fitted as drag. More pairs (the road's other direction on its own route, another day)\n"
    "give one CdA from all their cells: give one --route per pair, in order, or one for every pair.\n"
    "Prints the CdA with its standard error as `roadload analyze` options; --out writes them as CSV.\n\n"
    "--torque-scale measures the ECU's torque scale (EEC1's indicated torque against the engine's true\n"
    "one; J1939 states it to a few percent) from a powered drive and a coast-down in neutral over the\n"
    "same cells. The coast-down's CRR owes nothing to the engine's torque; the powered drive's moves with\n"
    "the scale by the tractive force over the weight, so the scale at which each cell's CRRs agree is the\n"
    "ECU's. Coast from cruise speed in neutral (ETC2 current gear 0) over the cells the powered drive\n"
    "crossed; a scenario with mode = \"coast\" simulates one (coast-down-65mph on the flat track). The\n"
    "drag both drives meet at other speeds passes CdA's error into the scale: give the CdA `--aero`\n"
    "measured, with its sigma and its slope per unit of scale, and the two are solved together. Prints\n"
    "the scale with its standard error as `roadload analyze` options; --out writes them as CSV."};

struct CalibrateOptions {
  std::vector<std::string> recordings, dbcs;
  std::string out;
  bool quiet = false, aero = false, scale = false;
  AeroOptions ao;
};

void add_options(CLI::App& cmd, CalibrateOptions& o) {
  cmd.add_option("RECORDING", o.recordings, "recording folders: standing holds, or the drives in pairs")->required();
  cmd.add_flag("--aero", o.aero, "measure CdA from pairs of drives at two speeds");
  cmd.add_flag("--torque-scale", o.scale, "measure the ECU's torque scale from pairs of a powered drive and a\ncoast-down");
  cmd.add_option("-o,--out", o.out, "write FILE: rpm,loss_nm,sigma_nm,eec3_loss_nm,hold_s,samples, one line\nper hold")
      ->type_name("FILE");
  cmd.add_option("--route", o.ao.routes,
                 "(--aero, --torque-scale) route file or built-in route name: the cells\n"
                 "both drives cross; repeatable, one per pair")
      ->type_name("R");
  cmd.add_option("--engine-losses", o.ao.engine_losses, "(--aero, --torque-scale) the engine-loss table of the same truck")
      ->type_name("FILE");
  cmd.add_option("--cda", o.ao.cda_prior_m2,
                 "(--aero, --torque-scale) the CdA the drives are analysed with\n"
                 "(default: the vehicle file's); the CdA fit does not depend on it\n"
                 "beyond linearity")
      ->type_name("M2")
      ->check(real_in(0.5, 30));
  cmd.add_option("--cda-sigma", o.ao.cda_sigma_m2, "(--torque-scale) that CdA's standard error, carried into the scale's\nsigma")
      ->type_name("M2")
      ->check(real_in(0.0001, 10));
  cmd.add_option("--cda-per-torque-scale", o.ao.cda_per_torque_scale_m2,
                 "(--torque-scale) how that CdA moves with the scale, as --aero prints\n"
                 "it: the scale and the CdA are then solved together")
      ->type_name("M2")
      ->check(real_in(-100, 100));
  cmd.add_option("--vehicle", o.ao.vehicle,
                 "(--aero, --torque-scale) vehicle file or built-in name (default: the one\neach recording carries)")
      ->type_name("V");
  cmd.add_option("--dbc", o.dbcs, "load FILE after the built-in definitions; repeatable")->type_name("FILE");
  cmd.add_flag("-q,--quiet", o.quiet, "no table on standard output");
}

// Feeds every frame of one recording to the calibration; an exit code when it cannot be read.
std::optional<int> read_recording(const std::string& path, EngineLossFrames& cal) {
  auto reader = recording::RecordingReader::open(path);
  if (!reader) {
    std::fprintf(stderr, "roadload calibrate: %s\n", reader.error().to_string().c_str());
    return kExitNoInput;
  }
  while (const recording::Record* r = reader.value().next()) {
    if (const auto* frame = std::get_if<CanFrame>(r)) cal.push(*frame);
  }
  const recording::ErrorLog& errors = reader.value().errors();
  for (const ParseError& e : errors.kept()) std::fprintf(stderr, "roadload calibrate: %s\n", e.to_string().c_str());
  return std::nullopt;
}

void print_holds(const std::vector<EngineLossHold>& holds) {
  std::printf("%8s %10s %9s %12s %12s %12s %7s\n", "rpm", "loss N m", "sigma", "friction", "EEC3 N m", "EEC3 error", "hold s");
  for (const EngineLossHold& h : holds) {
    std::printf("%8.1f %10.2f %9.2f %12.2f %12.2f %+12.2f %7.1f\n", h.point.rpm, h.point.loss_nm, h.point.sigma_nm,
                h.point.friction_nm, h.eec3_loss_nm, h.eec3_loss_nm - h.point.loss_nm, h.duration_s);
  }
}

// The drive-pair calibrations' own rules; a usage exit when one is broken.
std::optional<int> check_pairs(bool aero, std::size_t recordings, const AeroOptions& ao) {
  const std::string mode = aero ? "--aero" : "--torque-scale";
  const char* pair = aero ? "one at each of two speeds" : "a powered drive and then a coast-down";
  if (ao.routes.empty()) return usage_error("calibrate", mode + " needs --route");
  if (recordings % 2 != 0) return usage_error("calibrate", mode + " takes drives in pairs, " + pair);
  if (ao.routes.size() != 1 && ao.routes.size() != recordings / 2)
    return usage_error("calibrate", mode + " takes one --route, or one per pair of drives");
  if (ao.engine_losses.empty()) return usage_error("calibrate", mode + " needs --engine-losses (roadload calibrate, standing)");
  return std::nullopt;
}

// The engine-loss table from standing holds.
int run_engine_losses(const std::vector<std::string>& recordings, const std::string& out, bool quiet, const j1939::Database& db) {
  EngineLossFrames cal(db);
  for (const std::string& r : recordings) {
    if (auto rc = read_recording(r, cal)) return *rc;
  }
  const std::vector<EngineLossHold> holds = cal.finish();
  if (holds.empty()) {
    std::fprintf(stderr,
                 "roadload calibrate: %s: no steady engine speed standing in neutral (%" PRIu64 " EEC1 readings, %" PRIu64
                 " standing in neutral, %" PRIu64 " before EC1's reference torque): nothing written\n",
                 recordings.front().c_str(), cal.readings, cal.standing, cal.no_reference);
    return kExitDataErr;
  }
  if (holds.size() > model::EngineLossMap::kCapacity) {
    std::fprintf(stderr, "roadload calibrate: %zu holds, more than the %zu engine speeds a table keeps\n", holds.size(),
                 model::EngineLossMap::kCapacity);
    return kExitDataErr;
  }
  if (auto err = write_engine_loss_file(out, holds)) {
    std::fprintf(stderr, "roadload calibrate: %s\n", err->to_string().c_str());
    return kExitCantCreate;
  }
  if (!quiet) print_holds(holds);
  if (std::isnan(holds.front().point.friction_nm)) {
    std::fprintf(stderr,
                 "roadload calibrate: EEC3's friction steps fewer than three times over these speeds: the accessories "
                 "keep EEC3's parasitic share\n");
  }
  std::fprintf(stderr, "roadload calibrate: %zu engine speeds from %.0f to %.0f rpm, torque to %s %% -> %s\n", holds.size(),
               holds.front().point.rpm, holds.back().point.rpm, cal.whole_percent ? "whole" : "1/8", out.c_str());
  return kExitOk;
}

int calibrate(CalibrateOptions& o) {
  if (o.aero && o.scale) return usage_error("calibrate", "--aero and --torque-scale are separate calibrations");
  if (o.aero || o.scale) {
    if (auto rc = check_pairs(o.aero, o.recordings.size(), o.ao)) return *rc;
  } else if (o.out.empty()) {
    return usage_error("calibrate", "--out is required");
  }
  j1939::Database db;
  if (auto rc = load_definitions("calibrate", o.dbcs, db)) return *rc;
  if (!o.aero && !o.scale) return run_engine_losses(o.recordings, o.out, o.quiet, db);
  o.ao.recordings = o.recordings;
  o.ao.out = o.out;
  return o.aero ? run_calibrate_aero(o.ao, db) : run_calibrate_torque_scale(o.ao, db);
}

}  // namespace

Run add_calibrate(CLI::App& roadload) {
  auto o = std::make_shared<CalibrateOptions>();
  CLI::App& cmd = *roadload.add_subcommand(
      "calibrate", "measure the engine's losses by engine speed standing in neutral (replaces EEC3's whole percent)");
  describe(cmd, kCalibrateHelp);
  add_options(cmd, *o);
  return [o] { return calibrate(*o); };
}

}  // namespace roadload::cli
