#pragma once
// Engine losses from a standstill calibration: the truck stands in neutral while the engine is
// held at a series of speeds. Nothing then reaches the flywheel, so the indicated torque EEC1
// reports (SPN 513 with its 1/8 % fraction, SPN 4154) is the engine's friction plus the
// accessories it drives, at that speed. Each steady hold becomes one point of the map.
#include <deque>
#include <optional>
#include <vector>

#include "roadload/can_frame.hpp"
#include "roadload/drive_signals.hpp"
#include "roadload/j1939/assembler.hpp"
#include "roadload/model/engine_losses.hpp"
#include "roadload/running_stats.hpp"
#include "roadload/time.hpp"

namespace roadload {

struct EngineLossCalibrationConfig {
  double steady_band_rpm = 10;  // a hold ends when the speed leaves its first reading by more
  Seconds settle{3};            // the governor's approach, left out of each hold
  Seconds tail{0.5};            // and the start of the next approach, before it leaves the band
  Seconds min_hold{5};          // shorter holds (after settling) give no point
  Seconds max_gap{1};           // a longer silence ends a hold
  double max_speed_mps = 0.1;   // standing still
};

// One reading of the engine, in N m at the crankshaft.
struct EngineReading {
  CaptureTime t{};
  double rpm = 0;
  double indicated_nm = 0;      // EEC1 actual torque
  double eec3_loss_nm = 0;      // EEC3 friction + parasitic
  double eec3_friction_nm = 0;  // EEC3 friction alone
  double resolution_nm = 0;     // one step of the indicated torque: 1/8 % or 1 % of the reference
  bool standing = false;        // still, in neutral or declutched
};

// One hold: its point, and what EEC3 said of friction and parasitic losses there, for comparison.
struct EngineLossHold {
  model::EngineLossPoint point;
  double eec3_loss_nm = 0;      // mean of EEC3 friction + parasitic over the hold
  double eec3_friction_nm = 0;  // mean of EEC3 friction alone
  double duration_s = 0;
  std::uint64_t samples = 0;
};

class EngineLossCalibration {
 public:
  explicit EngineLossCalibration(EngineLossCalibrationConfig config = {}) : config_(config) {}

  void push(const EngineReading& r);
  // Ends the last hold and gives every hold found, in increasing engine speed (holds within the
  // steady band of each other are one), each with its friction (split_losses) where
  // fit_friction_curve finds a curve.
  std::vector<EngineLossHold> finish();

 private:
  void close_hold();
  void keep(const EngineReading& r);

  EngineLossCalibrationConfig config_;
  std::vector<EngineLossHold> holds_;
  bool open_ = false;
  double anchor_rpm_ = 0, resolution_nm_ = 0;
  std::deque<EngineReading> tail_;
  CaptureTime start_{}, last_{};
  RunningStats rpm_, torque_, eec3_, eec3_friction_;
  CaptureTime first_kept_{}, last_kept_{};
};

// The calibration fed from a recording's frames: every EEC1 reading becomes an EngineReading.
class EngineLossFrames {
 public:
  explicit EngineLossFrames(const j1939::Database& db, EngineLossCalibrationConfig config = {});
  void push(const CanFrame& frame);
  std::vector<EngineLossHold> finish() { return calibration_.finish(); }

  // What the readings were: all, standing in neutral, before EC1's reference torque (unusable).
  std::uint64_t readings = 0, standing = 0, no_reference = 0;
  bool whole_percent = false;  // some reading came without EEC1's fraction

 private:
  j1939::MessageAssembler assembler_;
  DriveSignals signals_;
  const j1939::MessageDef* eec1_;
  double max_speed_mps_;
  EngineLossCalibration calibration_;
};

// How the calibrated losses split into friction and accessories. EEC3's friction (SPN 514) comes in
// whole percent of the reference torque: at one engine speed it is up to 12 N m off on the MnROAD
// engine, a third of what its accessories take at cruise. Over the holds it is a staircase whose
// steps stand where the true friction crosses each half percent, so the crossings (the midpoints
// between holds on either side of a step) are points of the true curve to within half the holds'
// spacing. Friction is fitted through them as the usual mean-effective-pressure form, quadratic in
// engine speed; the accessories are the measured loss less it (split_losses).
struct FrictionCurve {
  double a_nm = 0, b_nm_per_krpm = 0, c_nm_per_krpm2 = 0;
  std::size_t crossings = 0;
  double at(double rpm) const;
};
// Nothing with fewer than three crossings: the split then stays EEC3's.
std::optional<FrictionCurve> fit_friction_curve(const std::vector<EngineLossHold>& holds);
// Sets each hold's friction: its loss less the accessories, which are the loss less the curve
// smoothed over +-150 rpm of holds. EEC1's 1/8 % rounding differs from hold to hold (+-1.5 N m, 4 %
// of the accessories at cruise); smoothed, it stays with the friction and so in the engine's row of
// the fuel breakdown, where it is a thousandth.
void split_losses(const FrictionCurve& curve, std::vector<EngineLossHold>& holds);

// The map `roadload analyze --engine-losses` uses, from the holds.
model::EngineLossMap engine_loss_map(const std::vector<EngineLossHold>& holds);

}  // namespace roadload
