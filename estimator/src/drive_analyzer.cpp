#include "roadload/drive_analyzer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace roadload {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr std::uint64_t kNisBatch = 50;  // 5 s at CCVS1's 10 Hz, longer than the innovations' memory

}  // namespace

AnalyzerConfig analyzer_config(const Vehicle& vehicle) {
  AnalyzerConfig c;
  c.filter.truck = model::truck_model(vehicle);
  c.filter.torque_bias_sigma_nm = eec3_quantization_sigma_nm(vehicle.engine.reference_torque_nm);
  for (const VehicleAxle& a : vehicle.axles) c.axles.push_back({a.position_m, a.load_kg});
  c.cg_behind_front_m = vehicle.cg_behind_front_m();
  c.antenna_behind_front_m = vehicle.gnss_antenna_behind_front_m;
  return c;
}

namespace {

double truck_length_m(const std::vector<AxleLoad>& axles) {
  double len = 0;
  for (const AxleLoad& a : axles) len = std::max(len, a.behind_front_m);
  return len;
}

}  // namespace

DriveAnalyzer::DriveAnalyzer(const j1939::Database& db, RouteGeometry route, std::vector<CellSpan> cells, AnalyzerConfig config)
    : route_(std::move(route)),
      grade_(GradeProfile::from_survey(route_, config.survey_elevation_sigma_m)),
      config_(std::move(config)),
      feed_(db),
      position_(config_.antenna_behind_front_m, config_.max_gnss_offset_m),
      cells_(std::move(cells), truck_length_m(config_.axles), config_.keep_history),
      filter_(filter_config(config_, !cells_.spans().empty())) {
  if (const auto* m = db.find_name("CCVS1")) ccvs1_pgn_ = m->pgn;
  if (config_.keep_history) filter_.attach(&smoother_);
  for (const CellSpan& c : cells_.spans()) {
    boundaries_m_.push_back(c.start_m);
    boundaries_m_.push_back(c.end_m);
  }
  std::sort(boundaries_m_.begin(), boundaries_m_.end());
  boundaries_m_.erase(std::unique(boundaries_m_.begin(), boundaries_m_.end()), boundaries_m_.end());
  for (const AxleLoad& a : config_.axles) ripple_axles_.push_back({a.behind_front_m, a.load_kg * model::kGravity_mps2});
  unit_height_m_ = model::roughness_height_sigma_m(1.0, config_.roughness_correlation_m);
}

CrrFilterConfig DriveAnalyzer::filter_config(const AnalyzerConfig& c, bool cells) {
  CrrFilterConfig f = c.filter;
  if (cells) f.crr_walk_per_sqrt_s = c.in_cell_crr_walk_per_sqrt_s;
  f.estimate_cda = c.estimate_cda;
  return f;
}

double DriveAnalyzer::crr_jump_variance(double from_front_m, double to_front_m) const {
  double total = 0;
  for (const AxleLoad& a : config_.axles) total += a.load_kg;
  if (total <= 0 || to_front_m <= from_front_m) return 0;
  double sum_w2 = 0;
  for (const AxleLoad& a : config_.axles) {
    const double lo = from_front_m - a.behind_front_m, hi = to_front_m - a.behind_front_m;
    const auto first = std::upper_bound(boundaries_m_.begin(), boundaries_m_.end(), lo);
    if (first != boundaries_m_.end() && *first <= hi) sum_w2 += (a.load_kg / total) * (a.load_kg / total);
  }
  return config_.cell_crr_jump_sigma * config_.cell_crr_jump_sigma * sum_w2;
}

void DriveAnalyzer::push(const CanFrame& frame) {
  const auto m = feed_.push(frame);
  if (!m || m->pgn != ccvs1_pgn_) return;
  if (feed_.fresh(Quantity::wheel_speed_mps, m->t)) tick(m->t, feed_.get(Quantity::wheel_speed_mps).value);
}

void DriveAnalyzer::push(const GnssFix& fix) {
  if (fix.mode == GnssFixMode::none || !started_) return;
  position_.place(fix, route_);
  trip_.gnss_used = position_.fixes_used();
  trip_.gnss_off_route = position_.fixes_off_route();
}

