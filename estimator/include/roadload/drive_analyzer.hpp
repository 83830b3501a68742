#pragma once
// A recorded or live drive turned into CRR per pavement cell: J1939, GNSS and weather pushed in
// capture-time order; the CRR filter ticks at each wheel-speed message; offline, a fixed-interval
// smoother then gives every cell the data on both sides of it. Pure: the caller reads the files.
#include <array>
#include <string>
#include <vector>

#include "roadload/can_frame.hpp"
#include "roadload/crr_filter.hpp"
#include "roadload/drive_signals.hpp"
#include "roadload/j1939/assembler.hpp"
#include "roadload/route_geometry.hpp"
#include "roadload/samples.hpp"

namespace roadload {

struct CellSpan {
  std::string id;
  double start_m = 0, end_m = 0;
};

struct AnalyzerConfig {
  CrrFilterConfig filter;
  double wheel_speed_sigma_mps = 0.02;
  double antenna_behind_front_m = 2.5;  // GNSS antenna behind the front axle
  double cg_behind_front_m = 9.74;      // from the axle loads of Table 6.2
  double max_gnss_offset_m = 30.0;      // fixes farther from the route are not on it
  double interval_z = 1.645;            // 90 % two-sided
};

struct CellResult {
  std::string id;
  double start_m = 0, end_m = 0;
  std::size_t samples = 0;  // usable filter ticks with the centre of gravity in the cell
  double crr = 0, crr_sigma = 0, crr_lo = 0, crr_hi = 0;
  bool identified = false;
  std::string reason;       // why not, when not
  double speed_mps = 0;
  double roll_force_n = 0;  // CRR x weight
};

struct TripResult {
  std::size_t ticks = 0, usable_ticks = 0;
  std::array<std::size_t, 7> unusable{};  // by Unusable
  double crr = 0, crr_sigma = 0, cda_m2 = 0;
  bool identified = false;
  std::size_t gnss_used = 0, gnss_off_route = 0;
  CrrCounters filter;
};

class DriveAnalyzer {
 public:
  DriveAnalyzer(const j1939::Database& db, RouteGeometry route, std::vector<CellSpan> cells, AnalyzerConfig config);

  void push(const CanFrame& frame);
  void push(const GnssFix& fix);
  void push(const WeatherSample& sample);
  // Runs the smoother; call once after the last push.
  void finish();

  std::vector<CellResult> cells() const;
  TripResult trip() const;

 private:
  struct Tick {
    CaptureTime t;
    double s_cg_m;
    double speed_mps;
    bool usable;
    std::size_t step;  // smoother index of the estimate after this tick's update
  };
  void tick(CaptureTime t, double wheel_speed_mps);
  double position_front_m() const { return odometer_m_ + (gnss_n_ > 0 ? offset_sum_m_ / static_cast<double>(gnss_n_) : 0.0); }

  const j1939::Database& db_;
  RouteGeometry route_;
  std::vector<CellSpan> cells_;
  AnalyzerConfig config_;
  j1939::MessageAssembler assembler_;
  DriveSignals signals_;
  j1939::Pgn ccvs1_pgn_ = 0;
  CrrFilter filter_;
  ekf::RtsSmoother<CrrState::count> smoother_;
  std::vector<Tick> ticks_;
  TripResult trip_;
  bool started_ = false;
  CaptureTime last_tick_{};
  double odometer_m_ = 0;
  double offset_sum_m_ = 0;
  std::size_t gnss_n_ = 0;
  // Air: from the weather station when it reports, else from the truck's AMB.
  double air_temp_c_ = 15.0, pressure_pa_ = 101325.0, wind_mps_ = 0.0, wind_from_deg_ = 0.0;
  bool station_air_ = false;
  bool finished_ = false;
};

}  // namespace roadload
