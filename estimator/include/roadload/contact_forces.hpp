#pragma once
// Tire contact force per axle from the accelerometers, Eq. 2.1 of the seed report:
//
//     F_z = (M_w + M_c) g cos(grade) + M_w a_w + M_c a_c
//
// M_w is the axle's unsprung mass, M_c its sprung share (static axle load - M_w), a_w the vertical
// acceleration of the axle (its axle accelerometer) and a_c that of the body above it (a frame
// accelerometer). The static part comes from the recorded axle load and the grade, never from the
// accelerometers' mean: a MEMS part's offset (+-25 mg) and gain (+-1 %) make its absolute reading
// worth +-250 N per tonne. The dynamic part M_w a_w + M_c a_c comes from each sensor's deviation
// around its own slow running mean (ContactConfig::highpass_hz).
//
// Pure computation: no I/O, no clocks. Storage is sized at construction; push() never allocates.
// Docs: docs/estimator.md, "Contact forces (Eq. 2.1)".
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "roadload/parse_error.hpp"
#include "roadload/running_stats.hpp"
#include "roadload/samples.hpp"
#include "roadload/time.hpp"
#include "roadload/vehicle.hpp"

namespace roadload {

// One axle as Eq. 2.1 needs it, with the vehicle's suspension for the dissipation (Eq. 2.7-2.8).
struct AxleContact {
  std::string name;               // the vehicle's axle name: "front", "drive1", ...
  double load_kg = 0;             // static axle load
  double unsprung_kg = 0;         // M_w
  double sprung_kg = 0;           // M_c = load_kg - unsprung_kg
  double position_m = 0;          // behind the front axle
  std::uint8_t axle_sensor = 0;   // accelerometer on the axle (sensor id of accel.csv)
  std::uint8_t frame_sensor = 0;  // accelerometer on the frame above it, or the nearest one
  std::string frame_of;           // axle whose frame sensor is used: == name when the axle has its own
  double frame_ahead_m = 0;       // how far that axle is ahead of this one (a tandem's trailing axle on its leader's frame)
  AxleSuspension suspension;
};

struct AxleLayout {
  std::vector<AxleContact> axles;    // front to rear, at most kMaxContactAxles
  std::vector<std::string> skipped;  // "trailer2: no accelerometer at 'trailer-axle2-left'" (lenient build only)
};

// What the layout builder reads of a [[sensor]] table entry.
struct SensorPlacement {
  std::int64_t id = 0;
  std::string_view kind;      // only "accelerometer" (or empty) is considered
  std::string_view position;  // "tractor-front-axle-left", ...
};

inline constexpr std::size_t kMaxContactAxles = 8;

struct LayoutOptions {
  // false: every axle of the vehicle must have an axle accelerometer and a frame accelerometer on
  // its unit, or the build fails naming the first one missing.
  // true: such axles are left out and listed in AxleLayout::skipped; it still fails if none is left.
  bool skip_axles_without_sensors = false;
};

// Builds the layout from the [[sensor]] table and the vehicle's axles. Sensors: kind
// accelerometer, position "<axle_mount>-left" (else "-right"); the lowest id wins when two share a
// position. An axle without its own frame sensor uses the frame sensor of the same unit nearest to
// it along the truck, same side first: a tandem's trailing axle uses its leader's frame.
// ContactForces then reads that frame's motion delayed by the spread over the speed
// (ContactConfig::delay_borrowed_frames).
// Errors (ParseError with file = source): the missing sensor ("[[sensor]] position"
// 'tractor-drive2-axle-left' for axle drive2), or an unsprung mass not below the axle load.
Parsed<AxleLayout> build_axle_layout(std::span<const SensorPlacement> sensors, const Vehicle& vehicle,
                                     std::string_view source = "meta.toml", LayoutOptions options = {});

struct ContactConfig {
  // Each sensor's running mean (its static reading: g cos(grade) x gain + offset) is a first-order
  // low-pass at this cut-off; the deviation from it is the dynamic acceleration. 0.05 Hz is 30x
  // below the 1.5-1.6 Hz body modes: amplitude 0.9994, phase lead 1.9 deg at 1.5 Hz; time constant
  // 3.2 s. Until 1/n drops below the filter's weight the mean is the plain average of the samples
  // so far, so a sensor's offset is gone within a second or two instead of 5 time constants.
  double highpass_hz = 0.05;
  Seconds warmup{5.0};            // samples this soon after a sensor's (re)start are not accumulated
  Seconds max_pair_age{0.005};    // axle and frame samples farther apart in time are not paired (6 periods at 1200 Hz)
  Seconds gap_reset{0.5};         // a sensor silent this long restarts its running mean and warm-up
  Seconds max_position_age{2.0};  // a set_cell older than this no longer places the truck
  // A borrowed frame sensor is read frame_ahead_m / speed earlier. Eq. 2.1 is the report's quarter
  // car (Fig. 2.1): one sprung share per axle, moved by that axle's road. A tandem's trailing axle
  // rolls over the leading axle's road frame_ahead_m / speed later, and the two suspensions of a
  // load-equalising tandem are alike, so its body moves as the leading one did then. Without the
  // delay the sprung term is the leading axle's body *now*: it no longer cancels the trailing
  // axle's own suspension force, and the dynamic std comes out ~12 % high (simulated Mainline,
  // 30 mph). On a real tandem under one rigid frame the bodies differ by pitch as well; a frame
  // sensor per axle is better than either.
  bool delay_borrowed_frames = true;
  double min_delay_speed_mps = 1.0;  // slower (or no speed): the borrowed frame is read undelayed
  double gravity_mps2 = 9.80665;
};

// Count, mean and (sample) standard deviation, Welford's update.
struct ForceStats {
  std::uint64_t count = 0;
  double mean_n = 0;
  double std_n = 0;
};

struct AxleForceStats {
  ForceStats fz;       // total contact force F_z
  ForceStats dynamic;  // its dynamic part M_w a_w + M_c a_c
};

struct ContactCounters {
  std::uint64_t paired = 0;       // axle samples that became a force (whether or not in a cell)
  std::uint64_t no_frame = 0;     // no frame sample yet (or the frame sensor is warming up)
  std::uint64_t stale_frame = 0;  // no frame sample within max_pair_age of the time read
  std::uint64_t warming_up = 0;   // the axle sensor itself warming up
  std::uint64_t no_cell = 0;      // paired, but the truck was in no cell (or its position was stale)
  // Paired with a borrowed frame undelayed: speed unknown, stale or below min_delay_speed_mps, the
  // delay beyond the frame history kept (kFrameHistory samples), or the frame sensor behind the axle.
  std::uint64_t undelayed = 0;
};

// The latest force of one axle, for a per-tick F_RR.
struct AxleForce {
  CaptureTime t{};
  double fz_n = 0;
  double dynamic_n = 0;
  bool valid = false;  // false until the axle's first paired sample
};

// F_RR = CRR x F_z with its dynamic part included (Eq. 2.2's rolling term per axle).
constexpr double rolling_resistance_n(double crr, double fz_n) { return crr * fz_n; }
// The same for a cell's statistics: mean and standard deviation scale with CRR.
ForceStats rolling_resistance(const ForceStats& fz, double crr);

class ContactForces {
 public:
  // `cell_count` cells, indices 0 .. cell_count-1 in set_cell.
  ContactForces(AxleLayout layout, std::size_t cell_count, ContactConfig config = {});

