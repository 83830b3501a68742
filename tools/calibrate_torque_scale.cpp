// roadload calibrate --torque-scale: the ECU's torque scale from pairs of a powered drive and a
// coast-down in neutral over the same route's cells (estimator/torque_scale_calibration.hpp),
// printed as the options `roadload analyze` takes.
#include <cstdio>
#include <variant>
#include <vector>

#include "calibrate_aero.hpp"
#include "files.hpp"
#include "roadload/recording/writer.hpp"
#include "roadload/torque_scale_calibration.hpp"

namespace roadload::cli {
namespace {

// Without a prior sigma in the vehicle file, the scale's run steps this far: J1939 states EEC1's
// torque to a few percent, and the fit is linear in it.
constexpr double kDefaultScaleStep = 0.05;

int write_fit(const std::string& path, const TorqueScaleCalibration& fit) {
  recording::LineBuilder line;
  line.num(fit.scale, 5).sep().num(fit.sigma, 5).sep().num(fit.statistical, 5).sep().num(fit.cda, 5).sep().num(fit.torque, 5).sep();
  line.num(fit.mass, 5).sep();
  line.num(static_cast<std::int64_t>(fit.cells)).sep().num(fit.chi2_per_dof, 3).sep().num(fit.residual_correlation, 3).sep();
  line.num(fit.scale_per_cda_m2, 5).sep().num(fit.scale_per_torque_nm, 6).sep().num(fit.cda_shift_m2, 4);
  return write_fit_csv(path,
                       "torque_scale,torque_scale_sigma,statistical,cda,torque,mass,cells,chi2_per_dof,residual_correlation,"
                       "scale_per_cda_m2,scale_per_torque_nm,cda_shift_m2\n",
                       line.finish());
}

}  // namespace

int run_calibrate_torque_scale(const AeroOptions& options, const j1939::Database& db) {
  AeroOptions o = options;
  if (!(o.scale_step > 0)) o.scale_step = kDefaultScaleStep;
  o.runs = AeroRuns::with_mass;
  auto analysed = calibration_drives(o, db);
  if (const int* rc = std::get_if<int>(&analysed)) return *rc;
  const CalibrationDrives& d = std::get<CalibrationDrives>(analysed);
  std::vector<ScalePair> pairs;
  for (std::size_t k = 0; k + 1 < d.drives.size(); k += 2) pairs.push_back({&d.drives[k], &d.drives[k + 1]});
  TorqueScaleCalibration fit = fit_torque_scale(pairs, d.cda_sigma_m2, d.torque_sigma_nm);
  if (fit.cells > 0 && o.cda_per_torque_scale_m2) {
    const double slope = fit.scale_per_cda_m2;
    fit = with_aero_coupling(fit, *o.cda_per_torque_scale_m2);
    if (fit.cells == 0) {
      std::fprintf(stderr,
                   "roadload calibrate: the scale moves %.4f per m^2 of CdA and the CdA %.3f m^2 per unit of scale: these "
                   "drives cannot tell the torque scale from the drag; coast at another speed than the powered drive: "
                   "nothing written\n",
                   slope, *o.cda_per_torque_scale_m2);
      return kExitDataErr;
    }
  }
  if (fit.cells == 0) {
    std::fprintf(stderr,
                 "roadload calibrate: %s and %s: fewer than two cells estimated in both, or the powered drive's cells "
                 "move too little with the scale: nothing written\n",
                 o.recordings[0].c_str(), o.recordings[1].c_str());
    return kExitDataErr;
  }
  if (!o.out.empty()) {
    if (const int rc = write_fit(o.out, fit); rc != kExitOk) return rc;
  }
  std::printf(
      "torque scale %+.4f +- %.4f (cells' scatter %.4f, CdA %.4f, flywheel torque %.4f, mass %.4f) from %zu cells, "
      "chi2/dof %.2f, neighbours' correlation %.2f; CdA %.2f +- %.2f m^2 held\n",
      fit.scale, fit.sigma, fit.statistical, fit.cda, fit.torque, fit.mass, fit.cells, fit.chi2_per_dof, fit.residual_correlation,
      d.cda_prior_m2, d.cda_sigma_m2);
  if (o.cda_per_torque_scale_m2) {
    std::printf("CdA at that scale %.3f m^2 (%.3f at a scale of 0, %+.3f per unit of scale)\n", d.cda_prior_m2 + fit.cda_shift_m2,
                d.cda_prior_m2, *o.cda_per_torque_scale_m2);
    std::printf("roadload analyze ... --engine-losses %s --cda %.4f --cda-sigma %.4f --cda-per-torque-scale %.3f ",
                o.engine_losses.c_str(), d.cda_prior_m2, d.cda_sigma_m2, *o.cda_per_torque_scale_m2);
  } else {
    std::printf("roadload analyze ... --engine-losses %s ", o.engine_losses.c_str());
  }
  std::printf("--torque-scale %.5f --torque-scale-sigma %.5f\n", fit.scale, fit.sigma);
  return kExitOk;
}

}  // namespace roadload::cli
