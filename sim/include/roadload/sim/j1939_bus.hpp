#pragma once
// The truck's J1939 network as the gateway hears it: each ECU broadcasts its messages at the
// DBC's repetition rate on its own drifting clock, quantised by the codec exactly as an ECU
// does, with not-available patterns for what a real truck does not send; EC1 travels by BAM;
// frames go onto a 250 kbit/s bus in order of their send time (the lower priority number wins
// when two are due together) and are stamped when the gateway receives them.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "roadload/can_frame.hpp"
#include "roadload/j1939/database.hpp"
#include "roadload/sim/random.hpp"

namespace roadload::sim {

// What the ECUs report at one moment, in the units their signals carry. Values an ECU measures
// with an error (torque bias, ambient sensor) are already reported values here.
struct BusView {
  double engine_rpm = 0;
  double actual_torque_pct = 0;  // indicated, of the reference torque
  double demand_torque_pct = 0;
  double friction_torque_pct = 0;
  double parasitic_torque_pct = 0;  // what the ECU knows of accessories
  double load_pct = 0;
  bool engine_controlled = false;  // torque mode: cruise control in charge
  double wheel_speed_kmh = 0;
  double front_axle_speed_kmh = 0;
  bool cruise_active = false;
  double cruise_set_kmh = 0;
  bool brake_switch = false;
  bool clutch_switch = false;
  double fuel_lph = 0;
  int gear = 0;  // 0 neutral
  int selected_gear = 0;
  double gear_ratio = 0;
  bool driveline_engaged = false;
  bool shift_in_process = false;
  double output_shaft_rpm = 0;
  double pressure_kpa = 0;
  double ambient_c = 0;
  double intake_c = 0;
  double total_distance_m = 0;
  double trip_distance_m = 0;
  double lat_deg = 0, lon_deg = 0;  // the truck's own (coarse) GPS
  bool fan_on = false;
  double fan_rpm = 0;
  double coolant_c = 0;
  // Engine configuration (EC1).
  double ref_torque_nm = 0;
  double idle_rpm = 0, high_idle_rpm = 0;
  double inertia_kgm2 = 0;
  double ec1_rpm[5]{}, ec1_pct[5]{};
};

// Reads one signal's value from a view; nullopt sends "not available".
using SignalGetter = std::function<std::optional<double>(const BusView&)>;

struct BusOptions {
  std::string iface = "can0";
  double bitrate_bps = 250000;
  double ecu_drift_ppm = 100;   // each ECU's oscillator, uniform +- this
  Seconds task_jitter{0.0002};  // ECU send task jitter, uniform 0..this late
  Seconds rx_latency{0.00008};  // controller to kernel stamp
  Seconds rx_jitter{0.00002};
};

class J1939Bus {
 public:
  J1939Bus(const j1939::Database& db, BusOptions options, Rng rng);

  // Time of the next scheduled transmission, true seconds.
  double next_due_s() const;
  // Sends every message due up to t_s with the values of `view`, in bus order; `emit` receives
  // each frame stamped in the capture clock.
  void run_until(double t_s, const BusView& view, const std::function<void(const CanFrame&)>& emit);

  // Composes one message's payload from a view (exposed for the codec round-trip test).
  std::vector<std::uint8_t> compose(const std::string& message, const BusView& view) const;

 private:
  struct Schedule {
    const j1939::MessageDef* def = nullptr;
    std::uint8_t sa = 0;
    std::uint8_t priority = 6;
    double period_s = 0;
    double rate = 1;        // ECU seconds per true second (its drift)
    double next_ecu_s = 0;  // next transmission on the ECU's clock
    // A message longer than 8 bytes goes out as TP.CM BAM and then TP.DT packets 50 ms apart.
    std::vector<std::uint8_t> bam_data;
    int bam_packet = 0;                        // next TP.DT sequence number; 0 when no BAM is running
    double bam_next_s = 0;                     // true time
    std::vector<const SignalGetter*> getters;  // per signal of def; null: left as all ones
  };
  std::vector<std::uint8_t> compose(const Schedule& s, const BusView& view) const;
  static std::vector<const SignalGetter*> bind(const j1939::MessageDef& def);
  double due_s(const Schedule& s) const;
  void transmit(double ready_s, std::uint32_t id, std::span<const std::uint8_t> data,
                const std::function<void(const CanFrame&)>& emit);

  const j1939::Database& db_;
  BusOptions options_;
  Rng rng_;
  std::vector<Schedule> schedules_;
  double bus_free_s_ = 0;
  std::int64_t last_stamp_ns_ = 0;
};

}  // namespace roadload::sim
