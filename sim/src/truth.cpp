#include "roadload/sim/truth.hpp"

#include <cmath>
#include <numbers>

namespace roadload::sim {
namespace {

constexpr const char* kSeriesHeader =
    "t_ns,x_m,speed_mps,accel_mps2,grade_rad,gear,engine_rpm,indicated_torque_nm,clutch_torque_nm,"
    "friction_torque_nm,accessory_torque_nm,fan_torque_nm,fuel_lph,crr,f_tractive_n,f_roll_n,f_aero_n,f_grade_n,"
    "f_profile_n,f_brake_n,f_inertia_n,f_driveline_loss_n,air_density_kgpm3,airspeed_mps,yaw_deg,air_temp_c,damper_power_w,tire_"
    "power_w\n";

}  // namespace

TruthRecorder::TruthRecorder(const Route& route, const TruckParams& truck)
    : route_(route), truck_(truck), acc_(route.def().cells.size()) {}

std::optional<ParseError> TruthRecorder::open(const std::string& folder) {
  folder_ = folder;
  auto s = recording::OutputFile::create(folder + "/series.csv");
  if (!s) return s.error();
  series_ = std::move(s.value());
  series_.write(kSeriesHeader);
  auto a = recording::OutputFile::create(folder + "/axles.csv");
  if (!a) return a.error();
  axles_ = std::move(a.value());
  std::string header = "t_ns";
  for (const auto& ax : truck_.axles) {
    header += ",fz_" + ax.name + "_n,damper_" + ax.name + "_w,tire_" + ax.name + "_w";
  }
  axles_.write(header + "\n");
  return std::nullopt;
}

void TruthRecorder::observe(const TruckState& s, const Environment& env, double dt_s) {
  const auto& cells = route_.def().cells;
  // Each axle's dissipation goes to the cell under that axle; fuel and time to the cell under the CG.
  for (std::size_t i = 0; i < truck_.axles.size(); ++i) {
    const Cell* c = route_.cell_at(s.x_m - truck_.axles[i].position_m);
    if (c == nullptr) continue;
    CellAcc& a = acc_[static_cast<std::size_t>(c - cells.data())];
    const AxleOutputs& o = s.axles[i];
    a.fz_dt += o.tire_force_n * dt_s;
    a.crr_fz_dt += s.crr[i] * o.tire_force_n * dt_s;
    a.axle_time[i] += dt_s;
    a.damper_j[i] += o.damper_power_w * dt_s;
    a.tire_j[i] += o.tire_power_w * dt_s;
    a.friction_j[i] += o.friction_power_w * dt_s;
    a.first_x = std::min(a.first_x, s.x_m - truck_.axles[i].position_m);
    a.last_x = std::max(a.last_x, s.x_m - truck_.axles[i].position_m);
  }
  if (const Cell* c = route_.cell_at(s.x_m - truck_.cg_position_m())) {
    CellAcc& a = acc_[static_cast<std::size_t>(c - cells.data())];
    a.time_s += dt_s;
    a.distance_m += s.speed_mps * dt_s;
    a.roll_j += s.roll_n * s.speed_mps * dt_s;
    a.fuel_kg += s.fuel_kgps * dt_s;
  }

  double damper = 0, tire = 0;
  for (const auto& o : s.axles) {
    damper += o.damper_power_w;
    tire += o.tire_power_w;
  }
  const double m_inertia = s.tractive_n - s.roll_n - s.aero_n - s.grade_n - s.profile_n - s.brake_n;
  const std::array<double, kSeriesFields> v{s.indicated_torque_nm,
                                            s.clutch_torque_nm,
                                            s.friction_torque_nm,
                                            s.accessory_torque_nm,
                                            s.fan_torque_nm,
                                            s.fuel_lph,
                                            s.crr_mean,
                                            s.tractive_n,
                                            s.roll_n,
                                            s.aero_n,
                                            s.grade_n,
                                            s.profile_n,
                                            s.brake_n,
                                            m_inertia,
                                            damper,
                                            tire,
                                            s.driveline_loss_n};
  for (std::size_t k = 0; k < kSeriesFields; ++k) sum_[k] += v[k] * dt_s;
  sum_dt_ += dt_s;
  if (series_.is_open() && s.t_s >= next_series_s_ - 1e-9) {
    next_series_s_ += 0.1;
    auto mean = [&](std::size_t k) { return sum_[k] / sum_dt_; };
    line_.clear();
    line_.num(std::llround(s.t_s * 1e9)).sep().num(s.x_m, 3).sep().num(s.speed_mps, 4).sep().num(s.accel_mps2, 4);
    line_.sep().num(s.grade_rad, 6).sep().num(std::int64_t{s.gear}).sep().num(s.engine_rpm, 2);
    for (std::size_t k = 0; k < 5; ++k) line_.sep().num(mean(k), 2);
    line_.sep().num(mean(5), 3).sep().num(mean(6), 6);
    for (std::size_t k = 7; k < 14; ++k) line_.sep().num(mean(k), 2);
    line_.sep().num(mean(16), 2);
    line_.sep().num(s.air_density_kgpm3, 5).sep().num(s.airspeed_mps, 3).sep().num(s.yaw_rad * 180.0 / std::numbers::pi, 3);
    line_.sep().num(env.air_temp_c, 2).sep().num(mean(14), 2).sep().num(mean(15), 2);
    series_.write(line_.finish());
    sum_.fill(0.0);
    sum_dt_ = 0;
  }
  if (axles_.is_open() && s.t_s >= next_axle_s_ - 1e-9) {
    next_axle_s_ += 0.01;
    line_.clear();
    line_.num(std::llround(s.t_s * 1e9));
    // The state holds room for the most axles a truck may have; the file holds this truck's.
    for (std::size_t i = 0; i < truck_.axles.size(); ++i) {
      const AxleOutputs& o = s.axles[i];
      line_.sep().num(o.tire_force_n, 1).sep().num(o.damper_power_w, 2).sep().num(o.tire_power_w, 2);
    }
    axles_.write(line_.finish());
  }
}

std::vector<CellTruth> TruthRecorder::cells() const {
  std::vector<CellTruth> out;
  const auto& cells = route_.def().cells;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const CellAcc& a = acc_[k];
    CellTruth t;
    t.id = cells[k].id;
    t.surface = cells[k].surface;
    t.start_m = cells[k].start_m;
    t.end_m = cells[k].end_m;
    if (a.fz_dt > 0) t.crr = a.crr_fz_dt / a.fz_dt;
    for (std::size_t i = 0; i < truck_.axles.size(); ++i) {
      if (a.axle_time[i] <= 0) continue;
      t.damper_power_w += a.damper_j[i] / a.axle_time[i];
      t.tire_power_w += a.tire_j[i] / a.axle_time[i];
      t.friction_power_w += a.friction_j[i] / a.axle_time[i];
    }
    t.time_s = a.time_s;
    if (a.time_s > 0) t.speed_mps = a.distance_m / a.time_s;
    if (a.distance_m > 0) t.roll_force_n = a.roll_j / a.distance_m;
    t.fuel_l = a.fuel_kg / truck_.fuel.density_kgpl;
    // Every axle entered at the start and left at the end (within one step of travel).
    t.complete = a.first_x <= cells[k].start_m + 0.5 && a.last_x >= cells[k].end_m - 0.5;
    bool all = true;
    for (std::size_t i = 0; i < truck_.axles.size(); ++i) all = all && a.axle_time[i] > 0;
    t.complete = t.complete && all;
    out.push_back(t);
  }
  return out;
}

