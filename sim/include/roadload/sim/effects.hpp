#pragma once
// Effects a simple rolling-resistance model leaves out, each a named switch with one magnitude.
// A recording never reveals which are on; only the ground truth does, so a diagnosis can be
// tested blind. Models and ranges: docs/simulator.md, "Effects".
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "roadload/time.hpp"

namespace roadload::sim {

enum class Effect : std::size_t {
  wind_gusts,           // turbulence standard deviation, m/s
  yaw_drag,             // Cd(psi) = Cd0 (1 + a psi^2): a in 1/deg^2
  tire_warmup,          // cold excess of CRR at the start of driving, fraction
  temperature_crr,      // K_T in CRR (1 - K_T (T - 14.3 C)), 1/degC
  speed_crr,            // k_v in CRR (1 + k_v (v - 13.41 m/s)), per m/s
  driveline_losses,     // gear- and load-dependent losses, scale of the churning torque
  torque_bias,          // reported engine torque = (1 + b) true, b as a fraction
  gnss_elevation_bias,  // slowly varying GNSS height bias, amplitude in m
  can_accel_offset,     // accelerometer stamps late against CAN, seconds
  mass_error,           // metadata mass = (1 + e) true mass, e as a fraction
  fan_engagement,       // fraction of the time the cooling fan is engaged
  joint_faulting,       // step at each concrete joint, m
  suspension_friction,  // Coulomb friction of the front leaf spring, N (air axles 13 % of it)
  slab_curl,            // parabolic curl of each concrete slab, m at its edges
  tire_pressure,        // inflation deviation, fraction (negative = under-inflated)
  drafting,             // peak drag reduction behind traffic, fraction
  air_density_error,    // weather station reads warm by this many degC (and low pressure)
  brake_drag,           // a dragging brake, N at the wheels
  cruise_hunting,       // cruise-control limit cycle amplitude, m/s
  ac_compressor,        // the cab's air conditioning switched on: compressor shaft power, W
  wet_road,             // water film on the road, mm: CRR x (1 + w_f h)
  tread_wear,           // share of the usable tread worn since the vehicle file's tires
  count
};

inline constexpr std::size_t kEffectCount = static_cast<std::size_t>(Effect::count);

// Figures two places share (the plant's CRR and the scenario's truck; docs/simulator.md,
// "Effects"): CRR rises 0.2 per mm of water film (docs/simulator-parameters.md #16, mid-range);
// a worn-out tire rolls 25 % easier than a new one (#20) and a truck tire's usable tread is 17 mm
// (about 21 mm new, pulled at about 3 mm).
inline constexpr double kWetCrrPerMm = 0.2;
inline constexpr double kWornCrrDrop = 0.25;
inline constexpr double kUsableTread_m = 0.017;

// The share of a tire's cold excess of CRR left after driving this long (`tire-warmup`): it
// falls with a 20 min time constant (docs/simulator-parameters.md).
double tire_warmup_left(Seconds driven);
// The report's protocol warmed the truck up for 30 minutes or more before a run. A day is the most
// a run is taken to follow (the warm-up is gone after two hours).
inline constexpr Seconds kReportWarmUp{1800.0};
inline constexpr Seconds kMaxDrivenBefore{86400.0};

struct EffectInfo {
  Effect id;
  std::string_view name;  // as given to --effect NAME=MAGNITUDE
  std::string_view unit;
  double typical;   // the magnitude used when the name is given without one
  double min, max;  // realistic range, for blind tests
  std::string_view summary;
};

std::span<const EffectInfo> effect_catalog();
const EffectInfo& effect_info(Effect e);
std::optional<Effect> find_effect(std::string_view name);

// Which effects are on and how strong. Off effects have magnitude 0 and cost nothing.
class EffectSet {
 public:
  void set(Effect e, double magnitude) {
    magnitude_[static_cast<std::size_t>(e)] = magnitude;
    on_[static_cast<std::size_t>(e)] = true;
  }
  void clear(Effect e) {
    magnitude_[static_cast<std::size_t>(e)] = 0.0;
    on_[static_cast<std::size_t>(e)] = false;
  }
  bool on(Effect e) const { return on_[static_cast<std::size_t>(e)]; }
  double magnitude(Effect e) const { return magnitude_[static_cast<std::size_t>(e)]; }
  bool any() const;

  // Parses "NAME=MAGNITUDE" or "NAME" (typical magnitude); the error says what was wrong.
  std::optional<std::string> parse_and_set(std::string_view spec);

 private:
  std::array<double, kEffectCount> magnitude_{};
  std::array<bool, kEffectCount> on_{};
};

}  // namespace roadload::sim
