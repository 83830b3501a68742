#include "roadload/vehicle_identification.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace roadload {
namespace {

constexpr j1939::Pgn kVehicleIdentificationPgn = 65260;  // VI: variable length, ASCII, "*" ends a field
constexpr double kMinSpeed_mps = 3.0;                    // below, wheel speed sensors lose resolution
constexpr double kMaxAcceleration_mps2 = 0.3;
constexpr Nanoseconds kFresh = std::chrono::milliseconds(250);       // EEC1 is 10-20 ms, CCVS1 100 ms
constexpr Nanoseconds kGearFresh = std::chrono::milliseconds(1500);  // ETC2 is 100 ms

double rad_per_s(double rpm) { return rpm * 2.0 * std::numbers::pi / 60.0; }

// The median and a standard error from the samples' spread: consecutive samples at 10 Hz are not
// independent, so a tenth of them count (a second of driving is one look).
std::optional<IdentifiedValue> robust(std::vector<double> x, std::string source, double resolution = 0.0) {
  if (x.size() < VehicleIdentifier::kMinSamples) return std::nullopt;
  const auto mid = x.begin() + static_cast<long>(x.size() / 2);
  std::nth_element(x.begin(), mid, x.end());
  const double median = *mid;
  std::vector<double> dev(x.size());
  std::transform(x.begin(), x.end(), dev.begin(), [&](double v) { return std::abs(v - median); });
  const auto dmid = dev.begin() + static_cast<long>(dev.size() / 2);
  std::nth_element(dev.begin(), dmid, dev.end());
  const double spread = 1.4826 * *dmid;
  const double looks = std::max(1.0, static_cast<double>(x.size()) / 10.0);
  const double sigma = std::hypot(spread / std::sqrt(looks), resolution / std::sqrt(12.0));
  return IdentifiedValue{median, sigma, x.size(), std::move(source)};
}

}  // namespace

VehicleIdentifier::VehicleIdentifier(const j1939::Database& db, const Vehicle& prior) : prior_(prior), feed_(db) {
  if (const j1939::MessageDef* m = db.find_name("CVW")) {
    for (const auto& s : m->signals) {
      if (s.name == "GrossCombinationVehicleWeight") {
        gcvw_ = &s;
        gcvw_pgn_ = m->pgn;
      }
    }
  }
  etc2_ratios_.resize(prior.driveline.gear_ratios.size());
  speed_ratios_.resize(prior.driveline.gear_ratios.size());
}

void VehicleIdentifier::push(const CanFrame& frame) {
  if (auto m = feed_.push(frame)) on_message(*m);
}

bool VehicleIdentifier::steady_in_gear(CaptureTime t) const {
  const Reading& rpm = feed_.get(Quantity::engine_speed_rpm);
  const Reading& wheel = feed_.get(Quantity::wheel_speed_mps);
  const Reading& gear = feed_.get(Quantity::current_gear);
  const auto flag = [&](Quantity q) { return feed_.get(q).seen && feed_.get(q).value > 0.5; };
  return rpm.seen && t - rpm.t <= kFresh && wheel.seen && t - wheel.t <= kFresh && wheel.value > kMinSpeed_mps && gear.seen &&
         t - gear.t <= kGearFresh && gear.value >= 1 && !flag(Quantity::shift_in_process) && !flag(Quantity::clutch_switch) &&
         !(feed_.get(Quantity::driveline_engaged).seen && feed_.get(Quantity::driveline_engaged).value < 0.5);
}

void VehicleIdentifier::on_message(const j1939::Message& m) {
  if (m.pgn == kVehicleIdentificationPgn) {
    std::string text(m.data.begin(), m.data.end());
    text = text.substr(0, text.find('*'));
    const bool printable = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c > 0x20 && c < 0x7f; });
    if (printable) vin_ = text;
    return;
  }
  if (gcvw_ != nullptr && m.pgn == gcvw_pgn_) {
    if (auto w = j1939::decode(*gcvw_, m.data).get(); w && *w > 0) weights_kg_.push_back(*w);
    return;
  }
  // One look per wheel-speed message: CCVS1 sets the pace (100 ms).
  if (!feed_.fresh(Quantity::wheel_speed_mps, m.t) || !steady_in_gear(m.t)) return;
  const auto gear = static_cast<std::size_t>(feed_.get(Quantity::current_gear).value);
  if (gear > etc2_ratios_.size()) return;
  const Reading& etc2 = feed_.get(Quantity::gear_ratio);
  if (etc2.seen && m.t - etc2.t <= kGearFresh && etc2.value > 0) etc2_ratios_[gear - 1].push_back(etc2.value);
  const VehicleAxle* drive = prior_.drive_axle();
  if (drive != nullptr && prior_.driveline.final_drive > 0) {
    const double wheel_rad_s = feed_.get(Quantity::wheel_speed_mps).value / drive->tire_radius_m;
    speed_ratios_[gear - 1].push_back(rad_per_s(feed_.get(Quantity::engine_speed_rpm).value) / wheel_rad_s /
                                      prior_.driveline.final_drive);
  }
}