std::optional<ParseError> TruthRecorder::finish(const std::string& truth_toml) {
  for (recording::OutputFile* f : {&series_, &axles_}) {
    if (auto e = f->close()) return e;
  }
  if (folder_.empty()) return std::nullopt;
  auto c = recording::OutputFile::create(folder_ + "/cells.csv");
  if (!c) return c.error();
  c.value().write(
      "cell,surface,start_m,end_m,complete,crr,damper_power_w,tire_power_w,friction_power_w,speed_mps,time_s,"
      "roll_force_n,fuel_l\n");
  for (const CellTruth& t : cells()) {
    line_.clear();
    line_.text(t.id).sep().text(t.surface).sep().num(t.start_m, 1).sep().num(t.end_m, 1).sep();
    line_.num(std::int64_t{t.complete ? 1 : 0}).sep().num(t.crr, 6).sep().num(t.damper_power_w, 2).sep();
    line_.num(t.tire_power_w, 2).sep().num(t.friction_power_w, 2).sep().num(t.speed_mps, 4).sep().num(t.time_s, 3);
    line_.sep().num(t.roll_force_n, 2).sep().num(t.fuel_l, 5);
    c.value().write(line_.finish());
  }
  if (auto e = c.value().close()) return e;
  auto m = recording::OutputFile::create(folder_ + "/truth.toml");
  if (!m) return m.error();
  m.value().write(truth_toml);
  return m.value().close();
}

std::array<BreakdownTruth, 8> breakdown_truth(const EnergyLedger& e) {
  return {{{"engine", e.thermal_j + e.friction_j},
           {"driveline", e.driveline_j + e.clutch_j},
           {"accessories", e.accessories_j + e.fan_j},
           {"aero", e.aero_j},
           {"rolling", e.roll_j + e.profile_j},
           {"grade", e.grade_j},
           {"acceleration", e.kinetic_j},
           {"braking", e.brake_j}}};
}

}  // namespace roadload::sim
