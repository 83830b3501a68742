#include "roadload/spectra/mode_spectra.hpp"

#include <cmath>
#include <limits>

namespace roadload::spectra {

ModeSpectra::ModeSpectra(std::vector<ModeSensor> sensors, std::vector<int> cell_group, std::size_t group_count, double grid_hz,
                         ModeConfig config)
    : sensors_(std::move(sensors)),
      cell_group_(std::move(cell_group)),
      group_count_(group_count),
      config_(config),
      transform_({grid_hz, config.nperseg, config.noverlap}),
      distance_transform_({1.0 / config.distance_step_m, config.distance_nperseg, config.distance_noverlap}),
      weights_(hann_periodic(config.nperseg)),
      distance_window_sq_(hann_periodic(config.distance_nperseg)),
      segment_(config.nperseg),
      distance_segment_(config.distance_nperseg),
      masked_segment_(config.distance_nperseg),
      distance_group_(config.distance_nperseg),
      spectrum_(bin_count(transform_.config())),
      distance_spectrum_(bin_count(distance_transform_.config())),
      group_weight_(group_count + 1),
      schedule_(config.nperseg, config.nperseg - config.noverlap, config.lag_samples) {
  for (double& w : distance_window_sq_) w *= w;
  const std::size_t n = (group_count_ + 1) * sensors_.size();
  time_.assign(n, SpectralSum(bin_count(transform_.config())));
  spatial_.assign(n, SpectralSum(bin_count(distance_transform_.config())));
  DistanceStream blank;
  blank.values.assign(config_.distance_nperseg, 0.0);
  blank.cells.assign(config_.distance_nperseg, -1);
  streams_.assign(sensors_.size(), blank);
  speed_sum_.assign(group_count_ + 1, 0.0);
  speed_weight_.assign(group_count_ + 1, 0.0);
}

void ModeSpectra::update(const SensorGrid& grid, const PlacementHistory& history) {
  if (grid.latest() == std::numeric_limits<std::int64_t>::min()) return;
  if (!started_) {
    next_distance_index_ = grid.latest();
    started_ = true;
  }
  schedule_.run(grid, [&](std::int64_t end) { take_time(grid, history, end); });
  // Every stream moves through the same grid instants: the position is looked up once for all.
  for (; next_distance_index_ <= grid.latest() - config_.lag_samples; ++next_distance_index_) {
    const CaptureTime t = grid.time_of(next_distance_index_);
    const double s_m = history.distance_at(t);
    const Placement* p = history.at(t);
    for (std::size_t i = 0; i < sensors_.size(); ++i) advance_distance(i, grid, next_distance_index_, s_m, p);
  }
}

// Group weights of one segment: the trip takes it whole, each group its cells' shares.
void ModeSpectra::share_groups(const SegmentShares& shares) {
  for (double& g : group_weight_) g = 0;
  group_weight_[0] = 1.0;
  for (std::size_t s = 0; s < shares.count; ++s) {
    const int c = shares.share[s].cell;
    const int g = c >= 0 && static_cast<std::size_t>(c) < cell_group_.size() ? cell_group_[static_cast<std::size_t>(c)] : -1;
    if (g >= 0) group_weight_[static_cast<std::size_t>(g) + 1] += shares.share[s].weight;
  }
}

void ModeSpectra::take_time(const SensorGrid& grid, const PlacementHistory& history, std::int64_t end) {
  const CaptureTime t0 = grid.time_of(end - static_cast<std::int64_t>(config_.nperseg) + 1);
  bool speed_counted = false;  // once per segment instant, by the first sensor that has it
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    const ModeSensor& m = sensors_[i];
    if (m.slot < 0 || !grid.copy(static_cast<std::size_t>(m.slot), end, segment_)) continue;
    transform_.transform(segment_, spectrum_);
    const SegmentShares shares = weights_.shares(history, m.axle, t0, grid.config().period_ns);
    share_groups(shares);
    for (std::size_t g = 0; g < group_weight_.size(); ++g) {
      const double w = group_weight_[g];
      if (w <= 0) continue;
      time_[g * sensors_.size() + i].add_scaled(spectrum_, spectrum_, w);
      if (!speed_counted && std::isfinite(shares.speed_mps)) {
        speed_sum_[g] += w * shares.speed_mps;
        speed_weight_[g] += w;
      }
    }
    speed_counted = speed_counted || std::isfinite(shares.speed_mps);
  }
}

