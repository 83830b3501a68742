#include "roadload/drive_analyzer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "roadload/running_stats.hpp"

namespace roadload {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

}  // namespace

DriveAnalyzer::DriveAnalyzer(const j1939::Database& db, RouteGeometry route, std::vector<CellSpan> cells,
                             AnalyzerConfig config)
    : db_(db),
      route_(std::move(route)),
      grade_(GradeProfile::from_survey(route_, config.survey_elevation_sigma_m)),
      cells_(std::move(cells)),
      config_(config),
      signals_(db),
      filter_(filter_config(config, !cells_.empty())),
      smoother_(config.keep_history ? 36000 : 0) {
  if (const auto* m = db_.find_name("CCVS1")) ccvs1_pgn_ = m->pgn;
  if (config_.keep_history) {
    filter_.attach(&smoother_);
  } else {
    live_cells_.resize(cells_.size());
  }
  for (const CellSpan& c : cells_) {
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

double DriveAnalyzer::truck_length_m() const {
  double len = 0;
  for (const AxleLoad& a : config_.axles) len = std::max(len, a.behind_front_m);
  return len;
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
  const auto m = assembler_.push(frame);
  if (!m) return;
  signals_.push(*m);
  if (m->pgn != ccvs1_pgn_) return;
  const Reading& wheel = signals_.get(Quantity::wheel_speed_mps);
  if (wheel.seen && wheel.t == m->t) tick(m->t, wheel.value);
}

void DriveAnalyzer::push(const GnssFix& fix) {
  if (fix.mode == GnssFixMode::none || !started_) return;
  const RouteGeometry::Projection p = route_.project(fix.lat_deg, fix.lon_deg);
  if (p.offset_m > config_.max_gnss_offset_m) {
    ++trip_.gnss_off_route;
    return;
  }
  // The fix is late by its receiver latency at most a tick; odometry carries position between.
  offset_sum_m_ += p.s_m + config_.antenna_behind_front_m - odometer_m_;
  ++gnss_n_;
  ++trip_.gnss_used;
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
  }
}

void DriveAnalyzer::push(const AccelSample& sample) {
  if (contact_ != nullptr) contact_->push(sample);
  if (vibration_ != nullptr) vibration_->push(sample);
}

int DriveAnalyzer::cell_at(double s_m) const {
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    if (s_m >= cells_[i].start_m && s_m < cells_[i].end_m) return static_cast<int>(i);
  }
  return -1;
}

