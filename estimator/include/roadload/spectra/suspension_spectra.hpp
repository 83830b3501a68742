#pragma once
// Dynamic rolling resistance per axle and per cell from the accelerometer spectra (seed report
// Eq. 2.5-2.8). For each axle: the axle accelerometer's auto-spectrum S_uu, the frame's above it
// S_ss and their cross-spectrum S_us, on the common grid (sensor_grid.hpp), so that
//     S_rel = S_uu + S_ss - 2 Re S_us             relative acceleration across the suspension
//     S_F   = M_w^2 S_uu + M_c^2 S_ss + 2 M_w M_c Re S_us   dynamic tire force (Eq. 2.1)
// and the same three of the velocities integrated on the grid (sensor_grid.hpp, VelocityIntegrator),
// from which the dashpots' powers come: d x integral of S_v = d x integral of S_a / (2 pi f)^2
// with the 1 / (2 pi f)^2 applied before the window. Eq. 2.8 evaluated on the acceleration's
// periodogram is kept beside it (damper_accel_w): it reads high where body modes leak into the
// lowest bins.
// An axle without its own frame sensor reads a borrowed one frame_ahead_m / speed later, as the
// contact forces do (contact_forces.hpp): a delay is a phase e^{-i w tau} on the frame's transform.
// Segments are shared among cells by segment_weights.hpp; powers follow dynamic_power.hpp.
//
// The trip keeps its spectra (the report draws them). The live window and a cell keep only their
// four powers' weighted sums: each power is linear in the spectra's sums, so a segment's power,
// added with the segment's weight in the cell, gives the cell's mean power exactly as its mean
// spectra would, in 40 bytes instead of 12 kB (an hour's 2,000 cells x 6 axles took 25 MB).
//
// Storage is sized at construction; update() never allocates. Readouts allocate.
#include <complex>
#include <cstdint>
#include <string>
#include <vector>

#include "roadload/spectra/cell_leak.hpp"
#include "roadload/spectra/dynamic_power.hpp"
#include "roadload/spectra/placement_history.hpp"
#include "roadload/spectra/segment_weights.hpp"
#include "roadload/spectra/sensor_grid.hpp"
#include "roadload/spectra/welch.hpp"

namespace roadload::spectra {

struct SuspensionAxle {
  std::string name;
  int axle_slot = -1, frame_slot = -1;  // SensorGrid slots of the axle and frame accelerometers
  double frame_ahead_m = 0;             // a borrowed frame sensor's lead along the truck; 0 if its own
  double unsprung_kg = 0, sprung_kg = 0;
  double damper_nspm = 0;         // the vehicle's (AxleSuspension), per axle
  double tire_damping_nspm = 0;   // all tires of the axle
  double tire_stiffness_npm = 0;  // all tires of the axle
};

struct SuspensionConfig {
  // 1.28 s segments at 200 Hz (0.78 Hz bins), 75 % overlap: short enough that a segment's blur
  // (+-8.6 m at 30 mph) stays small against 80-150 m cells; the power integral needs no finer bins
  // because the relative motion has little below the 1.5 Hz body modes.
  std::size_t nperseg = 256;
  std::size_t noverlap = 192;
  PowerBand band;
  double min_delay_speed_mps = 1.0;
  std::int64_t lag_samples = 20;  // a segment is taken once the grid is this far past its end
};

struct AxlePower {
  double segments = 0;           // (fractional) segments averaged
  double damper_w = 0;           // Eq. 2.8: d x integral of the relative velocity's density
  double damper_accel_w = 0;     // Eq. 2.8 on the relative acceleration's periodogram / (2 pi f)^2
  double tire_eq27_w = 0;        // Eq. 2.7: c_t x integral of the axle's absolute velocity density
  double tire_deflection_w = 0;  // c_t on the tire's deflection rate, from S_F (dynamic_power.hpp)
};

// Accelerations in (m/s^2)^2/Hz, the force in N^2/Hz, velocities in (m/s)^2/Hz.
enum class AxleDensity { axle, frame, relative, force, axle_velocity, relative_velocity };

struct SuspensionCounters {
  std::uint64_t segments = 0;       // segment instants taken
  std::uint64_t axle_segments = 0;  // axle x segment pairs averaged
  std::uint64_t missing = 0;        // axle x segment pairs with a sensor's grid values missing
};

class SuspensionSpectra {
 public:
  // `grid`: the rate and the velocity integrator whose response the densities divide out.
  SuspensionSpectra(std::vector<SuspensionAxle> axles, std::size_t cell_count, const SensorGrid& grid, SuspensionConfig config = {});