  // Where the truck is from capture time t on: every axle in `cell` (-1: in none), on `grade_rad`
  // (the static part is (M_w + M_c) g cos(grade)), at `speed_mps` (for the borrowed frames' delay;
  // NaN if unknown). Call it whenever the position is updated (each wheel-speed tick), interleaved
  // with push() in capture-time order.
  void set_cell(CaptureTime t, int cell, double grade_rad, double speed_mps);
  // The same with each axle in its own cell (cells[i] for layout().axles[i]; the cell under that
  // axle: axles 17.7 m apart are often in different cells). Missing entries count as -1.
  void set_axle_cells(CaptureTime t, std::span<const int> cells, double grade_rad, double speed_mps);

  // One accelerometer sample, in capture-time order across sensors. Only z is used. Samples of
  // sensors not in the layout are counted and ignored.
  void push(const AccelSample& s);

  const AxleLayout& layout() const { return layout_; }
  std::size_t axle_count() const { return layout_.axles.size(); }
  std::size_t cell_count() const { return cell_count_; }
  AxleForceStats cell(std::size_t cell, std::size_t axle) const;
  AxleForceStats trip(std::size_t axle) const;  // every paired sample of the drive, in a cell or not
  const ContactCounters& counters(std::size_t axle) const { return counters_[axle]; }
  std::uint64_t unknown_sensor_samples() const { return unknown_; }
  std::uint64_t sensor_restarts() const { return restarts_; }  // gaps longer than gap_reset
  AxleForce latest(std::size_t axle) const { return latest_[axle]; }

 private:
  static ForceStats stats(const RunningStats& r);
  struct Acc {
    RunningStats fz, dynamic;
  };
  // Running mean of one sensor's z and its latest deviation from it.
  struct SensorState {
    bool started = false;
    CaptureTime first{}, last{};
    std::uint64_t n = 0;
    double mean = 0;
    double deviation = 0;  // latest z - running mean
  };
  static constexpr std::int16_t kNone = -1;

 public:
  // Frame samples kept per borrowed frame sensor: 0.85 s at 1200 Hz, a 1.32 m spread down to 1.6 m/s.
  static constexpr std::size_t kFrameHistory = 1024;

 private:
  struct History {
    std::array<std::int64_t, kFrameHistory> t_ns{};
    std::array<double, kFrameHistory> deviation{};
    std::size_t next = 0, size = 0;
    enum class Found { ok, stale, not_kept };
    void add(CaptureTime t, double d);
    // The deviation at time t, interpolated between the samples around it (across a gap in the
    // samples: the nearer one, if within max_gap); stale when no sample is that close; not_kept
    // when t is before the oldest sample kept.
    Found at(CaptureTime t, Seconds max_gap, double& out) const;
  };
  struct SensorRole {
    std::int16_t axle = kNone;  // axle whose axle sensor this is
    bool frame = false;         // some axle's frame sensor
    bool used = false;
    std::int16_t history = kNone;  // index into histories_ when some axle borrows this frame
  };

  bool update_sensor(SensorState& st, const AccelSample& s);  // false while warming up
  void add_force(std::size_t axle, CaptureTime t, double a_w, double a_c);

  AxleLayout layout_;
  std::size_t cell_count_;
  ContactConfig config_;
  double alpha_tau_s_;
  std::array<SensorRole, 256> roles_{};
  std::array<SensorState, 256> sensors_{};
  std::array<int, kMaxContactAxles> cell_{};
  CaptureTime position_t_{};
  bool position_set_ = false;
  double cos_grade_ = 1.0;
  double speed_mps_ = 0.0;
  std::vector<History> histories_;  // one per borrowed frame sensor, sized at construction
  std::vector<Acc> cells_;          // cell_count x axles
  std::array<Acc, kMaxContactAxles> trip_{};
  std::array<ContactCounters, kMaxContactAxles> counters_{};
  std::array<AxleForce, kMaxContactAxles> latest_{};
  std::uint64_t unknown_ = 0;
  std::uint64_t restarts_ = 0;
};

}  // namespace roadload
