#pragma once
// A recorded or live drive turned into CRR per pavement cell: J1939, GNSS and weather pushed in
// capture-time order; the CRR filter ticks at each wheel-speed message; offline, a fixed-interval
// smoother then gives every cell the data on both sides of it. Pure: the caller reads the files.
#include <array>
#include <span>
#include <string>
#include <vector>

#include "roadload/can_frame.hpp"
#include "roadload/cell_span.hpp"
#include "roadload/contact_forces.hpp"
#include "roadload/crr_filter.hpp"
#include "roadload/drive_signals.hpp"
#include "roadload/fuel_breakdown.hpp"
#include "roadload/grade_profile.hpp"
#include "roadload/model/road_roughness.hpp"
#include "roadload/j1939/assembler.hpp"
#include "roadload/route_geometry.hpp"
#include "roadload/samples.hpp"
#include "roadload/vibration.hpp"

namespace roadload {

// An axle: where it sits behind the front axle and the share of the weight it carries.
struct AxleLoad {
  double behind_front_m = 0;
  double load_kg = 0;
};

struct AnalyzerConfig {
  CrrFilterConfig filter;
  // The MnROAD truck (report Table 6.2); a recording's metadata replaces it.
  std::vector<AxleLoad> axles = {{0.0, 5307}, {5.14, 7734}, {6.46, 7734}, {16.45, 7688.5}, {17.69, 7688.5}};
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
  double antenna_behind_front_m = 2.5;  // GNSS antenna behind the front axle
  double cg_behind_front_m = 9.74;      // from the axle loads of Table 6.2
  double max_gnss_offset_m = 30.0;      // fixes farther from the route are not on it
  double interval_z = 1.645;            // 90 % two-sided
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

// The filter's estimate now, as the daemon's status shows it.
struct LiveEstimate {
  CaptureTime t{};
  bool started = false;
  double speed_mps = 0;
  double s_front_m = 0;     // along the route
  int cell = -1;            // index of the cell under the centre of gravity; -1 off the cells
  double crr = 0, crr_lo = 0, crr_hi = 0;
  bool identified = false;
  bool usable = false;      // the last tick entered the force balance
};

struct CellResult {
  std::string id;
  double start_m = 0, end_m = 0;
  std::size_t samples = 0;  // usable filter ticks with every axle in the cell (the centre of gravity if it is shorter than the truck)
  double crr = 0, crr_sigma = 0, crr_lo = 0, crr_hi = 0;
  bool identified = false;
  std::string reason;       // why not, when not
  double speed_mps = 0;
  double roll_force_n = 0;  // CRR x weight
  double weight_n = 0;      // the truck's weight that CRR is a coefficient of
  FuelBreakdown fuel;       // over the time the centre of gravity was in the cell
  std::vector<AxleForceStats> contact;  // per axle of the attached ContactForces' layout (Eq. 2.1)
};

struct TripResult {
  std::size_t ticks = 0, usable_ticks = 0;
  std::array<std::size_t, kUnusableCount> unusable{};  // ticks by Unusable
  double crr = 0, crr_sigma = 0, cda_m2 = 0, torque_bias_nm = 0, torque_bias_sigma_nm = 0;
  bool identified = false;
  std::size_t gnss_used = 0, gnss_off_route = 0;
  std::size_t no_fuel_rate = 0;  // ticks without LFE1: the breakdown's measured fuel misses them
  CrrCounters filter;
  // Mean NIS of the speed updates and its standard error from means of batches of consecutive
  // updates (the innovations are correlated over a few ticks, so a plain chi-square band is too
  // narrow): the noise model is consistent when the mean lies within 1 +- 1.96 se.
  double mean_nis = 0, mean_nis_se = 0;
  FuelBreakdown fuel;
};

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
  void set_grade(GradeProfile grade) { grade_ = std::move(grade); }
  // Runs the smoother; call once after the last push.
  void finish();

  std::vector<CellResult> cells() const;
  TripResult trip() const;
  LiveEstimate live() const { return live_; }
  const j1939::TpCounters& transport() const { return assembler_.transport().counters(); }
  const std::vector<CellSpan>& cell_spans() const { return cells_; }

