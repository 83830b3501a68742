#include "roadload/drive_signals.hpp"

#include <cmath>
#include <numbers>

namespace roadload {
namespace {

struct Wanted {
  const char* message;
  const char* signal;
  Quantity quantity;
  double scale;
  bool fraction;
};

constexpr Wanted kWanted[] = {
    {"EEC1", "EngineSpeed", Quantity::engine_speed_rpm, 1.0, false},
    {"EEC1", "ActualEnginePercentTorque", Quantity::actual_torque_pct, 1.0, false},
    {"EEC1", "ActualEnginePercentTorqueFraction", Quantity::actual_torque_pct, 1.0, true},
    {"EEC3", "NominalFrictionPercentTorque", Quantity::friction_torque_pct, 1.0, false},
    {"EEC3", "EstimatedEngineParasiticLossesPercentTorque", Quantity::parasitic_torque_pct, 1.0, false},
    {"EC1", "EngineReferenceTorque", Quantity::reference_torque_nm, 1.0, false},
    {"CCVS1", "WheelBasedVehicleSpeed", Quantity::wheel_speed_mps, 1.0 / 3.6, false},
    {"ETC2", "ActualGearRatio", Quantity::gear_ratio, 1.0, false},
    {"ETC2", "CurrentGear", Quantity::current_gear, 1.0, false},
    {"CCVS1", "BrakeSwitch", Quantity::brake_switch, 1.0, false},
    {"CCVS1", "ClutchSwitch", Quantity::clutch_switch, 1.0, false},
    {"ETC1", "TransmissionDrivelineEngaged", Quantity::driveline_engaged, 1.0, false},
    {"ETC1", "TransmissionShiftInProcess", Quantity::shift_in_process, 1.0, false},
    {"AMB", "AmbientAirTemperature", Quantity::ambient_temp_c, 1.0, false},
    {"AMB", "BarometricPressure", Quantity::pressure_pa, 1000.0, false},
    {"LFE1", "EngineFuelRate", Quantity::fuel_rate_lph, 1.0, false},
    {"FD1", "FanSpeed", Quantity::fan_speed_rpm, 1.0, false},
};
static_assert(std::size(kWanted) <= kQuantityCount + 1);

}  // namespace

DriveSignals::DriveSignals(const j1939::Database& db) {
  for (const Wanted& w : kWanted) {
    const j1939::MessageDef* m = db.find_name(w.message);
    if (m == nullptr) continue;
    for (const auto& sig : m->signals) {
      if (sig.name == w.signal) bindings_[bound_++] = {m->pgn, &sig, w.quantity, w.scale, w.fraction};
    }
  }
}

void DriveSignals::push(const j1939::Message& m) {
  bool torque = false;
  for (std::size_t i = 0; i < bound_; ++i) {
    const Binding& b = bindings_[i];
    if (b.pgn != m.pgn) continue;
    const auto v = j1939::decode(*b.signal, m.data).get();
    if (!v) continue;
    if (b.quantity == Quantity::actual_torque_pct) {
      (b.add ? torque_fraction_ : torque_whole_) = *v;
      if (b.add) torque_fraction_seen_ = true;
      torque = true;
      continue;
    }
    readings_[static_cast<std::size_t>(b.quantity)] = {*v * b.scale, m.t, true};
  }
  if (torque) readings_[static_cast<std::size_t>(Quantity::actual_torque_pct)] = {torque_whole_ + torque_fraction_, m.t, true};
}

const char* to_string(Unusable u) {
  switch (u) {
    case Unusable::none: return "usable";
    case Unusable::no_reference_torque: return "no reference torque (EC1 SPN 544 never received)";
    case Unusable::no_torque: return "no engine torque (EEC1)";
    case Unusable::no_gear: return "no gear information (ETC2, or engine and wheel speed)";
    case Unusable::braking: return "braking";
    case Unusable::declutched: return "shifting or declutched";
    case Unusable::stale: return "inputs are stale";
    case Unusable::no_elevation: return "no elevation in the route's survey (no grade)";
    case Unusable::uncalibrated_rpm: return "engine speed outside the engine-loss calibration";
    case Unusable::count: break;
  }
  return "?";
}

namespace {

bool on(const Reading& r) { return r.seen && r.value > 0.5; }

// Below this the tires' rolling resistance is not yet the rolling one (a truck standing in
// neutral at a light would teach the filter that CRR is zero).
constexpr double kMinCoastSpeed_mps = 1.0;

// In neutral with the clutch released and no shift under way, rolling: the gearbox passes no
// torque, so the wheels feel only the road, the air and the grade (the truck coasting).
bool coasting_in_neutral(const DriveSignals& s, CaptureTime t, Nanoseconds stale_after) {
  const Reading& gear = s.get(Quantity::current_gear);
  const Reading& wheel = s.get(Quantity::wheel_speed_mps);
  return gear.seen && t - gear.t <= stale_after && gear.value == 0 && !on(s.get(Quantity::shift_in_process)) &&
         !on(s.get(Quantity::clutch_switch)) && wheel.seen && wheel.value > kMinCoastSpeed_mps;
}

}  // namespace

TractionEstimate traction(const DriveSignals& s, const model::TruckModel& truck, CaptureTime t, Nanoseconds stale_after) {
  TractionEstimate out;
  if (coasting_in_neutral(s, t, stale_after)) {
    const Reading& wheel = s.get(Quantity::wheel_speed_mps);
    const Reading& ref = s.get(Quantity::reference_torque_nm);
    const Reading& act = s.get(Quantity::actual_torque_pct);
    if (ref.seen && act.seen) {
      // The engine's own losses, for the fuel breakdown; nothing reaches the flywheel's output.
      out.indicated_nm = act.value / 100.0 * ref.value;
      out.friction_nm = s.get(Quantity::friction_torque_pct).seen ? s.get(Quantity::friction_torque_pct).value / 100.0 * ref.value
                                                                  : 0.0;
      out.parasitic_nm = out.indicated_nm - out.friction_nm;
    }
    out.coasting = true;
    out.effective_mass_kg = model::effective_mass_kg(truck, 0.0);
    if (wheel.seen && t - wheel.t > stale_after) out.reason = Unusable::stale;
    if (on(s.get(Quantity::brake_switch))) out.reason = Unusable::braking;
    return out;
  }
  const Reading& ref = s.get(Quantity::reference_torque_nm);
  const Reading& act = s.get(Quantity::actual_torque_pct);
  if (!ref.seen) {
    out.reason = Unusable::no_reference_torque;
    return out;
  }
  if (!act.seen) {
    out.reason = Unusable::no_torque;
    return out;
  }
  const Reading& ratio = s.get(Quantity::gear_ratio);
  const Reading& rpm = s.get(Quantity::engine_speed_rpm);
  const Reading& wheel = s.get(Quantity::wheel_speed_mps);
  if (ratio.seen && t - ratio.t <= stale_after) {
    out.gear_ratio = ratio.value;
  } else if (rpm.seen && wheel.seen && wheel.value > 1.0) {
    // Engine speed over wheel speed gives the overall ratio; divide out the final drive.
    const double wheel_radps = wheel.value / truck.tire_radius_m;
    out.gear_ratio = rpm.value * 2.0 * std::numbers::pi / 60.0 / wheel_radps / truck.final_drive;
  } else {
    out.reason = Unusable::no_gear;
    return out;
  }
  if (t - act.t > stale_after || (wheel.seen && t - wheel.t > stale_after)) {
    out.reason = Unusable::stale;
    return out;
  }
  const double friction = s.get(Quantity::friction_torque_pct).seen ? s.get(Quantity::friction_torque_pct).value : 0.0;
  const double parasitic = s.get(Quantity::parasitic_torque_pct).seen ? s.get(Quantity::parasitic_torque_pct).value : 0.0;
  out.indicated_nm = act.value / 100.0 * ref.value;
  out.friction_nm = friction / 100.0 * ref.value;
  out.parasitic_nm = parasitic / 100.0 * ref.value;
  out.flywheel_nm = model::flywheel_torque_nm(act.value, friction, parasitic, ref.value);
  if (!truck.engine_losses.empty()) {
    const std::optional<double> loss = rpm.seen ? truck.engine_losses.loss_nm(rpm.value) : std::nullopt;
    if (!loss) {
      out.reason = Unusable::uncalibrated_rpm;
      return out;
    }
    if (const std::optional<double> curve = truck.engine_losses.friction_nm(rpm.value)) {
      out.friction_nm = *curve;
      out.parasitic_nm = *loss - *curve;
    } else {
      out.friction_nm = *loss - out.parasitic_nm;
    }
    out.flywheel_nm = out.indicated_nm - *loss;
  }
  out.tractive_n = model::tractive_force_n(truck, out.flywheel_nm, out.gear_ratio);
  out.effective_mass_kg = model::effective_mass_kg(truck, out.gear_ratio);
  out.wheel_force_per_flywheel_nm = model::wheel_force_per_flywheel_nm(truck, out.gear_ratio);
  if (on(s.get(Quantity::brake_switch))) {
    out.reason = Unusable::braking;
  } else if (on(s.get(Quantity::shift_in_process)) ||
             (s.get(Quantity::driveline_engaged).seen && s.get(Quantity::driveline_engaged).value < 0.5)) {
    out.reason = Unusable::declutched;
  }
  return out;
}

}  // namespace roadload
