#pragma once
// The accelerometers' spectra of a drive, on board and streaming (seed report Sect. 2.3, 6.2-6.3):
// every sensor onto one time grid (spectra/sensor_grid.hpp), then short segments per axle for the
// dampers' and tires' dissipation per cell (spectra/suspension_spectra.hpp) and long segments per
// sensor for modes and the joint line per pavement (spectra/mode_spectra.hpp).
//
// Pure computation. Storage is sized at construction; push() and set_axle_cells() never allocate.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "roadload/contact_forces.hpp"
#include "roadload/samples.hpp"
#include "roadload/spectra/mode_spectra.hpp"
#include "roadload/spectra/placement_history.hpp"
#include "roadload/spectra/sensor_grid.hpp"
#include "roadload/spectra/suspension_spectra.hpp"

namespace roadload {

struct VibrationSensor {
  std::uint8_t id = 0;
  std::string name;    // TLF1 ...
  double rate_hz = 0;  // nominal output rate
};

struct VibrationConfig {
  spectra::GridConfig grid;
  spectra::SuspensionConfig suspension;
  spectra::ModeConfig modes;
  std::size_t placement_history = 1024;  // 20 s of placements at 50 Hz: longer than a mode segment
};

// Summed over the axles (the simulator's truth sums them the same way).
struct DynamicPower {
  double damper_w = 0;        // Eq. 2.8 on the relative velocity
  double damper_accel_w = 0;  // Eq. 2.8 on the relative acceleration's periodogram (reads high)
  double tire_w = 0;          // on the tire's deflection rate, from the contact force
  double tire_eq27_w = 0;     // Eq. 2.7: the axle's absolute velocity
  double segments = 0;        // fewest (fractional) segments of any axle: 0 when nothing was measured
  double total_w() const { return damper_w + tire_w; }
};

class VibrationAnalysis {
 public:
  // Axles and masses from the contact-force layout; every accelerometer of `sensors` gets mode
  // spectra, placed over the axle it is mounted on (or the front axle). `cell_group[c]` is the
  // pavement group of cell c (-1: none), groups 0 .. group_count - 1.
  VibrationAnalysis(const AxleLayout& layout, std::span<const VibrationSensor> sensors, std::size_t cell_count,
                    std::vector<int> cell_group, std::size_t group_count, VibrationConfig config = {});

  // Where the truck is from t on: the front axle at s_front_m along the route, each axle in
  // cells[i] (layout().axles[i]), at speed_mps. Unknown speed or position: NaN.
  void set_axle_cells(CaptureTime t, std::span<const int> cells, double speed_mps, double s_front_m);
  void push(const AccelSample& s);

  DynamicPower cell_power(std::size_t cell) const;
  DynamicPower trip_power() const;
  // Since the last clear_window(), for a live status every few seconds.
  DynamicPower window_power() const;
  void clear_window() { suspension_.clear_window(); }
  // Mean over a group's cells, each weighted by its segments (its time).
  DynamicPower group_power(std::size_t group) const;
  const std::vector<int>& cell_group() const { return cell_group_; }

  const AxleLayout& layout() const { return layout_; }
  const spectra::SuspensionSpectra& suspension() const { return suspension_; }
  const spectra::ModeSpectra& modes() const { return modes_; }
  const spectra::SensorGrid& grid() const { return grid_; }

 private:
  AxleLayout layout_;
  std::vector<int> cell_group_;
  spectra::SensorGrid grid_;
  spectra::PlacementHistory history_;
  spectra::SuspensionSpectra suspension_;
  spectra::ModeSpectra modes_;
};

}  // namespace roadload
