#include "roadload/spectra/suspension_spectra.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <span>

namespace roadload::spectra {
namespace {

constexpr std::array<double AxlePower::*, 4> kPowers = {&AxlePower::damper_w, &AxlePower::damper_accel_w, &AxlePower::tire_eq27_w,
                                                        &AxlePower::tire_deflection_w};

// std::complex's product checks its result for NaN, which keeps the loops around it scalar.
std::complex<double> times(std::complex<double> x, std::complex<double> y) {
  return {x.real() * y.real() - x.imag() * y.imag(), x.real() * y.imag() + x.imag() * y.real()};
}

std::size_t slot_count(const std::vector<SuspensionAxle>& axles) {
  int n = 0;
  for (const auto& a : axles) n = std::max({n, a.axle_slot + 1, a.frame_slot + 1});
  return static_cast<std::size_t>(n);
}

}  // namespace

SuspensionSpectra::SuspensionSpectra(std::vector<SuspensionAxle> axles, std::size_t cell_count, const SensorGrid& grid,
                                     SuspensionConfig config)
    : axles_(std::move(axles)),
      config_(config),
      transform_({grid.rate_hz(), config.nperseg, config.noverlap}),
      weights_(hann_periodic(config.nperseg)),
      leaks_(cell_count, axles_.size()),
      segment_(config.nperseg),
      slot_spectrum_(slot_count(axles_), std::vector<std::complex<double>>(bin_count(transform_.config()))),
      slot_velocity_(slot_spectrum_),
      slot_ok_(slot_count(axles_)),
      delayed_(bin_count(transform_.config())),
      delayed_velocity_(bin_count(transform_.config())),
      response_(bin_count(transform_.config()), 1.0),
      scratch_uu_(bin_count(transform_.config())),
      scratch_ss_(bin_count(transform_.config())),
      scratch_us_(bin_count(transform_.config())),
      scratch_density_(bin_count(transform_.config())),
      schedule_(config.nperseg, config.nperseg - config.noverlap, config.lag_samples) {
  for (std::size_t k = 1; k < response_.size(); ++k)
    response_[k] = grid.velocity_response_ratio(static_cast<double>(k) * bin_hz(transform_.config()));
  const std::size_t bins = bin_count(transform_.config());
  trip_.assign(axles_.size(), Sums(bins));
  window_.assign(axles_.size(), AxlePower{});
  cell_.assign(cell_count * axles_.size(), AxlePower{});
  for (std::size_t a = 0; a < axles_.size(); ++a) coefficients_.push_back(power_coefficients(a));
}

// power() of sums holding one unit in one bin of one term, one segment in every sum: the
// coefficients come from the one definition of the powers.
std::vector<double> SuspensionSpectra::power_coefficients(std::size_t axle) const {
  const std::size_t bins = bin_count(transform_.config());
  std::vector<double> out(kPowers.size() * 6 * bins);
  const std::vector<std::complex<double>> zero(bins);
  std::vector<std::complex<double>> unit(bins);
  for (std::size_t pair = 0; pair < 2; ++pair) {
    for (std::size_t term = 0; term < 3; ++term) {
      for (std::size_t k = 0; k < bins; ++k) {
        unit[k] = 1.0;
        Sums s(bins);
        std::size_t i = 0;
        for (Pair* p : {&s.accel, &s.velocity}) {
          for (SpectralSum* sum : {&p->uu, &p->ss, &p->us}) {
            const bool on = i++ == pair * 3 + term;
            sum->add_scaled(on ? unit : zero, on ? unit : zero, 1.0);
          }
        }
        const AxlePower p = power(s, axle);
        for (std::size_t f = 0; f < kPowers.size(); ++f) out[((pair * bins + k) * 3 + term) * kPowers.size() + f] = p.*kPowers[f];
        unit[k] = 0.0;
      }
    }
  }
  return out;
}

AxlePower SuspensionSpectra::segment_power(std::size_t axle) const {
  const auto u = static_cast<std::size_t>(axles_[axle].axle_slot);
  const std::array<std::span<const std::complex<double>>, 2> us = {slot_spectrum_[u], slot_velocity_[u]};
  const std::array<std::span<const std::complex<double>>, 2> ss = {delayed_, delayed_velocity_};
  const double* c = coefficients_[axle].data();
  const std::size_t bins = delayed_.size();
  // The four powers side by side, as the coefficients are laid out: one pass, kept in registers.
  std::array<double, kPowers.size()> sum{};
  for (std::size_t pair = 0; pair < 2; ++pair) {
    for (std::size_t k = 0; k < bins; ++k) {
      const std::complex<double> x = us[pair][k], y = ss[pair][k];
      const std::array<double, 3> terms = {std::norm(x), std::norm(y), x.real() * y.real() + x.imag() * y.imag()};
      for (std::size_t t = 0; t < 3; ++t, c += kPowers.size()) {
        for (std::size_t f = 0; f < kPowers.size(); ++f) sum[f] += c[f] * terms[t];
      }
    }
  }
  AxlePower p;
  p.segments = 1.0;
  for (std::size_t f = 0; f < kPowers.size(); ++f) p.*kPowers[f] = sum[f];
  return p;
}

void SuspensionSpectra::update(const SensorGrid& grid, const PlacementHistory& history) {
  schedule_.run(grid, [&](std::int64_t end) { take(grid, history, end); });
}

void SuspensionSpectra::take(const SensorGrid& grid, const PlacementHistory& history, std::int64_t end) {
  ++counters_.segments;
  for (std::size_t slot = 0; slot < slot_spectrum_.size(); ++slot) {
    slot_ok_[slot] = slot < grid.sensor_count() && grid.copy(slot, end, segment_);
    if (slot_ok_[slot]) transform_.transform(segment_, slot_spectrum_[slot]);
    slot_ok_[slot] = slot_ok_[slot] && grid.copy_velocity(slot, end, segment_);
    if (slot_ok_[slot]) transform_.transform(segment_, slot_velocity_[slot]);
  }
  const auto n = static_cast<std::int64_t>(config_.nperseg);
  const CaptureTime t0 = grid.time_of(end - n + 1);
  const std::int64_t period = grid.config().period_ns;
  for (std::size_t a = 0; a < axles_.size(); ++a) {
    const SuspensionAxle& ax = axles_[a];
    if (ax.axle_slot < 0 || ax.frame_slot < 0 || !slot_ok_[static_cast<std::size_t>(ax.axle_slot)] ||
        !slot_ok_[static_cast<std::size_t>(ax.frame_slot)]) {
      ++counters_.missing;
      continue;
    }
    const SegmentShares shares = weights_.shares(history, a, t0, period);
    const auto u = static_cast<std::size_t>(ax.axle_slot), f = static_cast<std::size_t>(ax.frame_slot);
    const double tau = (ax.frame_ahead_m > 0 && shares.speed_mps >= config_.min_delay_speed_mps) ? ax.frame_ahead_m / shares.speed_mps
                                                                                                 : 0.0;
    delay(slot_spectrum_[f], slot_velocity_[f], tau, delayed_, delayed_velocity_);
    ++counters_.axle_segments;
    const auto add = [&](Sums& sums, double w) {
      sums.accel.add(slot_spectrum_[u], delayed_, w);
      sums.velocity.add(slot_velocity_[u], delayed_velocity_, w);
    };
    add(trip_[a], 1.0);
    const AxlePower segment = segment_power(a);
    accumulate(window_[a], segment, 1.0);
    for (std::size_t i = 0; i < shares.count; ++i) {
      accumulate(cell_[static_cast<std::size_t>(shares.share[i].cell) * axles_.size() + a], segment, shares.share[i].weight);
    }
    leaks_.add(a, shares);
  }
}

void SuspensionSpectra::accumulate(AxlePower& sum, const AxlePower& segment, double weight) {
  sum.segments += weight;
  for (double AxlePower::*field : kPowers) sum.*field += weight * segment.*field;
}

AxlePower SuspensionSpectra::mean(AxlePower sum) {
  if (sum.segments <= 0) return AxlePower{};
  for (double AxlePower::*field : kPowers) sum.*field /= sum.segments;
  return sum;
}

AxlePower SuspensionSpectra::cell_power(std::size_t cell, std::size_t axle) const {
  const AxlePower own = mean(cell_[cell * axles_.size() + axle]);
  const CellLeak& k = leaks_.leak(cell, axle);
  std::array<AxlePower, CellLeak::kNeighbours> beside;
  for (std::size_t j = 0; j < k.count; ++j) beside[j] = mean(cell_[static_cast<std::size_t>(k.neighbour[j]) * axles_.size() + axle]);
  AxlePower p = own;
  for (double AxlePower::*field : kPowers) {
    p.*field = unblur(k, own.*field, own.segments, [&](std::size_t j) { return beside[j].*field; });
  }
  return p;
}

void SuspensionSpectra::clear_window() { window_.assign(window_.size(), AxlePower{}); }

void SuspensionSpectra::delay(std::span<const std::complex<double>> accel, std::span<const std::complex<double>> velocity,
                              double tau_s, std::span<std::complex<double>> accel_out,
                              std::span<std::complex<double>> velocity_out) const {
  const double step = -2.0 * std::numbers::pi * bin_hz(transform_.config()) * tau_s;
  for (std::size_t k = 0; k < accel.size(); ++k) {
    const std::complex<double> phase = std::polar(1.0, step * static_cast<double>(k));
    accel_out[k] = times(accel[k], phase);
    velocity_out[k] = times(velocity[k], phase);
  }
}

void SuspensionSpectra::density(const Sums& sums, std::size_t axle, AxleDensity which, std::span<double> out) const {
  const bool velocity = which == AxleDensity::axle_velocity || which == AxleDensity::relative_velocity;
  const Pair& p = velocity ? sums.velocity : sums.accel;
  const std::size_t bins = p.uu.bins();
  std::span<std::complex<double>> uu(scratch_uu_.data(), bins), ss(scratch_ss_.data(), bins), us(scratch_us_.data(), bins);
  const double scale = transform_.density_scale();
  p.uu.density(scale, uu);
  p.ss.density(scale, ss);
  p.us.density(scale, us);
  const double mw = axles_[axle].unsprung_kg, mc = axles_[axle].sprung_kg;
  // The trapezoid's zero at Nyquist: above ~0.37 fs (75 Hz on the 200 Hz grid) its response falls
  // below 0.2 and dividing it out would lift noise; the anti-alias filter has taken those bins down.
  const auto usable = [&](std::size_t k) { return k > 0 && response_[k] >= 0.2; };
  for (std::size_t k = 0; k < bins; ++k) {
    const double rel = uu[k].real() + ss[k].real() - 2.0 * us[k].real();
    switch (which) {
      case AxleDensity::axle: out[k] = uu[k].real(); break;
      case AxleDensity::frame: out[k] = ss[k].real(); break;
      case AxleDensity::relative: out[k] = rel; break;
      case AxleDensity::force: out[k] = mw * mw * uu[k].real() + mc * mc * ss[k].real() + 2.0 * mw * mc * us[k].real(); break;
      case AxleDensity::axle_velocity: out[k] = usable(k) ? uu[k].real() / response_[k] : 0.0; break;
      case AxleDensity::relative_velocity: out[k] = usable(k) ? rel / response_[k] : 0.0; break;
    }
  }
}

AxlePower SuspensionSpectra::power(const Sums& s, std::size_t axle) const {
  AxlePower p;
  p.segments = s.accel.uu.segments();
  if (p.segments <= 0) return p;
  const SuspensionAxle& a = axles_[axle];
  const double df = bin_hz(transform_.config());
  const std::span<double> d(scratch_density_);
  density(s, axle, AxleDensity::relative_velocity, d);
  p.damper_w = dashpot_velocity_power_w(a.damper_nspm, d, df, config_.band);
  density(s, axle, AxleDensity::relative, d);
  p.damper_accel_w = dashpot_power_w(a.damper_nspm, d, df, config_.band);
  density(s, axle, AxleDensity::axle_velocity, d);
  p.tire_eq27_w = dashpot_velocity_power_w(a.tire_damping_nspm, d, df, config_.band);
  density(s, axle, AxleDensity::force, d);
  p.tire_deflection_w = tire_deflection_power_w(a.tire_damping_nspm, a.tire_stiffness_npm, d, df, config_.band);
  return p;
}

std::vector<double> SuspensionSpectra::trip_density(std::size_t axle, AxleDensity which) const {
  std::vector<double> out(trip_[axle].accel.uu.bins());
  density(trip_[axle], axle, which, out);
  return out;
}

}  // namespace roadload::spectra