void DriveAnalyzer::push(const WeatherSample& w) {
  if (!std::isnan(w.air_temp_c) && !std::isnan(w.pressure_pa)) {
    air_temp_c_ = w.air_temp_c;
    pressure_pa_ = w.pressure_pa;
    station_air_ = true;
  }
  if (!std::isnan(w.wind_speed_mps) && !std::isnan(w.wind_from_deg)) {
    wind_mps_ = w.wind_speed_mps;
    wind_from_deg_ = w.wind_from_deg;
    ++trip_.wind_samples;
  }
}

void DriveAnalyzer::push(const AccelSample& sample) {
  if (contact_ != nullptr) contact_->push(sample);
  if (vibration_ != nullptr) vibration_->push(sample);
}

// The flywheel torque's error: the engine-loss calibration's where there is one, else EEC3's rounding.
void DriveAnalyzer::start(CaptureTime t, double wheel_speed_mps) {
  const Reading& ref = feed_.get(Quantity::reference_torque_nm);
  const model::EngineLossMap& losses = config_.filter.truck.engine_losses;
  std::optional<double> bias_sigma_nm;
  if (!losses.empty()) {
    bias_sigma_nm = losses.sigma_nm();
  } else if (ref.seen) {
    bias_sigma_nm = eec3_quantization_sigma_nm(ref.value);
  }
  filter_.start(t, wheel_speed_mps, bias_sigma_nm);
  started_ = true;
  last_tick_ = t;
  last_front_m_ = position_.front_m();
  last_speed_mps_ = wheel_speed_mps;
}

void DriveAnalyzer::update_air() {
  if (station_air_) return;
  const Reading& temp = feed_.get(Quantity::ambient_temp_c);
  const Reading& press = feed_.get(Quantity::pressure_pa);
  if (temp.seen) air_temp_c_ = temp.value;
  if (press.seen) pressure_pa_ = press.value;
}

void DriveAnalyzer::tick(CaptureTime t, double wheel_speed_mps) {
  if (!started_) start(t, wheel_speed_mps);
  const double dt_s = to_seconds(t - last_tick_);
  position_.advance(t, wheel_speed_mps);
  last_tick_ = t;
  update_air();
  const double s_front = position_.front_m();
  const double s_cg = s_front - config_.cg_behind_front_m;
  const TractionEstimate tr = traction(feed_.signals(), config_.filter.truck, t);
  const double grade = grade_.grade_rad(s_cg);
  const Unusable why = tr.reason == Unusable::none && std::isnan(grade) ? Unusable::no_elevation : tr.reason;
  const int cell = cells_.cell_at(s_cg);
  model::ForceInputs in = force_inputs(t, s_front, tr, why);
  add_ripple(in, cell, wheel_speed_mps, wheel_speed_mps * dt_s);
  last_front_m_ = s_front;
  place_axles(t, s_front, in.grade_rad, wheel_speed_mps);
  filter_.predict_to(in);
  const ekf::UpdateResult upd = filter_.update_speed(t, wheel_speed_mps, config_.wheel_speed_sigma_mps);
  const PowerInterval power = power_since_last_tick(dt_s, tr, wheel_speed_mps);
  last_speed_mps_ = wheel_speed_mps;
  const CrrMean now{filter_.crr(), filter_.crr_sigma()};
  cells_.tick(s_front, s_cg, wheel_speed_mps, why, now, smoother_.size());
  if (config_.keep_history) {
    fuel_.add({power, smoother_.size(), cell, in.air_density_kgpm3, in.headwind_mps, in.grade_rad});
    if (in.usable) usable_steps_.push_back(smoother_.size());
  }
  live_ = {t, true, wheel_speed_mps, s_front, cell, now.crr, 0, 0, false, nullptr, in.usable};
  live_.crr_lo = live_.crr - config_.interval_z * now.sigma;
  live_.crr_hi = live_.crr + config_.interval_z * now.sigma;
  count(in, why, upd, tr.coasting);
  live_.not_identified = live_failure();
  live_.identified = live_.not_identified == nullptr;
}

