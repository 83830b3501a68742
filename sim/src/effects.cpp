#include "roadload/sim/effects.hpp"

#include <charconv>
#include <cmath>

namespace roadload::sim {
namespace {

constexpr std::array<EffectInfo, kEffectCount> kCatalog{{
    {Effect::wind_gusts, "wind-gusts", "m/s", 1.0, 0.3, 2.5,
     "turbulence on the mean wind (first-order Gauss-Markov, 4 s correlation time) along and across"},
    {Effect::yaw_drag, "yaw-drag", "1/deg^2", 0.0023, 0.0015, 0.0035,
     "drag coefficient grows with the yaw angle of the relative wind: Cd0 (1 + a psi^2)"},
    {Effect::tire_warmup, "tire-warmup", "fraction", 0.3, 0.15, 0.5,
     "CRR starts high and falls with a 20 min time constant from the start of driving"},
    {Effect::temperature_crr, "temperature-crr", "1/degC", 0.006, 0.004, 0.010,
     "CRR falls with air temperature above 14.3 C (ISO 28580 correction, C3 tires)"},
    {Effect::speed_crr, "speed-crr", "per m/s", 0.010, 0.004, 0.025, "CRR rises linearly with speed from its 30 mph value"},
    {Effect::driveline_losses, "driveline-losses", "scale", 1.0, 0.5, 2.0,
     "gear-dependent mesh efficiency and load-independent churning instead of one efficiency"},
    {Effect::torque_bias, "torque-bias", "fraction", 0.03, -0.05, 0.05, "the engine reports its indicated torque scaled by (1 + b)"},
    {Effect::gnss_elevation_bias, "gnss-elevation-bias", "m", 1.0, 0.5, 2.0,
     "GNSS height carries a bias of this size that swings over 20 minutes"},
    {Effect::can_accel_offset, "can-accel-offset", "s", 0.1, 0.02, 0.5,
     "accelerometer stamps are late against CAN stamps by this offset (+20 ppm drift)"},
    {Effect::mass_error, "mass-error", "fraction", 0.02, -0.05, 0.05, "the recorded vehicle mass is (1 + e) times the true mass"},
    {Effect::fan_engagement, "fan-engagement", "duty", 0.1, 0.05, 0.5,
     "the cooling fan engages (20 kW at 1,340 rpm) for this share of the time, unreported as parasitic load"},
    {Effect::joint_faulting, "joint-faulting", "m", 0.002, 0.0005, 0.005, "step at every transverse joint of concrete cells"},
    {Effect::suspension_friction, "suspension-friction", "N", 1500.0, 500.0, 3000.0,
     "Coulomb friction in the front leaf spring (air axles get 13 % of it)"},
    {Effect::slab_curl, "slab-curl", "m", 0.0005, 0.0002, 0.002, "concrete slabs curl up at their edges (parabolic shape per slab)"},
    {Effect::tire_pressure, "tire-pressure", "fraction", -0.1, -0.2, 0.15,
     "inflation off nominal: CRR scales with (p/p0)^-0.3, tire stiffness with p/p0"},
    {Effect::drafting, "drafting", "fraction", 0.3, 0.1, 0.4, "following traffic in episodes lowers the drag by up to this share"},
    {Effect::air_density_error, "air-density-error", "degC", 2.0, -5.0, 5.0,
     "the weather station reads warm by this much and low by 150 Pa per degC"},
    {Effect::brake_drag, "brake-drag", "N", 100.0, 30.0, 150.0, "one wheel end drags its brake: a constant force at the wheels"},
    {Effect::cruise_hunting, "cruise-hunting", "m/s", 0.15, 0.05, 0.3,
     "cruise control hunts around its set speed with a 20 s period"},
    {Effect::ac_compressor, "ac-compressor", "W", 2000.0, 1000.0, 4000.0,
     "the driver runs the cab's air conditioning: its compressor takes this power from the crankshaft, unreported"},
    {Effect::wet_road, "wet-road", "mm", 0.5, 0.1, 1.0,
     "a water film on the road, unseen by the weather station: CRR x (1 + 0.2 per mm of film)"},
    {Effect::tread_wear, "tread-wear", "fraction", 0.3, 0.1, 0.8,
     "tires worn by this share of their 17 mm of usable tread: CRR x (1 - 0.25 w), radius smaller, speedometer high"},
}};

}  // namespace

double tire_warmup_left(Seconds driven) { return std::exp(-driven.count() / 1200.0); }

std::span<const EffectInfo> effect_catalog() { return kCatalog; }

const EffectInfo& effect_info(Effect e) { return kCatalog[static_cast<std::size_t>(e)]; }

std::optional<Effect> find_effect(std::string_view name) {
  for (const auto& e : kCatalog) {
    if (e.name == name) return e.id;
  }
  return std::nullopt;
}

bool EffectSet::any() const {
  for (bool b : on_) {
    if (b) return true;
  }
  return false;
}

std::optional<std::string> EffectSet::parse_and_set(std::string_view spec) {
  const auto eq = spec.find('=');
  const std::string_view name = spec.substr(0, eq);
  const auto effect = find_effect(name);
  if (!effect) return "unknown effect '" + std::string(name) + "' (roadload simulate --list-effects lists them)";
  double magnitude = effect_info(*effect).typical;
  if (eq != std::string_view::npos) {
    const std::string_view text = spec.substr(eq + 1);
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), magnitude);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty() || !std::isfinite(magnitude)) {
      return "effect " + std::string(name) + ": magnitude '" + std::string(text) + "' is not a number";
    }
  }
  set(*effect, magnitude);
  return std::nullopt;
}

}  // namespace roadload::sim