// The gear's ratio as ETC2 sends it now, else the prior's: a ratio from before a shift is another
// gear's.
double VehicleIdentifier::gear_ratio_now(int gear, CaptureTime t) const {
  const Reading& etc2 = feed_.get(Quantity::gear_ratio);
  if (etc2.seen && t - etc2.t <= kGearFresh && etc2.value > 0) return etc2.value;
  return prior_.driveline.gear_ratios[static_cast<std::size_t>(gear - 1)];
}

void VehicleIdentifier::push(const GnssFix& fix) {
  const bool steady = last_fix_ && std::abs(fix.speed_mps - last_fix_->speed_mps) < kMaxAcceleration_mps2 &&
                      fix.t - last_fix_->t < std::chrono::milliseconds(1500);
  last_fix_ = fix;
  const bool moving_fix = fix.mode != GnssFixMode::none && std::isfinite(fix.speed_mps) && fix.speed_mps > kMinSpeed_mps;
  if (!steady || !moving_fix || !steady_in_gear(fix.t)) return;
  const int gear = static_cast<int>(feed_.get(Quantity::current_gear).value);
  if (gear < 1 || static_cast<std::size_t>(gear) > prior_.driveline.gear_ratios.size()) return;
  const double wheel_rad_s = rad_per_s(feed_.get(Quantity::engine_speed_rpm).value) /
                             (gear_ratio_now(gear, fix.t) * prior_.driveline.final_drive);
  if (wheel_rad_s > 0) radii_m_.push_back(fix.speed_mps / wheel_rad_s);
  wheel_scales_.push_back(fix.speed_mps / feed_.get(Quantity::wheel_speed_mps).value);
}

VehicleIdentification VehicleIdentifier::result() const {
  VehicleIdentification r;
  r.vin = vin_;
  if (vin_.empty()) r.not_identified.push_back("vin: VI (PGN 65260) not on the bus");
  const Reading& ref = feed_.get(Quantity::reference_torque_nm);
  if (ref.seen) {
    r.reference_torque_nm = IdentifiedValue{ref.value, 0.5, 1, "EC1 SPN 544"};
  } else {
    r.not_identified.push_back("engine.reference_torque_nm: EC1 (SPN 544) not on the bus");
  }
  std::size_t gears_unseen = 0;
  for (std::size_t g = 0; g < etc2_ratios_.size(); ++g) {
    auto v = robust(etc2_ratios_[g], "ETC2 SPN 526 in gear " + std::to_string(g + 1), 0.001);
    if (!v)
      v = robust(speed_ratios_[g], "engine over wheel speed in gear " + std::to_string(g + 1) + " (prior radius and final drive)");
    if (!v) ++gears_unseen;
    r.gear_ratios.push_back(std::move(v));
  }
  if (gears_unseen > 0) {
    r.not_identified.push_back("driveline.gear_ratios: " + std::to_string(gears_unseen) + " of " +
                               std::to_string(etc2_ratios_.size()) + " gears not driven in for " + std::to_string(kMinSamples) +
                               " steady samples; their prior kept");
  }
  r.drive_tire_radius_m = robust(radii_m_, "GNSS speed over engine speed through the gear and final drive");
  if (!r.drive_tire_radius_m) r.not_identified.push_back("axle tire_radius_m: no steady driving in gear with GNSS speed");
  r.wheel_speed_scale = robust(wheel_scales_, "GNSS speed over CCVS1 wheel-based speed");
  if (auto w = robust(weights_kg_, "CVW SPN 1760")) {
    w->sigma = std::hypot(w->sigma, kCombinationWeightSigma * w->value);
    r.mass_kg = w;
  } else {
    r.not_identified.push_back(
        "mass: CVW (PGN 65136) not on the bus; `roadload analyze` finds each drive's mass on its grades "
        "(trip.json mass_kg, mass_sigma_kg)");
  }
  r.not_identified.push_back(
      "body.cda_m2: drag shows only beside the road's grade and rolling resistance, so it is fitted on a route: "
      "`roadload calibrate --aero SLOW FAST --route R` from drives at two speeds");
  return r;
}

}  // namespace roadload
