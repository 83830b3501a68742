#include "roadload/gap/features.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>

#include "roadload/drive_analyzer.hpp"
#include "roadload/drive_signals.hpp"
#include "roadload/numbers.hpp"
#include "roadload/recording/metadata_vehicle.hpp"
#include "roadload/route_position.hpp"
#include "roadload/running_stats.hpp"
#include "roadload/spectra/welch.hpp"

namespace roadload::gap {
namespace {

double mean_or_nan(double sum, double n) { return n > 0 ? sum / n : kNaN; }

// Where a sensor's axle sits behind the front axle: the vehicle's axle whose axle or frame mount
// the sensor's documented position names. A sensor feels the pavement under its own axle.
double behind_front_m(const recording::SensorInfo& s, const Vehicle& v) {
  for (const VehicleAxle& a : v.axles) {
    if (s.position.starts_with(a.axle_mount) || s.position.starts_with(a.frame_mount)) return a.position_m;
  }
  return 0.0;
}

// A sensor's channel is named by where it is mounted (the recording format states it), so a
// recording's sensors meet the model's whatever their names; by its name where no position is
// given, and by its order among sensors sharing a position.
std::string sensor_key(const recording::SensorInfo& info, const std::vector<std::string>& taken) {
  const std::string base = info.position.empty() ? info.name : info.position;
  std::string key = base;
  for (int n = 2; std::find(taken.begin(), taken.end(), key) != taken.end(); ++n) key = base + "#" + std::to_string(n);
  return key;
}

// Means over a bin plus the spread of its one-second means: slow wander and gust-like variation.
struct BinChannel {
  double sum = 0, n = 0;
  double second_sum = 0, second_n = 0;
  std::int64_t second = std::numeric_limits<std::int64_t>::min();
  RunningStats seconds;

  void add(double v, std::int64_t second_index) {
    sum += v;
    n += 1;
    if (second_index != second) close_second();
    second = second_index;
    second_sum += v;
    second_n += 1;
  }
  void close_second() {
    if (second_n > 0) seconds.add(second_sum / second_n);
    second_sum = second_n = 0;
  }
};

struct BinAcc {
  BinChannel torque, fuel, speed;
  double alt_sum = 0, alt_n = 0;
};

struct SensorSpectra {
  std::uint8_t id = 0;
  std::string name;
  double behind_m = 0;
  spectra::WelchConfig config;
  std::unique_ptr<spectra::SegmentRing> ring;
  std::unique_ptr<spectra::SegmentTransform> transform;
  std::vector<double> segment;
  std::vector<std::complex<double>> bins;
  int ring_bin = -1;  // the road bin the ring's samples came from
  // [concrete][half]
  std::array<std::array<std::optional<spectra::SpectralSum>, 2>, 2> sums;
};

std::size_t nperseg_for(double rate_hz) {
  std::size_t n = 64;
  while (static_cast<double>(n) < 1.5 * rate_hz && n < 16384) n *= 2;
  return n;
}

}  // namespace

struct FeatureExtractor::State {
  State(const j1939::Database& db, const RunLayout& l, const Vehicle& v)
      : layout(l),
        feed(db),
        position(v.gnss_antenna_behind_front_m, AnalyzerConfig{}.max_gnss_offset_m),
        cg_behind_m(v.cg_behind_front_m()),
        acc(l.bins.size()) {}

  const RunLayout& layout;
  SignalFeed feed;
  RoutePosition position;
  j1939::Pgn eec1 = 0, lfe1 = 0, ccvs1 = 0, fd1 = 0;
  double cg_behind_m;

  std::vector<BinAcc> acc;
  std::array<double, 2> fan_sum{}, fan_n{};
  std::vector<SensorSpectra> sensors;

  std::optional<GnssFix> first_fix;

  bool started = false;
  CaptureTime first{}, last{};
  RunningStats speed_all;
  double first_speed_mps = 0, disengaged = 0;
  RunningStats temp_t;
  double temp_tv = 0, temp_tt = 0;  // for the drift, about the first stamp
  double temp_sum = 0, temp_n = 0, pressure_sum = 0, pressure_n = 0;
  double wind_e = 0, wind_n = 0, wind_count = 0;
  std::vector<sim::WindPoint> wind;