void DriveAnalyzer::tick(CaptureTime t, double wheel_speed_mps) {
  if (!started_) {
    const Reading& ref = signals_.get(Quantity::reference_torque_nm);
    // The flywheel torque's error: the engine-loss calibration's where there is one, else EEC3's rounding.
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
    last_front_m_ = position_front_m();
    last_speed_mps_ = wheel_speed_mps;
  }
  const double dt_s = to_seconds(t - last_tick_);
  odometer_m_ += wheel_speed_mps * dt_s;
  last_tick_ = t;
  if (!station_air_) {
    const Reading& temp = signals_.get(Quantity::ambient_temp_c);
    const Reading& press = signals_.get(Quantity::pressure_pa);
    if (temp.seen) air_temp_c_ = temp.value;
    if (press.seen) pressure_pa_ = press.value;
  }
  const double s_front = position_front_m();
  const double s_cg = s_front - config_.cg_behind_front_m;
  const TractionEstimate tr = traction(signals_, config_.filter.truck, t);
  const double grade = grade_.grade_rad(s_cg);
  const Unusable why = tr.reason == Unusable::none && std::isnan(grade) ? Unusable::no_elevation : tr.reason;
  const int cell = cell_at(s_cg);
  model::ForceInputs in = force_inputs(t, s_front, tr, why);
  add_ripple(in, cell, wheel_speed_mps, wheel_speed_mps * dt_s);
  last_front_m_ = s_front;
  place_axles(t, s_front, in.grade_rad, wheel_speed_mps);
  filter_.predict_to(in);
  const ekf::UpdateResult upd = filter_.update_speed(t, wheel_speed_mps, config_.wheel_speed_sigma_mps);
  const PowerInterval power = power_since_last_tick(dt_s, tr, wheel_speed_mps);
  last_speed_mps_ = wheel_speed_mps;
  if (config_.keep_history) {
    ticks_.push_back({t, s_front, s_cg, wheel_speed_mps, in.usable, why, upd.accepted ? upd.nis : std::nan(""),
                      smoother_.size(), power, in.air_density_kgpm3, in.headwind_mps, in.grade_rad});
  }
  if (!config_.keep_history) note_live_cell(s_front, s_cg, wheel_speed_mps, in.usable, why);
  live_ = {t, true, wheel_speed_mps, s_front, cell, filter_.crr(), 0, 0, filter_.crr_identified(), in.usable};
  live_.crr_lo = live_.crr - config_.interval_z * filter_.crr_sigma();
  live_.crr_hi = live_.crr + config_.interval_z * filter_.crr_sigma();
  ++trip_.ticks;
  if (in.usable) {
    ++trip_.usable_ticks;
  } else {
    ++trip_.unusable[static_cast<std::size_t>(why)];
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
  const double iri = cell >= 0 && !std::isnan(cells_[static_cast<std::size_t>(cell)].iri_m_per_km)
                         ? cells_[static_cast<std::size_t>(cell)].iri_m_per_km
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
  for (std::size_t i = 0; i < n; ++i) under[i] = cell_at(s_front_m - axles[i].position_m);
  if (contact_ != nullptr) contact_->set_axle_cells(t, std::span(under.data(), n), grade_rad, speed_mps);
  if (vibration_ != nullptr) vibration_->set_axle_cells(t, std::span(under.data(), n), speed_mps, s_front_m);
}

PowerInterval DriveAnalyzer::power_since_last_tick(double dt_s, const TractionEstimate& tr, double wheel_speed_mps) {
  PowerInterval power;
  power.dt_s = dt_s;
  const Reading& fuel = signals_.get(Quantity::fuel_rate_lph);
  power.fuel_rate_lph = fuel.seen ? fuel.value : 0.0;
  if (!fuel.seen) ++trip_.no_fuel_rate;
  power.engine_speed_rpm = signals_.get(Quantity::engine_speed_rpm).value;
  power.indicated_nm = tr.indicated_nm;
  power.friction_nm = tr.friction_nm;
  power.parasitic_nm = tr.parasitic_nm;
  power.engaged = tr.reason != Unusable::declutched;
  power.braking = tr.reason == Unusable::braking;
  power.attributable = tr.reason != Unusable::no_reference_torque && tr.reason != Unusable::no_torque &&
                       tr.reason != Unusable::no_gear && tr.reason != Unusable::stale;
  power.tractive_n = tr.tractive_n;
  power.speed_from_mps = last_speed_mps_;
  power.speed_to_mps = wheel_speed_mps;
  power.effective_mass_kg = tr.effective_mass_kg > 0 ? tr.effective_mass_kg : config_.filter.truck.mass_kg;
  return power;
}

void DriveAnalyzer::nis_statistics() {
  constexpr std::uint64_t kBatch = 50;  // 5 s at CCVS1's 10 Hz, longer than the innovations' memory
  RunningStats all, batch, batch_means;
  for (const Tick& k : ticks_) {
    if (std::isnan(k.nis)) continue;
    all.add(k.nis);
    batch.add(k.nis);
    if (batch.n == kBatch) {
      batch_means.add(batch.mean);
      batch = {};
    }
  }
  trip_.mean_nis = all.mean;
  if (batch_means.n >= 2) trip_.mean_nis_se = batch_means.std() / std::sqrt(static_cast<double>(batch_means.n));
}

CrrFilter::Vec DriveAnalyzer::state_at(std::size_t step) const {
  return step >= smoother_.size() ? filter_.core().x() : smoother_.x(step);
}

DriveAnalyzer::CrrMean DriveAnalyzer::crr_mean(std::span<const std::size_t> steps) const {
  const double w = 1.0 / static_cast<double>(steps.size());
  std::vector<Smoother::Weight> weights;
  weights.reserve(steps.size());
  CrrMean m;
  for (const std::size_t step : steps) {
    m.crr += w * state_at(step)(CrrState::crr);
    weights.push_back({step, w});
  }
  CrrFilter::Vec e = CrrFilter::Vec::Zero();
  e(CrrState::crr) = 1.0;
  m.sigma = std::sqrt(std::max(0.0, smoother_.variance_of_sum(e, weights)));
  return m;
}

// The resistances over the interval before a tick, from the smoothed CRR and CdA.
void DriveAnalyzer::fill_resistances(Tick& k) const {
  const CrrFilter::Vec x = state_at(k.step);
  PowerInterval& p = k.power;
  const double v = 0.5 * (p.speed_from_mps + p.speed_to_mps);
  const double v_air = v + k.headwind_mps;
  const double weight = config_.filter.truck.mass_kg * model::kGravity_mps2;
  p.aero_n = 0.5 * k.air_density_kgpm3 * x(CrrState::cda) * v_air * std::abs(v_air);
  p.rolling_n = x(CrrState::crr) * weight * std::cos(k.grade_rad);
  p.grade_n = weight * std::sin(k.grade_rad);
}

void DriveAnalyzer::finish() {
  if (finished_) return;
  finished_ = true;
  smoother_.finish(filter_.core().x(), filter_.core().p());
  smoother_.smooth();
  cell_fuel_.assign(cells_.size(), FuelBreakdown{});
  for (Tick& k : ticks_) {
    fill_resistances(k);
    trip_.fuel.add(k.power);
    if (const int c = cell_at(k.s_cg_m); c >= 0) cell_fuel_[static_cast<std::size_t>(c)].add(k.power);
  }
  // The trip's CRR is the smoothed CRR averaged over every usable tick (a distance average at
  // steady speed), its sigma that of the average.
  std::vector<std::size_t> usable;
  for (const Tick& k : ticks_) {
    if (k.usable) usable.push_back(k.step);
  }
  if (!usable.empty()) {
    const CrrMean m = crr_mean(usable);
    trip_.crr = m.crr;
    trip_.crr_sigma = m.sigma;
  } else {
    trip_.crr = filter_.crr();
    trip_.crr_sigma = filter_.crr_sigma();
  }
  trip_.cda_m2 = filter_.cda_m2();
  trip_.torque_bias_nm = filter_.torque_bias_nm();
  trip_.torque_bias_sigma_nm = std::sqrt(filter_.core().p()(CrrState::torque_bias, CrrState::torque_bias));
  trip_.identified = !usable.empty() && trip_.crr_sigma <= config_.filter.identified_crr_sigma;
  trip_.filter = filter_.counters();
  nis_statistics();
}

// A cell longer than the truck is read while the whole truck is on it; a shorter one while its
// centre of gravity is.
bool DriveAnalyzer::inside(const CellSpan& c, double s_front_m, double s_cg_m) const {
  const double len = truck_length_m();
  return c.end_m - c.start_m > len ? s_front_m - len >= c.start_m && s_front_m < c.end_m
                                   : s_cg_m >= c.start_m && s_cg_m < c.end_m;
}

void DriveAnalyzer::note_live_cell(double s_front_m, double s_cg_m, double speed_mps, bool usable, Unusable why) {
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    if (!inside(cells_[i], s_front_m, s_cg_m)) continue;
    LiveCell& c = live_cells_[i];
    ++c.seen;
    ++c.why[static_cast<std::size_t>(why)];
    if (!usable) continue;
    c.crr = filter_.crr();
    c.crr_sigma = filter_.crr_sigma();
    c.speed_sum_mps += speed_mps;
    ++c.samples;
  }
}