 private:
  static CrrFilterConfig filter_config(const AnalyzerConfig& c, bool cells);
  struct Tick {
    CaptureTime t;
    double s_front_m;
    double s_cg_m;
    double speed_mps;
    bool usable;
    Unusable why;
    double nis;  // of this tick's speed update; NaN when gated out
    std::size_t step;  // smoother index of the estimate after this tick's update
    PowerInterval power;  // since the previous tick; its resistances are filled in after smoothing
    double air_density_kgpm3, headwind_mps, grade_rad;
  };
  void nis_statistics();
  // The smoothed state at a tick's smoother step (the filter's own after the last prediction).
  CrrFilter::Vec state_at(std::size_t step) const;
  using Smoother = ekf::RtsSmoother<CrrState::count>;
  struct CrrMean {
    double crr = 0, sigma = 0;
  };
  // The mean smoothed CRR over ticks (their smoother steps) and its sigma: the shared parts (CdA,
  // torque bias) and the correlation between neighbouring ticks both kept. Needs a step.
  CrrMean crr_mean(std::span<const std::size_t> steps) const;
  void fill_resistances(Tick& k) const;
  void tick(CaptureTime t, double wheel_speed_mps);
  model::ForceInputs force_inputs(CaptureTime t, double s_front_m, const TractionEstimate& tr, Unusable why) const;
  void add_ripple(model::ForceInputs& in, int cell, double speed_mps, double step_m) const;
  void place_axles(CaptureTime t, double s_front_m, double grade_rad, double speed_mps);
  PowerInterval power_since_last_tick(double dt_s, const TractionEstimate& tr, double wheel_speed_mps);
  // Variance of the CRR change as axles cross cell boundaries between two front-axle positions.
  double crr_jump_variance(double from_front_m, double to_front_m) const;
  double truck_length_m() const;
  int cell_at(double s_m) const;
  double position_front_m() const { return odometer_m_ + (gnss_n_ > 0 ? offset_sum_m_ / static_cast<double>(gnss_n_) : 0.0); }

  const j1939::Database& db_;
  RouteGeometry route_;
  GradeProfile grade_;
  std::vector<CellSpan> cells_;
  AnalyzerConfig config_;
  j1939::MessageAssembler assembler_;
  DriveSignals signals_;
  j1939::Pgn ccvs1_pgn_ = 0;
  CrrFilter filter_;
  Smoother smoother_;
  std::vector<Tick> ticks_;
  std::vector<FuelBreakdown> cell_fuel_;
  struct LiveCell {
    double crr = 0, crr_sigma = 0, speed_sum_mps = 0;
    std::size_t samples = 0, seen = 0;
    std::array<std::size_t, kUnusableCount> why{};
  };
  std::vector<LiveCell> live_cells_;  // live mode only, one per cell, sized at construction
  void note_live_cell(double s_front_m, double s_cg_m, double speed_mps, bool usable, Unusable why);
  CellResult live_cell_result(std::size_t i) const;
  bool inside(const CellSpan& c, double s_front_m, double s_cg_m) const;
  ContactForces* contact_ = nullptr;
  VibrationAnalysis* vibration_ = nullptr;
  TripResult trip_;
  LiveEstimate live_;
  bool started_ = false;
  CaptureTime last_tick_{};
  double odometer_m_ = 0;
  std::vector<model::AxleWeight> ripple_axles_;
  double unit_height_m_ = 0;  // the roughness's height sigma at 1 m/km of IRI
  double last_front_m_ = 0;
  double last_speed_mps_ = 0;
  std::vector<double> boundaries_m_;  // every cell start and end, sorted
  double offset_sum_m_ = 0;
  std::size_t gnss_n_ = 0;
  // Air: from the weather station when it reports, else from the truck's AMB.
  double air_temp_c_ = 15.0, pressure_pa_ = 101325.0, wind_mps_ = 0.0, wind_from_deg_ = 0.0;
  bool station_air_ = false;
  bool finished_ = false;
};

}  // namespace roadload
