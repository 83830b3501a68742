#include "roadload/sim/sensors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "roadload/sim/units.hpp"

namespace roadload::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

void gauss_markov(double& x, double sigma, double tau_s, double dt_s, Rng& rng) {
  const double a = std::exp(-dt_s / tau_s);
  x = a * x + sigma * std::sqrt(1.0 - a * a) * rng.normal();
}

// Where t_s lies between two physics steps, as a weight on the later one.
double lerp_weight(const Kinematics& a, const Kinematics& b, double t_s) {
  const double span = b.t_s - a.t_s;
  return span > 0 ? std::clamp((t_s - a.t_s) / span, 0.0, 1.0) : 1.0;
}

double lerp(double a, double b, double w) { return a + w * (b - a); }

}  // namespace

std::vector<AccelMount> accel_mounts(const TruckParams& truck, std::size_t count) {
  std::vector<AccelMount> all;
  for (const AccelerometerMount& m : truck.accelerometers) {
    all.push_back({m.name, m.position, std::min(truck.axle_index(m.axle), kMaxAxles - 1), m.on_axle, m.range_g});
  }
  std::vector<AccelMount> out;
  for (std::size_t i = 0; i < count && !all.empty(); ++i) {
    AccelMount m = all[i % all.size()];
    if (i >= all.size()) m.name += "-" + std::to_string(i / all.size());
    out.push_back(m);
  }
  return out;
}

Accelerometer::Accelerometer(std::uint8_t id, AccelMount mount, double rate_hz, Rng rng)
    : id_(id), mount_(std::move(mount)), rate_hz_(rate_hz), rng_(rng) {
  // ADXL355-class part: 20-bit output, 22.5 ug/rtHz at +-2 g (25 at +-8 g), +-25 mg zero-g
  // offset, +-1 % sensitivity, internal oscillator within +-0.5 % of its nominal rate.
  const double odr = rate_hz_ * (1.0 + rng_.uniform(-0.005, 0.005));
  period_s_ = 1.0 / odr;
  start_s_ = rng_.uniform(0.0, period_s_);
  next_true_s_ = start_s_;
  noise_density_ = (mount_.range_g <= 2.1 ? 22.5e-6 : 25e-6) * kGravity_mps2;
  noise_sigma_ = noise_density_ * std::sqrt(rate_hz_ / 2.0);
  lsb_ = mount_.range_g * kGravity_mps2 / static_cast<double>(1 << 19);
  for (std::size_t a = 0; a < 3; ++a) {
    offset_[a] = rng_.uniform(-0.025, 0.025) * kGravity_mps2;
    gain_[a] = 1.0 + rng_.uniform(-0.01, 0.01);
  }
}

double Accelerometer::reading(double true_mps2, std::size_t axis, double cross_mps2) {
  const double range = mount_.range_g * kGravity_mps2;
  double v = gain_[axis] * (true_mps2 + 0.01 * cross_mps2) + offset_[axis] + noise_sigma_ * rng_.normal();
  v = std::clamp(v, -range, range - lsb_);
  return std::round(v / lsb_) * lsb_;
}

AccelSample Accelerometer::sample(const Kinematics& before, const Kinematics& now, double stamp_s) {
  // Only the fields this part senses: a sample interpolates 4 of the 19, and there are millions.
  const double w = lerp_weight(before, now, next_true_s_);
  const auto& b_vertical = mount_.unsprung ? before.unsprung_mps2 : before.sprung_mps2;
  const auto& n_vertical = mount_.unsprung ? now.unsprung_mps2 : now.sprung_mps2;
  const double vertical = lerp(b_vertical[mount_.axle], n_vertical[mount_.axle], w);
  const double x = lerp(before.accel_long_mps2, now.accel_long_mps2, w) + lerp(before.gravity_along_mps2, now.gravity_along_mps2, w);
  const double z = vertical + lerp(before.gravity_normal_mps2, now.gravity_normal_mps2, w);
  AccelSample s;
  s.t = capture_time_from_ns(std::llround(stamp_s * 1e9));
  s.sensor = id_;
  s.x_mps2 = reading(x, 0, z);
  s.y_mps2 = reading(0.0, 1, z);
  s.z_mps2 = reading(z, 2, x);
  ++index_;
  next_true_s_ = start_s_ + static_cast<double>(index_) * period_s_;
  return s;
}

GnssReceiver::GnssReceiver(double rate_hz, std::int64_t utc_start_ns, double latency_s, double elevation_bias_m, Rng rng)
    : rate_hz_(rate_hz), utc_start_ns_(utc_start_ns), latency_s_(latency_s), elevation_bias_m_(elevation_bias_m), rng_(rng) {
  // Fixes fall on whole tenths of a UTC second; the run starts on a whole second.
  next_true_s_ = 0.0;
}