CellResult DriveAnalyzer::live_cell_result(std::size_t i) const {
  const LiveCell& l = live_cells_[i];
  CellResult r;
  r.id = cells_[i].id;
  r.start_m = cells_[i].start_m;
  r.end_m = cells_[i].end_m;
  r.samples = l.samples;
  if (l.samples == 0) {
    const auto worst = static_cast<std::size_t>(std::max_element(l.why.begin() + 1, l.why.end()) - l.why.begin());
    r.reason = l.seen == 0 ? std::string("not driven")
                           : std::string("no usable force balance: ") + to_string(static_cast<Unusable>(worst));
    return r;
  }
  r.crr = l.crr;
  r.crr_sigma = l.crr_sigma;
  r.crr_lo = r.crr - config_.interval_z * r.crr_sigma;
  r.crr_hi = r.crr + config_.interval_z * r.crr_sigma;
  r.speed_mps = l.speed_sum_mps / static_cast<double>(l.samples);
  r.weight_n = config_.filter.truck.mass_kg * model::kGravity_mps2;
  r.roll_force_n = r.crr * r.weight_n;
  r.identified = r.crr_sigma <= config_.filter.identified_crr_sigma;
  if (!r.identified) r.reason = "CRR not identified: its uncertainty exceeds the configured limit";
  return r;
}

