#pragma once
// A scenario: which road, at what speed, in what weather, with which sensors and effects.
// Built-in scenarios are files in the data directory (config/scenarios), so users read and copy them.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "roadload/parse_error.hpp"
#include "roadload/sim/effects.hpp"
#include "roadload/sim/route.hpp"
#include "roadload/sim/truck.hpp"
#include "roadload/sim/wind.hpp"
#include "roadload/vehicle.hpp"

namespace roadload::sim {

// How each sensor's stamps relate to the true time of what they measured (the capture clock is
// the gateway's monotonic clock, the simulator's virtual time).
struct ClockSpec {
  Seconds can_rx_latency{80e-6};  // end of frame to kernel stamp
  Seconds can_rx_jitter{20e-6};   // uniform 0..this on top
  double ecu_drift_ppm = 100;     // each ECU's oscillator, uniform +-this
  Seconds accel_offset{0};        // accelerometer stamps late against the capture clock
  double accel_drift_ppm = 0;     // and drifting against it
  Seconds gnss_latency{0.05};     // fix epoch to arrival at the logger
  Seconds weather_offset{0};      // weather mast clock against the capture clock
};

struct Scenario {
  std::string name;
  std::string description;
  std::string source;  // the file it came from
  RouteDef route;
  Vehicle vehicle;                  // the truck driven (`vehicle = NAME`, else the default vehicle)
  double speed_mps = 0;             // cruise set speed
  double start_m = 0;               // front axle at the start
  double end_m = 0;                 // the run ends when the front axle passes here
  std::optional<Seconds> duration;  // or after this long, whichever first
  std::int64_t start_utc_ns = 0;
  std::uint64_t road_seed = 1;  // the road is the same whatever the run's seed
  WeatherSpec weather;
  ClockSpec clocks;
  EffectSet effects;
  UnsprungDefinition unsprung = UnsprungDefinition::physical;
  double accel_rate_hz = 1200;
  std::size_t accelerometers = 8;
  double gnss_rate_hz = 10;
  double physics_rate_hz = 2400;
  double load_scale = 1.0;  // every axle's load (its sprung part) times this: a heavier or lighter cargo
  // This truck's engine against its type's: friction and the accessories' power times these (one
  // engine of a fleet; EEC3 rounds each truck's losses differently).
  double engine_friction_scale = 1.0;
  double accessory_scale = 1.0;
  double cda_scale = 1.0;  // and its drag area against the type's (body, mirrors, trailer gap)
  // and its tires' rolling radius against the vehicle file's, which the ECUs turn wheel
  // revolutions into speed and distance with
  double tire_radius_scale = 1.0;
  // and its tires' rolling resistance against the pavement's own CRR, which the route's cells give
  // (brand, model, wear: truck tires of one size differ by 5-10 %)
  double tire_crr_scale = 1.0;
  // How long the truck had been driving when the run starts: its tires' warm-up.
  Seconds driven_before = kReportWarmUp;
  bool coast = false;  // neutral coast-down instead of cruise
  // City traffic: at a stop line every `every_m` the driver slows to `crawl_mps` for `crawl_m`,
  // braking down to it and accelerating at full load back to the set speed. A crawl, not a stop:
  // the plant has no launch clutch, so a stand-still would stall its engine.
  struct StopAndGo {
    double every_m = 0;  // 0: none
    double crawl_mps = 0;
    double crawl_m = 0;
  } stops;
  // Rev-hold (an engine-loss calibration): standing in neutral, the governor holds the engine at
  // each of these speeds in turn for `hold`; coast is set, the speed is 0.
  std::vector<double> hold_rpm;
  Seconds hold{0};
};

// NAME (a built-in, data_dir/scenarios/NAME.toml) or a path to a scenario file.
Parsed<Scenario> load_scenario(std::string_view name_or_path, const std::string& data_dir);
// Names of the built-in scenarios, sorted.
std::vector<std::string> builtin_scenarios(const std::string& data_dir);

}  // namespace roadload::sim