// Grid instant n at time t, the front axle at s_m (NaN if unknown) with placement p: one step of
// sensor i's stream along the road.
void ModeSpectra::advance_distance(std::size_t i, const SensorGrid& grid, std::int64_t n, double s_m, const Placement* p) {
  const ModeSensor& m = sensors_[i];
  DistanceStream& d = streams_[i];
  double value = 0;
  if (m.slot < 0 || !grid.value_at(static_cast<std::size_t>(m.slot), n, value) || !std::isfinite(s_m)) {
    d.primed = false;  // a hole in the sensor or the position: start again after it
    d.total = 0;
    return;
  }
  const std::size_t len = config_.distance_nperseg, hop_n = config_.distance_nperseg - config_.distance_noverlap;
  const double ds = config_.distance_step_m;
  if (d.primed && s_m > d.prev_s) {
    const int cell = p != nullptr && m.axle < kMaxPlacedAxles ? p->cell[m.axle] : -1;
    for (; d.next_s <= s_m; d.next_s += ds) {
      const double frac = (d.next_s - d.prev_s) / (s_m - d.prev_s);
      const std::size_t k = d.total % len;
      d.values[k] = d.prev_value + frac * (value - d.prev_value);
      d.cells[k] = cell;
      ++d.total;
      if (d.total >= len && (d.total - len) % hop_n == 0) take_distance(i);
    }
  } else if (!d.primed) {
    d.next_s = std::ceil(s_m / ds) * ds;
  }
  if (!d.primed || s_m > d.prev_s) {
    d.prev_s = s_m;
    d.prev_value = value;
  }
  d.primed = true;
}

// The trip takes the segment whole. A group takes only its own stretches of it, the rest zeroed:
// a segment is longer than most cells, and a weighted share of the whole would carry one
// pavement's joint lines into its neighbours' spectra. The masked periodogram holds about
// `share` of the group's density, so it is added as `share` of a segment.
void ModeSpectra::take_distance(std::size_t i) {
  DistanceStream& d = streams_[i];
  const std::size_t n = config_.distance_nperseg, oldest = d.total % n;
  double total = 0;
  for (std::size_t j = 0, k = oldest; j < n; ++j, k = k + 1 == n ? 0 : k + 1) {
    distance_segment_[j] = d.values[k];
    const int c = d.cells[k];
    distance_group_[j] = c >= 0 && static_cast<std::size_t>(c) < cell_group_.size() ? cell_group_[static_cast<std::size_t>(c)] : -1;
    total += distance_window_sq_[j];
  }
  distance_transform_.transform(distance_segment_, distance_spectrum_);
  spatial_[index(i, -1)].add_scaled(distance_spectrum_, distance_spectrum_, 1.0);
  for (int g = 0; g < static_cast<int>(group_count_); ++g) {
    double share = 0, sum = 0, count = 0;
    for (std::size_t j = 0; j < n; ++j) {
      if (distance_group_[j] != g) continue;
      share += distance_window_sq_[j];
      sum += distance_segment_[j];
      ++count;
    }
    share /= total;
    if (share <= 0) continue;
    const double mean = sum / count;
    for (std::size_t j = 0; j < n; ++j) masked_segment_[j] = distance_group_[j] == g ? distance_segment_[j] - mean : 0.0;
    distance_transform_.transform(masked_segment_, distance_spectrum_);
    for (auto& x : distance_spectrum_) x /= share;
    spatial_[index(i, g)].add_scaled(distance_spectrum_, distance_spectrum_, share);
  }
}

std::vector<double> ModeSpectra::density(std::size_t sensor, int group) const {
  const SpectralSum& s = time_[index(sensor, group)];
  std::vector<double> out(s.bins());
  s.density(transform_.density_scale(), out);
  return out;
}

double ModeSpectra::segments(std::size_t sensor, int group) const { return time_[index(sensor, group)].segments(); }

std::vector<double> ModeSpectra::spatial_density(std::size_t sensor, int group) const {
  const SpectralSum& s = spatial_[index(sensor, group)];
  std::vector<double> out(s.bins());
  s.density(distance_transform_.density_scale(), out);
  return out;
}

double ModeSpectra::spatial_segments(std::size_t sensor, int group) const { return spatial_[index(sensor, group)].segments(); }

double ModeSpectra::mean_speed_mps(int group) const {
  const auto g = static_cast<std::size_t>(group + 1);
  return speed_weight_[g] > 0 ? speed_sum_[g] / speed_weight_[g] : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace roadload::spectra
