#pragma once
// The J1939 quantities the force balance needs, kept as the latest value of each with its stamp.
// Signals are looked up by name in the definitions once, at construction; a message updates only
// the quantities it carries, and a not-available value clears nothing (the last good one stays,
// with its old stamp, so staleness is visible).
#include <array>
#include <optional>

#include "roadload/can_frame.hpp"
#include "roadload/j1939/assembler.hpp"
#include "roadload/j1939/database.hpp"
#include "roadload/model/longitudinal.hpp"
#include "roadload/time.hpp"

namespace roadload {

enum class Quantity : std::size_t {
  engine_speed_rpm,
  actual_torque_pct,     // EEC1 SPN 513 + the SPN 4154 fraction
  friction_torque_pct,   // EEC3 SPN 514
  parasitic_torque_pct,  // EEC3 SPN 2978
  reference_torque_nm,   // EC1 SPN 544
  wheel_speed_mps,       // CCVS1 SPN 84
  gear_ratio,            // ETC2 SPN 526
  current_gear,          // ETC2 SPN 523
  brake_switch,          // CCVS1 SPN 597
  clutch_switch,         // CCVS1 SPN 598
  driveline_engaged,     // ETC1 SPN 560
  shift_in_process,      // ETC1 SPN 574
  ambient_temp_c,        // AMB SPN 171
  pressure_pa,           // AMB SPN 108
  fuel_rate_lph,         // LFE1 SPN 183
  fan_speed_rpm,         // FD1 SPN 1639
  count
};
inline constexpr std::size_t kQuantityCount = static_cast<std::size_t>(Quantity::count);

struct Reading {
  double value = 0;
  CaptureTime t{};
  bool seen = false;
};

class DriveSignals {
 public:
  explicit DriveSignals(const j1939::Database& db);
  void push(const j1939::Message& m);
  const Reading& get(Quantity q) const { return readings_[static_cast<std::size_t>(q)]; }
  // Whether EEC1's actual torque came with its 1/8 % fraction (SPN 4154), or in whole percent.
  bool torque_fraction_seen() const { return torque_fraction_seen_; }

 private:
  struct Binding {
    j1939::Pgn pgn = 0;
    const j1939::SignalDef* signal = nullptr;
    Quantity quantity = Quantity::count;
    double scale = 1.0;  // to SI where the DBC unit is not (km/h, kPa)
    bool add = false;    // the torque fraction adds to the whole percent
  };
  std::array<Binding, kQuantityCount + 1> bindings_{};
  std::size_t bound_ = 0;
  std::array<Reading, kQuantityCount> readings_{};
  double torque_whole_ = 0, torque_fraction_ = 0;
  bool torque_fraction_seen_ = false;
};

// CAN frames in, drive signals out: J1939 transport sessions reassembled, every complete message
// decoded into the quantities it carries. The analyzer and the gap diagnosis read the bus this way.
class SignalFeed {
 public:
  explicit SignalFeed(const j1939::Database& db) : signals_(db) {}
  // The message this frame completed, its quantities already updated; none if it completed none.
  std::optional<j1939::Message> push(const CanFrame& frame) {
    auto m = assembler_.push(frame);
    if (m) signals_.push(*m);
    return m;
  }
  const Reading& get(Quantity q) const { return signals_.get(q); }
  // The quantity came with the message stamped t, not held over from an earlier one.
  bool fresh(Quantity q, CaptureTime t) const {
    const Reading& r = get(q);
    return r.seen && r.t == t;
  }
  const DriveSignals& signals() const { return signals_; }
  const j1939::TpCounters& transport() const { return assembler_.transport().counters(); }

 private:
  j1939::MessageAssembler assembler_;
  DriveSignals signals_;
};

// Why a sample cannot feed the force balance; `none` when it can.
enum class Unusable : std::uint8_t {
  none,
  no_reference_torque,  // EC1 never received: percent torque has no scale
  no_torque,
  no_gear,  // neither ETC2 ratio nor engine over wheel speed
  braking,
  declutched,        // shifting or clutch open
  stale,             // inputs older than the staleness limit
  no_elevation,      // the route's survey has no elevation here: no grade
  uncalibrated_rpm,  // an engine-loss calibration is given, but not for this engine speed
  count
};
inline constexpr std::size_t kUnusableCount = static_cast<std::size_t>(Unusable::count);
const char* to_string(Unusable u);

struct TractionEstimate {
  double tractive_n = 0;
  double gear_ratio = 0;
  double effective_mass_kg = 0;
  double wheel_force_per_flywheel_nm = 0;
  // The engine's torques in N m: indicated (EEC1), friction and the parasitic loads it knows
  // (EEC3; with an engine-loss calibration, friction is the calibrated losses less EEC3's
  // parasitic share), and what is left at the flywheel.
  double indicated_nm = 0, friction_nm = 0, parasitic_nm = 0, flywheel_nm = 0;
  // In neutral, clutch released (ETC2 current gear 0): no tractive force and none of the engine's
  // inertia, so the force balance holds without the engine's torque, its scale or the
  // driveline's efficiency. The engine's torques then go to its friction and its loads
  // (EEC3's friction, the rest parasitic); none reaches the flywheel's output.
  bool coasting = false;
  Unusable reason = Unusable::none;
};

// Tractive force at the wheels from the latest signals at time t (model/longitudinal.hpp). The gear
// ratio is ETC2's, or inferred from engine speed over wheel speed when ETC2 is absent; none in
// neutral (coasting).
TractionEstimate traction(const DriveSignals& s, const model::TruckModel& truck, CaptureTime t,
                          Nanoseconds stale_after = Nanoseconds{500'000'000});

}  // namespace roadload
