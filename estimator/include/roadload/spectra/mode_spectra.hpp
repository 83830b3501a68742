#pragma once
// Long-segment spectra of every accelerometer for its vibration modes and the joint line: per
// sensor, over the trip and per group of cells (a pavement type), in time frequency (Hz) and in
// spatial frequency (cycles per metre). For the spatial spectra each sensor's grid values are
// resampled at equal steps of distance travelled (the front axle's position from the placements),
// so a joint line at 1/L stays one line while the cruise control wanders, where in Hz it would
// smear over v/L +- dv/L, and a segment can span several hundred metres at any speed.
//
// Storage is sized at construction; update() never allocates. Readouts allocate.
#include <complex>
#include <cstdint>
#include <string>
#include <vector>

#include "roadload/spectra/placement_history.hpp"
#include "roadload/spectra/segment_weights.hpp"
#include "roadload/spectra/sensor_grid.hpp"
#include "roadload/spectra/welch.hpp"

namespace roadload::spectra {

struct ModeConfig {
  std::size_t nperseg = 2048;  // 10.24 s at 200 Hz: 0.098 Hz bins, 3 % of the 2.9 Hz joint line
  std::size_t noverlap = 1024;
  // Spatial: 8 cm steps keep the grid's 80 Hz band unaliased up to 23 m/s and resolve 6 cycles/m;
  // 4096 steps (328 m) give bins of 0.003 cycles/m, where a 15 ft panel's line stands 1.5 % wide.
  double distance_step_m = 0.08;
  std::size_t distance_nperseg = 4096;
  std::size_t distance_noverlap = 2048;
  std::int64_t lag_samples = 20;
};

struct ModeSensor {
  std::string name;      // TLF1 ...
  int slot = -1;         // SensorGrid slot
  std::size_t axle = 0;  // whose cell the sensor is over (placement index)
};

class ModeSpectra {
 public:
  // `cell_group[c]`: the group of cell c (e.g. its surface), or -1; groups 0 .. group_count-1.
  ModeSpectra(std::vector<ModeSensor> sensors, std::vector<int> cell_group, std::size_t group_count, double grid_hz,
              ModeConfig config = {});

  void update(const SensorGrid& grid, const PlacementHistory& history);

  const WelchConfig& welch() const { return transform_.config(); }
  const WelchConfig& spatial_welch() const { return distance_transform_.config(); }
  const ModeConfig& config() const { return config_; }
  std::size_t sensor_count() const { return sensors_.size(); }
  const ModeSensor& sensor(std::size_t i) const { return sensors_[i]; }
  std::size_t group_count() const { return group_count_; }
  // One-sided density per Hz; group -1 is the whole trip.
  std::vector<double> density(std::size_t sensor, int group) const;
  double segments(std::size_t sensor, int group) const;
  // One-sided density per cycle/m on bins of spatial_welch().fs_hz / nperseg cycles/m.
  std::vector<double> spatial_density(std::size_t sensor, int group) const;
  double spatial_segments(std::size_t sensor, int group) const;
  double mean_speed_mps(int group) const;

 private:
  // One sensor resampled along the road.
  struct DistanceStream {
    bool primed = false;  // the previous grid value and distance are known
    double prev_value = 0, prev_s = 0, next_s = 0;
    std::size_t total = 0;       // distance samples since the last restart
    std::vector<double> values;  // ring of distance_nperseg
    std::vector<int> cells;
  };
  std::size_t index(std::size_t sensor, int group) const { return static_cast<std::size_t>(group + 1) * sensors_.size() + sensor; }
  void take_time(const SensorGrid& grid, const PlacementHistory& history, std::int64_t end);
  void advance_distance(std::size_t sensor, const SensorGrid& grid, std::int64_t n, double s_m, const Placement* p);
  void take_distance(std::size_t sensor);
  void share_groups(const SegmentShares& shares);

  std::vector<ModeSensor> sensors_;
  std::vector<int> cell_group_;
  std::size_t group_count_;
  ModeConfig config_;
  SegmentTransform transform_, distance_transform_;
  SegmentWeights weights_;
  std::vector<double> distance_window_sq_;
  std::vector<SpectralSum> time_, spatial_;  // [(group + 1) * sensors + sensor]
  std::vector<DistanceStream> streams_;
  std::vector<double> speed_sum_, speed_weight_;  // per group + 1
  std::vector<double> segment_, distance_segment_, masked_segment_;
  std::vector<int> distance_group_;  // per sample of distance_segment_, -1 outside every group
  std::vector<std::complex<double>> spectrum_, distance_spectrum_;
  std::vector<double> group_weight_;
  SegmentSchedule schedule_;
  bool started_ = false;                  // the distance streams begin at the first grid value
  std::int64_t next_distance_index_ = 0;  // the grid instant all distance streams read next
};

}  // namespace roadload::spectra
