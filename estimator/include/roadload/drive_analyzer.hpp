#pragma once
// A recorded or live drive turned into CRR per pavement cell: J1939, GNSS and weather pushed in
// capture-time order; the CRR filter ticks at each wheel-speed message; offline, a fixed-interval
// smoother then gives every cell the data on both sides of it. Pure: the caller reads the files.
// Its parts: the bus (SignalFeed), the position along the route (RoutePosition), the cells
// (CellEstimates) and the fuel (DriveFuel); this class ties them to the filter.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "roadload/can_frame.hpp"
#include "roadload/cell_estimates.hpp"
#include "roadload/cell_span.hpp"
#include "roadload/contact_forces.hpp"
#include "roadload/crr_filter.hpp"
#include "roadload/drive_fuel.hpp"
#include "roadload/drive_results.hpp"
#include "roadload/drive_signals.hpp"
#include "roadload/grade_profile.hpp"
#include "roadload/identification.hpp"
#include "roadload/model/road_roughness.hpp"
#include "roadload/route_geometry.hpp"
#include "roadload/route_position.hpp"
#include "roadload/running_stats.hpp"
#include "roadload/samples.hpp"
#include "roadload/vehicle.hpp"
#include "roadload/vibration.hpp"

namespace roadload {

// An axle: where it sits behind the front axle and the share of the weight it carries.
struct AxleLoad {
  double behind_front_m = 0;
  double load_kg = 0;
};

struct AnalyzerConfig {
  CrrFilterConfig filter;
  std::vector<AxleLoad> axles;  // analyzer_config() takes them from the vehicle
  // With cells known, CRR is a pavement's: nearly constant within a cell (this walk replaces the
  // filter's), free to jump as each axle rolls onto the next pavement by this much (one sigma,
  // the spread of Table 6.3).
  double in_cell_crr_walk_per_sqrt_s = 2e-5;
  // The report's runs hold one speed: CdA then keeps its prior (crr_filter.hpp, estimate_cda).
  bool estimate_cda = false;
  double cell_crr_jump_sigma = 0.003;
  // CCVS1 rounds to 1/256 km/h, 0.00031 m/s if each rounding were independent; a speed moving less
  // than a step between ticks rounds alike, and 0.0002 gives NIS near 1 on the simulated drives.
  double wheel_speed_sigma_mps = 0.0002;
  double antenna_behind_front_m = 0;  // GNSS antenna behind the front axle
  double cg_behind_front_m = 0;
  double max_gnss_offset_m = 30.0;        // fixes farther from the route are not on it
  double interval_z = 1.645;              // 90 % two-sided
  IdentificationLimits identification;    // when a CRR may be called identified (identification.hpp)
  double survey_elevation_sigma_m = 0.0;  // the route survey's height error (0: taken as exact)
  // The road's roughness, which ripples the speed (road_roughness.hpp), where a cell states none:
  // agencies measure IRI; 2.0 m/km is a fair highway's, and route files give their own.
  double roughness_iri_m_per_km = 2.0;
  double roughness_correlation_m = 30.0;  // longer waves are the grade profile's
  // Offline, every tick is kept for the smoother and the cells; live (roadloadd), only the filter
  // runs, in fixed memory, and cells() gives each cell the filter's estimate at the last usable
  // tick in it: everything the cell taught the filter, without the data after it.
  bool keep_history = true;
};

// The analyzer's truck: its force balance, axles, centre of gravity and antenna from the vehicle,
// and the torque bias's prior from EEC3's rounding at the vehicle's reference torque (EC1 tells the
// truck's own once it is heard).
AnalyzerConfig analyzer_config(const Vehicle& vehicle);

class DriveAnalyzer {
 public:
  DriveAnalyzer(const j1939::Database& db, RouteGeometry route, std::vector<CellSpan> cells, AnalyzerConfig config);