GnssFix GnssReceiver::fix(const GnssTruth& truth) {
  // Code DGPS: white noise plus errors correlated over minutes (what limits grade from GNSS).
  const double dt = 1.0 / rate_hz_;
  gauss_markov(gm_north_, 0.2, 100.0, dt, rng_);
  gauss_markov(gm_east_, 0.2, 100.0, dt, rng_);
  gauss_markov(gm_up_, 0.35, 100.0, dt, rng_);
  const double north = gm_north_ + 0.1 * rng_.normal();
  const double east = gm_east_ + 0.1 * rng_.normal();
  double up = gm_up_ + 0.2 * rng_.normal();
  if (elevation_bias_m_ != 0.0) up += elevation_bias_m_ * std::sin(2 * std::numbers::pi * truth.t_s / 1200.0 + 0.7);
  GnssFix f;
  // The receiver outputs the fix some tens of ms after its epoch; the logger stamps it on arrival.
  f.t = capture_time_from_ns(std::llround((truth.t_s + latency_s_ + 0.002 * rng_.uniform()) * 1e9));
  f.utc_ns = utc_start_ns_ + std::llround(truth.t_s * 1e9);
  f.lat_deg = truth.lat_deg + north / 111132.0;
  f.lon_deg = truth.lon_deg + east / (111320.0 * std::cos(truth.lat_deg * kDeg));
  f.alt_m = truth.alt_m + up;
  f.speed_mps = std::max(0.0, truth.speed_mps + 0.03 * rng_.normal());
  const double course_noise = truth.speed_mps > 0.5 ? std::atan2(0.03 * rng_.normal(), truth.speed_mps) / kDeg : 0.0;
  f.course_deg = std::fmod(truth.course_deg + course_noise + 360.0, 360.0);
  f.mode = GnssFixMode::dgps;
  f.hdop = 0.9;
  ++epoch_;
  next_true_s_ = static_cast<double>(epoch_) / rate_hz_;
  return f;
}

WeatherMast::WeatherMast(double warm_c, double clock_offset_s, Rng rng)
    : warm_c_(warm_c), clock_offset_s_(clock_offset_s), rng_(rng) {}

double WeatherMast::next_true_s() const { return std::min(next_station_s_, next_anemometer_s_); }

void WeatherMast::observe(const Environment& air, double dt_s) {
  const double from = air.wind_from_deg * kDeg;
  sum_east_ += -air.wind_speed_mps * std::sin(from) * dt_s;
  sum_north_ += -air.wind_speed_mps * std::cos(from) * dt_s;
  sum_temp_ += air.air_temp_c * dt_s;
  sum_pressure_ += air.pressure_pa * dt_s;
  sum_dt_ += dt_s;
  last_ = air;
}

bool WeatherMast::sample(double t_s, WeatherSample& out) {
  if (next_true_s() > t_s) return false;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (next_station_s_ <= next_anemometer_s_) {
    out.t = capture_time_from_ns(std::max<std::int64_t>(0, std::llround((next_station_s_ + clock_offset_s_) * 1e9)));
    out.station = 0;
    const double n = std::max(sum_dt_, 1e-9);
    out.air_temp_c = sum_temp_ / n + warm_c_ + 0.1 * rng_.normal();
    out.pressure_pa = sum_pressure_ / n - 150.0 * warm_c_ + 10.0 * rng_.normal();
    const double east = sum_east_ / n, north = sum_north_ / n;
    out.wind_speed_mps = std::hypot(east, north);
    out.wind_from_deg = std::fmod(std::atan2(-east, -north) / kDeg + 360.0, 360.0);
    sum_east_ = sum_north_ = sum_temp_ = sum_pressure_ = sum_dt_ = 0;
    next_station_s_ += 5.0;
    return true;
  }
  out.t = capture_time_from_ns(std::max<std::int64_t>(0, std::llround((next_anemometer_s_ + clock_offset_s_) * 1e9)));
  out.station = 1;
  out.air_temp_c = nan;
  out.pressure_pa = nan;
  out.wind_speed_mps = std::max(0.0, last_.wind_speed_mps + 0.1 * rng_.normal());
  out.wind_from_deg = std::fmod(last_.wind_from_deg + 3.0 * rng_.normal() + 360.0, 360.0);
  next_anemometer_s_ += 1.0;
  return true;
}

}  // namespace roadload::sim