std::vector<CellResult> DriveAnalyzer::cells() const {
  std::vector<CellResult> out;
  if (!config_.keep_history) {
    for (std::size_t i = 0; i < cells_.size(); ++i) out.push_back(live_cell_result(i));
    return out;
  }
  const double weight = config_.filter.truck.mass_kg * model::kGravity_mps2;
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    const CellSpan& c = cells_[i];
    CellResult r;
    if (i < cell_fuel_.size()) r.fuel = cell_fuel_[i];
    for (std::size_t a = 0; contact_ != nullptr && a < contact_->axle_count(); ++a) r.contact.push_back(contact_->cell(i, a));
    r.id = c.id;
    r.start_m = c.start_m;
    r.end_m = c.end_m;
    double speed = 0;
    std::vector<std::size_t> usable;
    std::size_t seen = 0;
    std::array<std::size_t, kUnusableCount> why{};
    for (const Tick& k : ticks_) {
      if (!inside(c, k.s_front_m, k.s_cg_m)) continue;
      ++seen;
      ++why[static_cast<std::size_t>(k.why)];
      if (!k.usable) continue;
      usable.push_back(k.step);
      speed += k.speed_mps;
      ++r.samples;
    }
    if (r.samples == 0) {
      // Name the commonest reason, so a missing input shows as itself and not as a blank.
      const auto worst = static_cast<std::size_t>(std::max_element(why.begin() + 1, why.end()) - why.begin());
      r.reason = seen == 0 ? std::string("not driven")
                           : std::string("no usable force balance: ") + to_string(static_cast<Unusable>(worst)) + " (" +
                                 std::to_string(why[worst]) + " of " + std::to_string(seen) + " ticks)";
      out.push_back(r);
      continue;
    }
    const auto n = static_cast<double>(r.samples);
    const CrrMean m = crr_mean(usable);
    r.crr = m.crr;
    r.crr_sigma = m.sigma;
    r.crr_lo = r.crr - config_.interval_z * r.crr_sigma;
    r.crr_hi = r.crr + config_.interval_z * r.crr_sigma;
    r.speed_mps = speed / n;
    r.weight_n = weight;
    r.roll_force_n = r.crr * weight;
    r.identified = r.crr_sigma <= config_.filter.identified_crr_sigma;
    if (!r.identified) r.reason = "CRR not identified: its uncertainty exceeds the configured limit";
    out.push_back(r);
  }
  return out;
}

TripResult DriveAnalyzer::trip() const { return trip_; }

}  // namespace roadload