// The checks a live estimate can have, without allocating: its sigma and range, the outliers so far
// and the GNSS fixes that placed it.
const char* DriveAnalyzer::live_failure() const {
  const IdentificationLimits& l = config_.identification;
  const CrrCounters& c = filter_.counters();
  const double updates = static_cast<double>(c.updates + c.outliers);
  if (position_.fixes_used() < l.min_fixes_on_route) return "the drive is not placed on the route (too few GNSS fixes on it)";
  if (trip_.wind_samples == 0) return "no wind measured (no weather station)";
  if (!filter_.crr_identified()) return "its uncertainty exceeds the limit";
  if (!(filter_.crr() >= l.min_crr && filter_.crr() <= l.max_crr)) return "the CRR lies outside what truck tires show";
  if (static_cast<double>(c.outliers) > l.max_outlier_share * updates) return "too many speed updates were outliers";
  return nullptr;
}

void DriveAnalyzer::count(const model::ForceInputs& in, Unusable why, const ekf::UpdateResult& update, bool coasting) {
  ++trip_.ticks;
  if (in.usable) {
    ++trip_.usable_ticks;
    if (coasting) ++trip_.coasting_ticks;
  } else {
    ++trip_.unusable[static_cast<std::size_t>(why)];
  }
  if (!update.accepted) return;
  nis_.add(update.nis);
  nis_batch_.add(update.nis);
  if (nis_batch_.n == kNisBatch) {
    nis_batch_means_.add(nis_batch_.mean);
    nis_batch_ = {};
  }
}

model::ForceInputs DriveAnalyzer::force_inputs(CaptureTime t, double s_front_m, const TractionEstimate& tr, Unusable why) const {
  const double s_cg = s_front_m - config_.cg_behind_front_m;
  const double grade = grade_.grade_rad(s_cg);
  const double grade_sigma = grade_.grade_sigma_rad(s_cg);
  model::ForceInputs in;
  in.t = t;
  in.tractive_n = tr.tractive_n;
  in.effective_mass_kg = tr.effective_mass_kg;
  in.wheel_force_per_flywheel_nm = tr.wheel_force_per_flywheel_nm;
  in.indicated_force_n = tr.indicated_nm * tr.wheel_force_per_flywheel_nm;
  in.crr_jump_variance = crr_jump_variance(last_front_m_, s_front_m);
  in.air_density_kgpm3 = model::air_density_kgpm3(pressure_pa_, air_temp_c_);
  in.grade_rad = std::isnan(grade) ? 0.0 : grade;
  in.grade_sigma_rad = std::isnan(grade_sigma) ? 0.0 : grade_sigma;
  in.headwind_mps = wind_mps_ * std::cos((wind_from_deg_ - route_.heading_deg(s_cg)) * kDeg);
  in.usable = why == Unusable::none;
  return in;
}

// The ripple's sigma grows with the IRI of the cell under the truck in proportion; its correlation
// is the axles' over this tick's distance. Below walking pace it would grow without bound; there
// the tires barely climb.
void DriveAnalyzer::add_ripple(model::ForceInputs& in, int cell, double speed_mps, double step_m) const {
  const std::vector<CellSpan>& spans = cells_.spans();
  const double iri = cell >= 0 && !std::isnan(spans[static_cast<std::size_t>(cell)].iri_m_per_km)
                         ? spans[static_cast<std::size_t>(cell)].iri_m_per_km
                         : config_.roughness_iri_m_per_km;
  const model::RoughnessRipple ripple = model::roughness_ripple(ripple_axles_, config_.filter.truck.mass_kg, unit_height_m_,
                                                                config_.roughness_correlation_m, step_m);
  in.ripple_sigma_mps = ripple.sigma_m2ps * iri / std::max(speed_mps, 1.0);
  in.ripple_correlation_m = ripple.correlation_m > 0 ? ripple.correlation_m : config_.roughness_correlation_m;
}