  void stamp(CaptureTime t) {
    if (!started) first = t;
    started = true;
    last = std::max(last, t);
  }
  // The front axle's position now, once a fix has placed the truck on the route.
  std::optional<double> front_m(CaptureTime t) const {
    if (!position.placed()) return std::nullopt;
    return position.front_m_at(t);
  }
  int bin_at(double s_m) const {
    const auto& b = layout.bins;
    auto it = std::upper_bound(b.begin(), b.end(), s_m, [](double s, const RoadBin& r) { return s < r.start_m; });
    if (it == b.begin()) return -1;
    --it;
    return s_m < it->end_m ? static_cast<int>(it - b.begin()) : -1;
  }
  int cg_bin(CaptureTime t) const {
    const auto s = front_m(t);
    return s ? bin_at(*s - cg_behind_m) : -1;
  }
  static std::int64_t second_of(CaptureTime t) { return to_ns(t) / 1'000'000'000; }
};

FeatureExtractor::FeatureExtractor(const j1939::Database& db, const RunLayout& layout, const recording::Metadata& meta,
                                   const Vehicle& base)
    : s_(std::make_unique<State>(db, layout, recording::vehicle_from_metadata(base, meta))) {
  auto pgn_of = [&](const char* name) {
    const j1939::MessageDef* m = db.find_name(name);
    return m ? m->pgn : j1939::Pgn{0};
  };
  s_->eec1 = pgn_of("EEC1");
  s_->lfe1 = pgn_of("LFE1");
  s_->ccvs1 = pgn_of("CCVS1");
  s_->fd1 = pgn_of("FD1");
  const Vehicle vehicle = recording::vehicle_from_metadata(base, meta);
  std::vector<std::string> keys;
  for (const auto& info : meta.sensors) {
    if (info.kind != "accelerometer" || info.id < 0 || info.id > 255 || info.rate_hz < 20) continue;
    SensorSpectra& sp = s_->sensors.emplace_back();
    sp.id = static_cast<std::uint8_t>(info.id);
    sp.name = sensor_key(info, keys);
    keys.push_back(sp.name);
    sp.behind_m = behind_front_m(info, vehicle);
    sp.config = {info.rate_hz, nperseg_for(info.rate_hz), nperseg_for(info.rate_hz) / 2};
    sp.ring = std::make_unique<spectra::SegmentRing>(sp.config);
    sp.transform = std::make_unique<spectra::SegmentTransform>(sp.config);
    sp.segment.resize(sp.config.nperseg);
    sp.bins.resize(spectra::bin_count(sp.config));
    for (auto& surface : sp.sums) {
      for (auto& half : surface) half.emplace(sp.bins.size());
    }
  }
}

FeatureExtractor::~FeatureExtractor() = default;

void FeatureExtractor::push(const CanFrame& frame) {
  State& s = *s_;
  s.stamp(frame.t);
  const auto m = s.feed.push(frame);
  if (!m) return;
  const int bin = s.cg_bin(frame.t);
  const auto second = State::second_of(frame.t);
  auto fresh = [&](Quantity q) { return s.feed.fresh(q, frame.t); };
  if (m->pgn == s.ccvs1) {
    if (!fresh(Quantity::wheel_speed_mps)) return;
    const double v = s.feed.get(Quantity::wheel_speed_mps).value;
    s.position.advance(frame.t, v);
    if (s.speed_all.n == 0) s.first_speed_mps = v;
    s.speed_all.add(v);
    // ETC1 comes every 10 ms; a reading older than a second is no longer the driveline's state.
    const Reading& engaged = s.feed.get(Quantity::driveline_engaged);
    if (engaged.seen && frame.t - engaged.t < std::chrono::seconds(1) && engaged.value < 0.5) s.disengaged += 1;
    if (bin >= 0) s.acc[static_cast<std::size_t>(bin)].speed.add(v, second);
  } else if (m->pgn == s.eec1 && bin >= 0) {
    const Reading& ref = s.feed.get(Quantity::reference_torque_nm);
    if (fresh(Quantity::actual_torque_pct) && ref.seen) {
      s.acc[static_cast<std::size_t>(bin)].torque.add(s.feed.get(Quantity::actual_torque_pct).value / 100.0 * ref.value, second);
    }
  } else if (m->pgn == s.lfe1 && bin >= 0) {
    if (fresh(Quantity::fuel_rate_lph))
      s.acc[static_cast<std::size_t>(bin)].fuel.add(s.feed.get(Quantity::fuel_rate_lph).value, second);
  } else if (m->pgn == s.fd1 && bin >= 0 && fresh(Quantity::fan_speed_rpm)) {
    s.fan_sum[static_cast<std::size_t>(bin % 2)] += s.feed.get(Quantity::fan_speed_rpm).value;
    s.fan_n[static_cast<std::size_t>(bin % 2)] += 1;
  }
}

void FeatureExtractor::push(const AccelSample& sample) {
  State& s = *s_;
  s.stamp(sample.t);
  const auto front = s.front_m(sample.t);
  if (!front) return;
  for (SensorSpectra& sp : s.sensors) {
    if (sp.id != sample.sensor) continue;
    const int bin = s.bin_at(*front - sp.behind_m);
    if (bin != sp.ring_bin) {
      sp.ring->clear();
      sp.ring_bin = bin;
    }
    if (bin < 0 || !sp.ring->push(sample.z_mps2)) return;
    sp.ring->copy_segment(sp.segment);
    sp.transform->transform(sp.segment, sp.bins);
    const auto& road = s.layout.bins[static_cast<std::size_t>(bin)];
    sp.sums[road.concrete ? 1 : 0][static_cast<std::size_t>(bin % 2)]->add(sp.bins);
    return;
  }
}

void FeatureExtractor::push(const GnssFix& fix) {
  State& s = *s_;
  s.stamp(fix.t);
  if (fix.mode == GnssFixMode::none) return;
  if (!s.first_fix) s.first_fix = fix;
  const auto p = s.position.place(fix, s.layout.geometry);
  if (!p) return;
  const int bin = s.bin_at(p->s_m);
  if (bin < 0) return;
  BinAcc& a = s.acc[static_cast<std::size_t>(bin)];
  a.alt_sum += fix.alt_m;
  a.alt_n += 1;
}

void FeatureExtractor::push(const WeatherSample& w) {
  State& s = *s_;
  s.stamp(w.t);
  if (std::isfinite(w.air_temp_c)) {
    const double t_h = to_seconds(w.t - s.first) / 3600.0;
    s.temp_t.add(t_h);
    s.temp_tv += t_h * w.air_temp_c;
    s.temp_tt += t_h * t_h;
    s.temp_sum += w.air_temp_c;
    s.temp_n += 1;
  }
  if (std::isfinite(w.pressure_pa)) {
    s.pressure_sum += w.pressure_pa;
    s.pressure_n += 1;
  }
  if (std::isfinite(w.wind_speed_mps) && std::isfinite(w.wind_from_deg)) {
    const double from = w.wind_from_deg * std::numbers::pi / 180.0;
    s.wind_e += w.wind_speed_mps * std::sin(from);
    s.wind_n += w.wind_speed_mps * std::cos(from);
    s.wind_count += 1;
    s.wind.push_back({to_seconds(w.t - s.first), -w.wind_speed_mps * std::sin(from), -w.wind_speed_mps * std::cos(from)});
  }
}

namespace {

double spread(BinChannel c) {
  c.close_second();
  return c.seconds.n >= 3 ? c.seconds.std() * c.seconds.std() : kNaN;
}

// Variance pooled over a half's bins, as a standard deviation.
double pooled_sd(const std::vector<BinAcc>& acc, std::size_t half, BinChannel BinAcc::*channel) {
  double sum = 0, n = 0;
  for (std::size_t i = half; i < acc.size(); i += 2) {
    const double v = spread(acc[i].*channel);
    if (std::isfinite(v)) {
      sum += v;
      n += 1;
    }
  }
  return n > 0 ? std::sqrt(sum / n) : kNaN;
}

// Each sample replaced by the mean of those within +-half_s: the anemometer's noise averaged
// down, the slow wander of the mean wind kept.
std::vector<sim::WindPoint> running_means(std::vector<sim::WindPoint> w, double half_s) {
  std::stable_sort(w.begin(), w.end(), [](const auto& a, const auto& b) { return a.t_s < b.t_s; });
  std::vector<sim::WindPoint> out;
  std::size_t lo = 0, hi = 0;
  double e = 0, n = 0;
  for (const auto& p : w) {
    while (hi < w.size() && w[hi].t_s <= p.t_s + half_s) e += w[hi].east_mps, n += w[hi].north_mps, ++hi;
    while (w[lo].t_s < p.t_s - half_s) e -= w[lo].east_mps, n -= w[lo].north_mps, ++lo;
    const auto count = static_cast<double>(hi - lo);
    out.push_back({p.t_s, e / count, n / count});
  }
  return out;
}

std::string band_name(bool concrete, std::size_t band) {
  char text[64];
  std::snprintf(text, sizeof text, "%s %g-%g Hz", concrete ? "concrete" : "bituminous", kBandEdgesHz[band], kBandEdgesHz[band + 1]);
  return text;
}

}  // namespace

RunFeatures FeatureExtractor::finish() const {
  const State& s = *s_;
  RunFeatures out;
  auto& f = out.features;
  for (std::size_t i = 0; i < s.acc.size(); ++i) {
    const BinAcc& a = s.acc[i];
    const auto half = static_cast<std::uint8_t>(i % 2);
    const std::string& id = s.layout.bins[i].id;
    f.push_back({"torque_nm", id, half, mean_or_nan(a.torque.sum, a.torque.n)});
    f.push_back({"fuel_lph", id, half, mean_or_nan(a.fuel.sum, a.fuel.n)});
    f.push_back({"speed_mps", id, half, mean_or_nan(a.speed.sum, a.speed.n)});
    f.push_back({"gnss_alt_m", id, half, mean_or_nan(a.alt_sum, a.alt_n)});
  }
  for (std::size_t half = 0; half < 2; ++half) {
    const auto h = static_cast<std::uint8_t>(half);
    f.push_back({"torque_sd_nm", "road", h, pooled_sd(s.acc, half, &BinAcc::torque)});
    f.push_back({"speed_sd_mps", "road", h, pooled_sd(s.acc, half, &BinAcc::speed)});
    f.push_back({"fan_rpm", "road", h, mean_or_nan(s.fan_sum[half], s.fan_n[half])});
  }
  for (const SensorSpectra& sp : s.sensors) {
    const std::size_t first = f.size();
    std::vector<double> psd(sp.bins.size());
    const double df = spectra::bin_hz(sp.config);
    for (std::size_t concrete = 0; concrete < 2; ++concrete) {
      for (std::size_t half = 0; half < 2; ++half) {
        const spectra::SpectralSum& sum = *sp.sums[concrete][half];
        sum.density(sp.transform->density_scale(), psd);
        for (std::size_t band = 0; band + 1 < kBandEdgesHz.size(); ++band) {
          double power = 0;
          for (std::size_t k = 0; k < psd.size(); ++k) {
            const double hz = static_cast<double>(k) * df;
            if (hz >= kBandEdgesHz[band] && hz < kBandEdgesHz[band + 1]) power += psd[k] * df;
          }
          const bool seen = sum.segments() >= 4 && power > 0 && kBandEdgesHz[band + 1] < sp.config.fs_hz / 2;
          f.push_back({"psd_db:" + sp.name, band_name(concrete == 1, band), static_cast<std::uint8_t>(half),
                       seen ? 10.0 * std::log10(power) : kNaN});
        }
      }
    }
    // Levels relative to the sensor's own mean: each part's sensitivity is off by up to 1 %, which
    // moves all its bands together and says nothing about the truck.
    double sum = 0, n = 0;
    for (std::size_t i = first; i < f.size(); ++i) {
      if (std::isfinite(f[i].value)) sum += f[i].value, n += 1;
    }
    for (std::size_t i = first; i < f.size() && n > 0; ++i) f[i].value -= sum / n;
  }
  RunConditions& c = out.conditions;
  c.duration_s = s.started ? to_seconds(s.last - s.first) : 0.0;
  c.mean_speed_mps = s.speed_all.mean;
  c.speed_samples = s.speed_all.n;
  c.first_speed_mps = s.first_speed_mps;
  if (s.speed_all.n > 0) c.disengaged_share = s.disengaged / static_cast<double>(s.speed_all.n);
  if (s.temp_n > 0) {
    c.air_temp_c = s.temp_sum / s.temp_n;
    const double n = s.temp_n, mt = s.temp_t.mean;
    const double sxx = s.temp_tt - n * mt * mt;
    // A drift is fitted only over a long enough run: below 10 minutes it is the station's noise.
    if (sxx > 0 && c.duration_s > 600) c.temp_drift_c_per_h = (s.temp_tv - n * mt * c.air_temp_c) / sxx;
  }
  if (s.pressure_n > 0) c.pressure_pa = s.pressure_sum / s.pressure_n;
  if (s.wind_count > 0) {
    const double e = s.wind_e / s.wind_count, n = s.wind_n / s.wind_count;
    c.wind_speed_mps = std::hypot(e, n);
    c.wind_from_deg = std::fmod(std::atan2(e, n) * 180.0 / std::numbers::pi + 360.0, 360.0);
  }
  c.weather_samples = static_cast<std::size_t>(s.temp_n + s.wind_count);
  c.wind_trace = running_means(s.wind, 5.0);
  if (s.first_fix) {
    c.have_fix = true;
    c.first_lat_deg = s.first_fix->lat_deg;
    c.first_lon_deg = s.first_fix->lon_deg;
  }
  return out;
}

}  // namespace roadload::gap
