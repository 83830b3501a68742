#include <CLI/CLI.hpp>

#include "roadload/analysis/analyze.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/cli/values.hpp"

namespace roadload::analysis {
namespace {

using cli::describe;
using cli::HelpText;
using cli::real_in;

const HelpText kHelp{"usage: roadload analyze <recording>... --out RESULTS [--route ROUTE] [options]",
                     "Estimates the coefficient of rolling resistance (CRR) along the drive and per pavement cell:\n"
                     "the J1939 force balance (EEC1, EEC3, EC1, ETC2, CCVS1) in an EKF over speed, CRR, CdA, a\n"
                     "torque bias and the speed's ripple from the road's roughness (the route's IRI per cell), with\n"
                     "grade from the route's survey, air from the weather station, position from GNSS and odometry,\n"
                     "then a fixed-interval smoother so each cell uses data on both sides of it.\n"
                     "Per cell also: the fuel breakdown (engine, driveline, accessories, aero, rolling, grade,\n"
                     "acceleration, braking; litres at 35.8 MJ/L) and, from the accelerometers, the contact force\n"
                     "per axle (report Eq. 2.1) and the power the dampers and tires dissipate (dynamic rolling\n"
                     "resistance, Eq. 2.7-2.8; the vehicle file's dampers and tire damping). Per pavement group\n"
                     "(surface and panel length): PSDs, vibration modes and the concrete joint line."};

// The road and the files beside the recording.
void add_inputs(CLI::App& cmd, AnalyzeOptions& o) {
  cmd.add_option("RECORDING", o.recordings,
                 "the recording folder; several: the segments of one roadloadd run,\nread as one drive (in any order)")
      ->required();
  cmd.add_option("--route", o.route,
                 "route file or built-in route name (config/routes): geometry, grade,\n"
                 "cells, IRI; without it the drive's own GNSS traces the road (cells of\n"
                 "250 m, grade from that one pass with its error: wide intervals), and\n"
                 "without GNSS nothing is placed")
      ->type_name("R");
  cmd.add_option("-o,--out", o.out,
                 "write DIR/cells.csv (cell,crr,crr_lo,crr_hi,... 90 % interval; fuel\n"
                 "breakdown per cell in litres; damper_power_w,tire_power_w,...),\n"
                 "DIR/pavements.csv (the same per pavement type, with the rolling\n"
                 "resistance's L/100 km), DIR/trip.json (with the provenance), and\n"
                 "the PSDs: DIR/psd.csv (trip) and DIR/psd-<group>.csv (freq_hz, one\n"
                 "column per accelerometer, (m/s^2)^2/Hz),\n"
                 "DIR/psd-spatial-<group>.csv (cycles_per_m, per cycle/m)")
      ->type_name("DIR")
      ->required();
  cmd.add_option("--truth", o.truth_dir,
                 "a simulation's ground truth: the true CRR beside each cell, RMSE and\n"
                 "coverage, and the true fuel breakdown beside the estimate")
      ->type_name("DIR");
  cmd.add_option("--grade", o.grade_file, "grade and its sigma from FILE (`roadload grade`) instead of the\nroute's survey")
      ->type_name("FILE");
  cmd.add_option("--engine-losses", o.losses_file,
                 "the engine's friction + accessories by engine speed (`roadload\n"
                 "calibrate`) instead of EEC3's whole percent; engine speeds outside it\n"
                 "are not used")
      ->type_name("FILE");
  cmd.add_option("--survey-sigma", o.survey_sigma,
                 "the route survey's height error, carried into the force balance\n(default 0: the survey taken as exact)")
      ->type_name("M")
      ->check(real_in(0, 10));
  cmd.add_option("--dbc", o.dbcs, "load FILE after the built-in definitions; repeatable")->type_name("FILE");
  cmd.add_flag("-q,--quiet", o.quiet, "no table on standard output");
}

// The truck: its vehicle file, its mass, and what calibrations measured of it.
void add_truck(CLI::App& cmd, AnalyzeOptions& o) {
  cmd.add_option("--vehicle", o.vehicle,
                 "vehicle file or built-in name (config/vehicles): the truck's force\n"
                 "balance, axles and priors (default: the vehicle file the recording's\n"
                 "meta.toml carries; a recording that describes no truck is analysed as\n"
                 "the default vehicle and nothing is identified)")
      ->type_name("V");
  cmd.add_option("--mass", o.mass, "vehicle mass (default: meta.toml vehicle.mass_kg, else the vehicle\nfile's axle loads)")
      ->type_name("KG")
      ->check(real_in(1000, 200000));
  cmd.add_flag("--estimate-cda", o.estimate_cda, "fit CdA from the drive (drives across speeds); otherwise CdA keeps its\nprior");
  cmd.add_option("--cda", o.cda_m2,
                 "CdA's prior (default: the vehicle file's, the type's value); a\n"
                 "measured value, for example `roadload calibrate --aero`")
      ->type_name("M2")
      ->check(real_in(0.5, 30));
  cmd.add_option("--cda-sigma", o.cda_sigma_m2, "that prior's standard error (default: the vehicle file's, the type's\nspread)")
      ->type_name("M2")
      ->check(real_in(0.0001, 10));
  cmd.add_option("--cda-torque-correlation", o.cda_torque_correlation,
                 "between that CdA's error and the flywheel torque's (-1..1; what\n"
                 "`roadload calibrate --aero` prints: its CdA took up the engine-loss\n"
                 "table's error)")
      ->type_name("R")
      ->check(real_in(-1, 1));
  cmd.add_option("--cda-per-torque-scale", o.cda_per_torque_scale_m2,
                 "how that CdA moves with the ECU's torque scale (what `roadload\n"
                 "calibrate --aero` prints): the scale's second run moves CdA with it")
      ->type_name("M2")
      ->check(real_in(-100, 100));
  cmd.add_option("--torque-scale", o.torque_scale,
                 "the ECU's torque scale (true = EEC1's x (1 + K)), as `roadload\n"
                 "calibrate --torque-scale` measures it (default 0); the CdA moves with K\n"
                 "as --cda-per-torque-scale says")
      ->type_name("K")
      ->check(real_in(-0.5, 0.5));
  cmd.add_option("--torque-scale-sigma", o.torque_scale_sigma,
                 "that scale's standard error (default: the vehicle file's prior sigma)")
      ->type_name("S")
      ->check(real_in(0, 0.5));
}

}  // namespace

void add_options(CLI::App& cmd, AnalyzeOptions& o) {
  describe(cmd, kHelp);
  add_inputs(cmd, o);
  add_truck(cmd, o);
}

}  // namespace roadload::analysis