// Every axle in the cell under it, for the contact forces.
void DriveAnalyzer::place_axles(CaptureTime t, double s_front_m, double grade_rad, double speed_mps) {
  if (contact_ == nullptr && vibration_ == nullptr) return;
  std::array<int, kMaxContactAxles> under{};
  const auto& axles = contact_ != nullptr ? contact_->layout().axles : vibration_->layout().axles;
  const std::size_t n = std::min(axles.size(), under.size());
  for (std::size_t i = 0; i < n; ++i) under[i] = cells_.cell_at(s_front_m - axles[i].position_m);
  if (contact_ != nullptr) contact_->set_axle_cells(t, std::span(under.data(), n), grade_rad, speed_mps);
  if (vibration_ != nullptr) vibration_->set_axle_cells(t, std::span(under.data(), n), speed_mps, s_front_m);
}

PowerInterval DriveAnalyzer::power_since_last_tick(double dt_s, const TractionEstimate& tr, double wheel_speed_mps) {
  PowerInterval power;
  power.dt_s = dt_s;
  const Reading& fuel = feed_.get(Quantity::fuel_rate_lph);
  power.fuel_rate_lph = fuel.seen ? fuel.value : 0.0;
  if (!fuel.seen) ++trip_.no_fuel_rate;
  power.engine_speed_rpm = feed_.get(Quantity::engine_speed_rpm).value;
  // At the torque scale the filter holds (calibrate --torque-scale): the work the resistances are
  // fitted to, so the breakdown closes on the same force balance.
  const double scale = config_.filter.torque_scale_held;
  power.indicated_nm = tr.indicated_nm * (1.0 + scale);
  power.friction_nm = tr.friction_nm;
  power.parasitic_nm = tr.parasitic_nm;
  power.engaged = tr.reason != Unusable::declutched;
  power.braking = tr.reason == Unusable::braking;
  power.attributable = tr.reason != Unusable::no_reference_torque && tr.reason != Unusable::no_torque &&
                       tr.reason != Unusable::no_gear && tr.reason != Unusable::stale;
  power.tractive_n = tr.tractive_n + scale * tr.indicated_nm * tr.wheel_force_per_flywheel_nm;
  power.speed_from_mps = last_speed_mps_;
  power.speed_to_mps = wheel_speed_mps;
  power.effective_mass_kg = tr.effective_mass_kg > 0 ? tr.effective_mass_kg : config_.filter.truck.mass_kg;
  return power;
}

CrrFilter::Vec DriveAnalyzer::state_at(std::size_t step) const {
  return step >= smoother_.size() ? filter_.core().x() : smoother_.x(step);
}

DriveAnalyzer::Smoother::Sum DriveAnalyzer::crr_sum(std::span<const std::size_t> steps) {
  Smoother::Sum sum;
  sum.e(CrrState::crr) = 1.0;
  const double w = 1.0 / static_cast<double>(steps.size());
  sum.weights.reserve(steps.size());
  for (const std::size_t step : steps) sum.weights.push_back({step, w});
  return sum;
}

CrrMean DriveAnalyzer::crr_mean(std::span<const std::size_t> steps, double variance) const {
  const double w = 1.0 / static_cast<double>(steps.size());
  CrrMean m;
  for (const std::size_t step : steps) m.crr += w * state_at(step)(CrrState::crr);
  m.sigma = std::sqrt(std::max(0.0, variance));
  return m;
}