  void update(const SensorGrid& grid, const PlacementHistory& history);

  std::size_t axle_count() const { return axles_.size(); }
  const SuspensionAxle& axle(std::size_t i) const { return axles_[i]; }
  const WelchConfig& welch() const { return transform_.config(); }
  // The cell's average with what it borrowed from the cells beside it taken out (cell_leak.hpp).
  AxlePower cell_power(std::size_t cell, std::size_t axle) const;
  AxlePower trip_power(std::size_t axle) const { return power(trip_[axle], axle); }
  // Since the last clear_window(): the live status's time window.
  AxlePower window_power(std::size_t axle) const { return mean(window_[axle]); }
  void clear_window();
  std::vector<double> trip_density(std::size_t axle, AxleDensity which) const;
  const SuspensionCounters& counters() const { return counters_; }

 private:
  struct Pair {
    explicit Pair(std::size_t bins) : uu(bins), ss(bins), us(bins) {}
    SpectralSum uu, ss, us;
    void add(std::span<const std::complex<double>> u, std::span<const std::complex<double>> s, double w) {
      uu.add_scaled(u, u, w);
      ss.add_scaled(s, s, w);
      us.add_scaled(u, s, w);
    }
  };
  struct Sums {
    explicit Sums(std::size_t bins) : accel(bins), velocity(bins) {}
    Pair accel, velocity;
  };
  // Each power's coefficient on each bin of |U|^2, |S|^2 and Re(conj(U) S), of the accelerations
  // and of the velocities: [((pair * bins + bin) * 3 + term) * 4 + field], the four powers side by side.
  std::vector<double> power_coefficients(std::size_t axle) const;
  // One segment's power on an axle, from the transforms take() holds (segments = 1).
  AxlePower segment_power(std::size_t axle) const;
  // Powers summed by segment weight, and their mean over the segments.
  static void accumulate(AxlePower& sum, const AxlePower& segment, double weight);
  static AxlePower mean(AxlePower sum);
  // Into `out` (one value per bin) through the scratch spectra below: no heap.
  void density(const Sums& s, std::size_t axle, AxleDensity which, std::span<double> out) const;
  AxlePower power(const Sums& s, std::size_t axle) const;
  void take(const SensorGrid& grid, const PlacementHistory& history, std::int64_t end);
  // The frame's acceleration and velocity transforms delayed by tau_s: one phase per bin for both.
  void delay(std::span<const std::complex<double>> accel, std::span<const std::complex<double>> velocity, double tau_s,
             std::span<std::complex<double>> accel_out, std::span<std::complex<double>> velocity_out) const;

  std::vector<SuspensionAxle> axles_;
  SuspensionConfig config_;
  SegmentTransform transform_;
  SegmentWeights weights_;
  std::vector<Sums> trip_;
  // The live window's and each cell's [cell * axles + axle] segments and powers, summed by weight.
  std::vector<AxlePower> window_, cell_;
  std::vector<std::vector<double>> coefficients_;  // per axle, power_coefficients()
  CellLeaks leaks_;
  std::vector<double> segment_;
  std::vector<std::vector<std::complex<double>>> slot_spectrum_, slot_velocity_;
  std::vector<bool> slot_ok_;
  std::vector<std::complex<double>> delayed_, delayed_velocity_;
  std::vector<double> response_;  // the grid integrator's power response per bin
  // Scratch of density() and power(), sized at construction; one thread uses an instance.
  mutable std::vector<std::complex<double>> scratch_uu_, scratch_ss_, scratch_us_;
  mutable std::vector<double> scratch_density_;
  SegmentSchedule schedule_;
  SuspensionCounters counters_;
};

}  // namespace roadload::spectra
