#pragma once
// Sensors of the logger, each on its own clock: tri-axial MEMS accelerometers on axles and frame
// rails, a DGPS receiver at 10 Hz, a weather station and an anemometer. Each turns the true state
// into what the part would report, with its noise, bias, range and quantisation.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "roadload/samples.hpp"
#include "roadload/sim/air.hpp"
#include "roadload/sim/random.hpp"
#include "roadload/sim/truck.hpp"

namespace roadload::sim {

// What accelerometers sense at one instant; linear between physics steps.
struct Kinematics {
  double t_s = 0;
  double accel_long_mps2 = 0;
  double gravity_along_mps2 = 0;   // g sin(grade): what a level-mounted x axis feels of gravity
  double gravity_normal_mps2 = 0;  // g cos(grade)
  std::array<double, kMaxAxles> sprung_mps2{};
  std::array<double, kMaxAxles> unsprung_mps2{};
};

struct AccelMount {
  std::string name;      // as the report labels them: TLF1 ...
  std::string position;  // "tractor-front-axle-left", ...
  std::size_t axle = 0;
  bool unsprung = false;
  double range_g = 2.048;
};

// The first `count` of the truck's accelerometers; more than it has repeat its layout, named -1, -2...
std::vector<AccelMount> accel_mounts(const TruckParams& truck, std::size_t count);

class Accelerometer {
 public:
  Accelerometer(std::uint8_t id, AccelMount mount, double rate_hz, Rng rng);
  // True time of the next sample: the part's own oscillator sets the spacing.
  double next_true_s() const { return next_true_s_; }
  // Samples at next_true_s(), between the physics steps `before` and `now`, and advances;
  // `stamp_s` is the capture stamp the logger gives it.
  AccelSample sample(const Kinematics& before, const Kinematics& now, double stamp_s);
  const AccelMount& mount() const { return mount_; }
  double rate_hz() const { return rate_hz_; }
  // Every reading is a whole number of this (the 20-bit output's step over the range).
  double step_mps2() const { return lsb_; }
  // Noise density of the part, (m/s^2)/sqrt(Hz).
  double noise_density() const { return noise_density_; }

 private:
  double reading(double true_mps2, std::size_t axis, double cross_mps2);

  std::uint8_t id_;
  AccelMount mount_;
  double rate_hz_;
  Rng rng_;
  double period_s_;
  double next_true_s_;
  std::int64_t index_ = 0;
  double start_s_;
  double noise_density_;
  double noise_sigma_;
  double lsb_;
  std::array<double, 3> offset_{};
  std::array<double, 3> gain_{};
};

struct GnssTruth {
  double t_s;
  double lat_deg, lon_deg, alt_m;  // antenna, ellipsoidal height
  double speed_mps, course_deg;
};

class GnssReceiver {
 public:
  // `elevation_bias_m` > 0 adds the slowly swinging height bias of the GNSS elevation effect.
  GnssReceiver(double rate_hz, std::int64_t utc_start_ns, double latency_s, double elevation_bias_m, Rng rng);
  double next_true_s() const { return next_true_s_; }
  GnssFix fix(const GnssTruth& truth);

 private:
  double rate_hz_;
  std::int64_t utc_start_ns_;
  double latency_s_;
  double elevation_bias_m_;
  Rng rng_;
  double next_true_s_ = 0;
  std::int64_t epoch_ = 0;
  double gm_north_ = 0, gm_east_ = 0, gm_up_ = 0;
};

// A weather mast: station 0 reports 5 s means of everything, station 1 (anemometer) the wind
// every second. `warm_c` is the air-density effect: the station reads warm and low.
class WeatherMast {
 public:
  WeatherMast(double warm_c, double clock_offset_s, Rng rng);
  double next_true_s() const;
  // Called every physics step with the air at the mast; returns true when `out` holds a sample.
  void observe(const Environment& air, double dt_s);
  bool sample(double t_s, WeatherSample& out);

 private:
  double warm_c_;
  double clock_offset_s_;
  Rng rng_;
  double next_station_s_ = 5.0;
  double next_anemometer_s_ = 1.0;
  double sum_east_ = 0, sum_north_ = 0, sum_temp_ = 0, sum_pressure_ = 0, sum_dt_ = 0;
  Environment last_{};
};

}  // namespace roadload::sim
