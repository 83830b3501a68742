#pragma once
// One drive reduced to the numbers a real drive and its re-simulation can be compared on, each
// named by where it lies: a channel (engine torque, fuel rate, speed, GNSS height, fan, each
// accelerometer), a place (a route cell, or a pavement and frequency band) and a half of the road.
// Cells alternate between half 0 and half 1, so every kind of feature exists in both halves: an
// effect fitted on one half is judged on the other.
//
// The same code reduces a recording read from disk and a simulation streamed from memory; it
// sees only what a recording holds (CAN frames, accelerometer samples, GNSS fixes, weather).
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "roadload/can_frame.hpp"
#include "roadload/j1939/database.hpp"
#include "roadload/recording/metadata.hpp"
#include "roadload/route_geometry.hpp"
#include "roadload/samples.hpp"
#include "roadload/sim/wind.hpp"
#include "roadload/vehicle.hpp"

namespace roadload::gap {

struct RoadBin {
  std::string id;
  double start_m = 0, end_m = 0;
  bool concrete = false;
};

// The road a run drives and where the truck's sensors sit on it.
struct RunLayout {
  RouteGeometry geometry;
  std::vector<RoadBin> bins;  // in order along the road
};

struct Feature {
  // torque_nm, fuel_lph, speed_mps, gnss_alt_m, torque_sd_nm, speed_sd_mps, fan_rpm, psd_db:<position>
  // (the sensor's mounting position, its name where the recording gives none)
  std::string channel;
  std::string where;  // a cell id, "road", or "<pavement> <lo>-<hi> Hz"
  std::uint8_t half = 0;
  double value = 0;  // NaN when the run never saw it
};

// What the recording says the conditions were, for the re-simulation.
struct RunConditions {
  double duration_s = 0;
  double mean_speed_mps = 0;
  double first_speed_mps = 0;  // the first wheel-based speed: a coast-down's entry speed
  // Share of the speed samples sent while ETC1 said the driveline was disengaged (out of gear or
  // clutch open): near 1 for a neutral coast-down, near 0 for a cruise.
  double disengaged_share = 0;
  double air_temp_c = 15.0, temp_drift_c_per_h = 0.0, pressure_pa = 98100.0;
  double wind_speed_mps = 0.0, wind_from_deg = 0.0;
  std::vector<sim::WindPoint> wind_trace;  // 10 s running means of the measured wind, from the run's start
  std::size_t weather_samples = 0, speed_samples = 0;
  bool have_fix = false;
  double first_lat_deg = 0, first_lon_deg = 0;  // where the run started, to find its route
};

struct RunFeatures {
  std::vector<Feature> features;
  RunConditions conditions;
};

// Frequency bands of the accelerometer features, Hz: bounce and pitch, joint lines at highway
// and test-track speeds, axle hop, roll.
inline constexpr std::array<double, 11> kBandEdgesHz{0.7, 1.5, 2.5, 3.5, 5.0, 7.0, 10.0, 14.0, 20.0, 30.0, 45.0};

class FeatureExtractor {
 public:
  // The recording's vehicle is `base` with what its metadata states over it (axle loads and
  // positions, the antenna): where its sensors and centre of gravity sit.
  FeatureExtractor(const j1939::Database& db, const RunLayout& layout, const recording::Metadata& meta, const Vehicle& base);
  ~FeatureExtractor();
  FeatureExtractor(const FeatureExtractor&) = delete;
  FeatureExtractor& operator=(const FeatureExtractor&) = delete;

  void push(const CanFrame& frame);
  void push(const AccelSample& sample);
  void push(const GnssFix& fix);
  void push(const WeatherSample& sample);
  RunFeatures finish() const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace roadload::gap