void DriveAnalyzer::finish(const PavementGroups& groups) {
  if (finished_) return;
  finished_ = true;
  groups_ = groups;
  // Every mean the results give is summed in the smoother's one backward pass: the trip's, each
  // cell's, each pavement's.
  std::vector<Smoother::Sum> sums{crr_sum(usable_steps_)};
  const std::size_t n_cells = cells_.spans().size();
  for (std::size_t i = 0; i < n_cells; ++i) sums.push_back(crr_sum(cells_.steps(i)));
  std::vector<std::vector<std::size_t>> group_steps;
  for (std::size_t g = 0; g < groups_.names.size(); ++g) {
    group_steps.push_back(cells_.group_steps(groups_, g));
    sums.push_back(crr_sum(group_steps.back()));
  }
  smoother_.finish(filter_.core().x(), filter_.core().p());
  const std::vector<double> variance = smoother_.smooth(std::move(sums));
  for (std::size_t i = 0; i < n_cells; ++i) cell_means_.push_back(crr_mean(cells_.steps(i), variance[1 + i]));
  for (std::size_t g = 0; g < group_steps.size(); ++g) group_means_.push_back(crr_mean(group_steps[g], variance[1 + n_cells + g]));
  fuel_.finish(config_.filter.truck.mass_kg, cells_.spans().size(), [this](std::size_t step) { return state_at(step); });
  trip_.fuel = fuel_.trip();
  // The trip's CRR is the smoothed CRR averaged over every usable tick (a distance average at
  // steady speed), its sigma that of the average.
  if (!usable_steps_.empty()) {
    const CrrMean m = crr_mean(usable_steps_, variance.front());
    trip_.crr = m.crr;
    trip_.crr_sigma = m.sigma;
  } else {
    trip_.crr = filter_.crr();
    trip_.crr_sigma = filter_.crr_sigma();
  }
  trip_.cda_m2 = filter_.cda_m2();
  trip_.mass_kg = filter_.mass_kg();
  trip_.mass_sigma_kg = filter_.mass_sigma_kg();
  trip_.torque_bias_nm = filter_.torque_bias_nm();
  trip_.torque_bias_sigma_nm = std::sqrt(filter_.core().p()(CrrState::torque_bias, CrrState::torque_bias));
  trip_ = trip_so_far();
  trip_.not_identified = trip_failures(trip_, !usable_steps_.empty(), config_.filter.identified_crr_sigma, config_.identification);
  trip_.identified = trip_.not_identified.empty();
}

TripResult DriveAnalyzer::trip_so_far() const {
  TripResult t = trip_;
  t.filter = filter_.counters();
  t.mean_nis = nis_.mean;
  if (nis_batch_means_.n >= 2) t.mean_nis_se = nis_batch_means_.std() / std::sqrt(static_cast<double>(nis_batch_means_.n));
  return t;
}

// A cell of a drive the model does not fit is not identified either: live, the trip so far stands
// for the drive.
CellLimits DriveAnalyzer::cell_limits() const {
  return {config_.filter.truck.mass_kg * model::kGravity_mps2, config_.interval_z, config_.filter.identified_crr_sigma,
          config_.identification, drive_failures(finished_ ? trip_ : trip_so_far(), config_.identification)};
}

std::vector<CellResult> DriveAnalyzer::cells() const {
  // Before finish() a kept history has no smoothed means: no CRR rather than one that is not the
  // cell's (the filter's now is the whole drive's so far).
  std::vector<CellResult> out = cells_.results(cell_limits(), [this](std::size_t i, std::span<const std::size_t>) {
    return i < cell_means_.size() ? std::optional<CrrMean>(cell_means_[i]) : std::nullopt;
  });
  if (!config_.keep_history) return out;
  const std::vector<FuelBreakdown>& fuel = fuel_.cells();
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (i < fuel.size()) out[i].fuel = fuel[i];
    for (std::size_t a = 0; contact_ != nullptr && a < contact_->axle_count(); ++a) out[i].contact.push_back(contact_->cell(i, a));
  }
  return out;
}

std::vector<PavementResult> DriveAnalyzer::pavements() const {
  const PavementGroups& groups = groups_;
  const std::vector<CellResult> crr = cells_.group_results(
      groups, cell_limits(), [this](std::size_t g, std::span<const std::size_t>) {
        return g < group_means_.size() ? std::optional<CrrMean>(group_means_[g]) : std::nullopt;
      });
  const std::vector<FuelBreakdown>& fuel = fuel_.cells();
  std::vector<PavementResult> out(crr.size());
  for (std::size_t g = 0; g < crr.size(); ++g) out[g].crr = crr[g];
  for (std::size_t i = 0; i < groups.cell_group.size(); ++i) {
    const int g = groups.cell_group[i];
    if (g < 0 || static_cast<std::size_t>(g) >= out.size()) continue;
    ++out[static_cast<std::size_t>(g)].cells;
    if (i >= fuel.size()) continue;
    out[static_cast<std::size_t>(g)].rolling_l += fuel[i].liters(FuelUse::rolling);
    out[static_cast<std::size_t>(g)].distance_m += fuel[i].distance_m;
  }
  return out;
}

}  // namespace roadload