  void push(const CanFrame& frame);
  void push(const GnssFix& fix);
  void push(const WeatherSample& sample);
  // Accelerometer samples go to the attached contact-force estimator and vibration spectra, placed
  // by this drive's position; without them they are ignored. Both are built on one axle layout.
  void push(const AccelSample& sample);
  void attach(ContactForces* contact) { contact_ = contact; }
  void attach(VibrationAnalysis* vibration) { vibration_ = vibration; }
  // Grade and its sigma from this profile (`roadload grade`) instead of the route's survey.
  void set_grade(GradeProfile grade) {
    filter_.set_grade_error_correlation_m(grade.error_correlation_m());
    grade_ = std::move(grade);
  }
  // Runs the smoother; call once after the last push. `groups` (of this drive's cells) are the
  // pavements that pavements() reports.
  void finish(const PavementGroups& groups = {});

  // Live (no history kept), each cell's estimate so far; offline, the smoothed ones once finished.
  std::vector<CellResult> cells() const;
  // Each pavement type's CRR and rolling fuel over its cells, once finished.
  std::vector<PavementResult> pavements() const;
  TripResult trip() const { return trip_; }
  LiveEstimate live() const { return live_; }
  const j1939::TpCounters& transport() const { return feed_.transport(); }
  const std::vector<CellSpan>& cell_spans() const { return cells_.spans(); }

 private:
  using Smoother = ekf::RtsSmoother<CrrState::count>;
  static CrrFilterConfig filter_config(const AnalyzerConfig& c, bool cells);
  void start(CaptureTime t, double wheel_speed_mps);
  void tick(CaptureTime t, double wheel_speed_mps);
  void update_air();
  model::ForceInputs force_inputs(CaptureTime t, double s_front_m, const TractionEstimate& tr, Unusable why) const;
  void add_ripple(model::ForceInputs& in, int cell, double speed_mps, double step_m) const;
  void place_axles(CaptureTime t, double s_front_m, double grade_rad, double speed_mps);
  PowerInterval power_since_last_tick(double dt_s, const TractionEstimate& tr, double wheel_speed_mps);
  void count(const model::ForceInputs& in, Unusable why, const ekf::UpdateResult& update, bool coasting);
  // Variance of the CRR change as axles cross cell boundaries between two front-axle positions.
  double crr_jump_variance(double from_front_m, double to_front_m) const;
  // The smoothed state at a smoother step (the filter's own after the last prediction).
  CrrFilter::Vec state_at(std::size_t step) const;
  // The mean CRR over ticks (their smoother steps), as a sum whose variance the smoother gives: the
  // shared parts (CdA, torque bias) and the correlation between neighbouring ticks both kept.
  static Smoother::Sum crr_sum(std::span<const std::size_t> steps);
  // Its mean over the smoothed states, and the sigma from that variance.
  CrrMean crr_mean(std::span<const std::size_t> steps, double variance) const;
  CellLimits cell_limits() const;
  // The trip's counters and NIS statistics as far as the drive has gone.
  TripResult trip_so_far() const;
  // The first live check that fails; nullptr when every one holds.
  const char* live_failure() const;

  RouteGeometry route_;
  GradeProfile grade_;
  AnalyzerConfig config_;
  SignalFeed feed_;
  j1939::Pgn ccvs1_pgn_ = 0;
  RoutePosition position_;
  CellEstimates cells_;
  CrrFilter filter_;
  Smoother smoother_;
  DriveFuel fuel_;
  std::vector<std::size_t> usable_steps_;  // offline: for the trip's mean
  PavementGroups groups_;
  std::vector<CrrMean> cell_means_, group_means_;  // smoothed, once finished
  RunningStats nis_, nis_batch_, nis_batch_means_;
  ContactForces* contact_ = nullptr;
  VibrationAnalysis* vibration_ = nullptr;
  TripResult trip_;
  LiveEstimate live_;
  bool started_ = false;
  CaptureTime last_tick_{};
  std::vector<model::AxleWeight> ripple_axles_;
  double unit_height_m_ = 0;  // the roughness's height sigma at 1 m/km of IRI
  double last_front_m_ = 0;
  double last_speed_mps_ = 0;
  std::vector<double> boundaries_m_;  // every cell start and end, sorted
  // Air: from the weather station when it reports, else from the truck's AMB.
  double air_temp_c_ = 15.0, pressure_pa_ = 101325.0, wind_mps_ = 0.0, wind_from_deg_ = 0.0;
  bool station_air_ = false;
  bool finished_ = false;
};

}  // namespace roadload
