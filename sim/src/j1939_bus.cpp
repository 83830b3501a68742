#include "roadload/sim/j1939_bus.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "roadload/j1939/id.hpp"
#include "roadload/j1939/signal.hpp"
#include "roadload/j1939/transport.hpp"

namespace roadload::sim {
namespace {

using Getter = SignalGetter;

// Which ECU sends which message (source address, priority). ERC1, HOURS and LFC are absent: this
// truck has no retarder and sends the totals only on request.
struct Sender {
  const char* message;
  std::uint8_t sa;
  std::uint8_t priority;
};
constexpr Sender kSenders[] = {
    {"EEC1", 0x00, 3}, {"EEC2", 0x00, 3}, {"EEC3", 0x00, 6}, {"EC1", 0x00, 6},  {"CCVS1", 0x00, 6}, {"LFE1", 0x00, 6},
    {"ET1", 0x00, 6},  {"FD1", 0x00, 6},  {"DM1", 0x00, 6},  {"AMB", 0x00, 6},  {"ETC1", 0x03, 3},  {"ETC2", 0x03, 6},
    {"EBC1", 0x0B, 6}, {"EBC2", 0x0B, 6}, {"VD", 0x17, 6},   {"VDHR", 0x17, 6}, {"VP1", 0x1C, 6},
};

double b(bool v) { return v ? 1.0 : 0.0; }

// Whole percent and the 1/8 % fraction of SPN 4154, as an ECU splits them.
double torque_whole(double pct) { return std::floor(std::round(pct * 8.0) / 8.0); }
double torque_fraction(double pct) { return std::round(pct * 8.0) / 8.0 - torque_whole(pct); }

// Long because it is one table: every signal the simulated ECUs send, each with how it reads the
// plant's state, in the order of the DBC's messages.
const std::map<std::string, Getter>& getters() {
  static const std::map<std::string, Getter> g = {
      // Torque mode 2 is cruise control, 0 low idle (SPN 899).
      {"EEC1.EngineTorqueMode", [](const BusView& v) { return v.engine_controlled ? 2.0 : 0.0; }},
      {"EEC1.ActualEnginePercentTorque", [](const BusView& v) { return torque_whole(v.actual_torque_pct); }},
      {"EEC1.ActualEnginePercentTorqueFraction", [](const BusView& v) { return torque_fraction(v.actual_torque_pct); }},
      {"EEC1.DriversDemandEnginePercentTorque", [](const BusView& v) { return v.demand_torque_pct; }},
      {"EEC1.EngineDemandPercentTorque", [](const BusView& v) { return v.demand_torque_pct; }},
      {"EEC1.EngineSpeed", [](const BusView& v) { return v.engine_rpm; }},
      {"EEC1.SourceAddressOfControllingDeviceForEngineControl", [](const BusView&) { return 0.0; }},
      {"EEC1.EngineStarterMode", [](const BusView&) { return 0.0; }},
      {"EEC2.AcceleratorPedal1LowIdleSwitch", [](const BusView&) { return 1.0; }},
      {"EEC2.AcceleratorPedalKickdownSwitch", [](const BusView&) { return 0.0; }},
      {"EEC2.AcceleratorPedalPosition1", [](const BusView&) { return 0.0; }},
      {"EEC2.EnginePercentLoadAtCurrentSpeed", [](const BusView& v) { return v.load_pct; }},
      {"EEC3.NominalFrictionPercentTorque", [](const BusView& v) { return v.friction_torque_pct; }},
      {"EEC3.EstimatedEngineParasiticLossesPercentTorque", [](const BusView& v) { return v.parasitic_torque_pct; }},
      {"EC1.EngineSpeedAtIdlePoint1", [](const BusView& v) { return v.ec1_rpm[0]; }},
      {"EC1.EnginePercentTorqueAtIdlePoint1", [](const BusView& v) { return v.ec1_pct[0]; }},
      {"EC1.EngineSpeedAtPoint2", [](const BusView& v) { return v.ec1_rpm[1]; }},
      {"EC1.EnginePercentTorqueAtPoint2", [](const BusView& v) { return v.ec1_pct[1]; }},
      {"EC1.EngineSpeedAtPoint3", [](const BusView& v) { return v.ec1_rpm[2]; }},
      {"EC1.EnginePercentTorqueAtPoint3", [](const BusView& v) { return v.ec1_pct[2]; }},
      {"EC1.EngineSpeedAtPoint4", [](const BusView& v) { return v.ec1_rpm[3]; }},
      {"EC1.EnginePercentTorqueAtPoint4", [](const BusView& v) { return v.ec1_pct[3]; }},
      {"EC1.EngineSpeedAtPoint5", [](const BusView& v) { return v.ec1_rpm[4]; }},
      {"EC1.EnginePercentTorqueAtPoint5", [](const BusView& v) { return v.ec1_pct[4]; }},
      {"EC1.EngineSpeedAtHighIdlePoint6", [](const BusView& v) { return v.high_idle_rpm; }},
      {"EC1.EngineReferenceTorque", [](const BusView& v) { return v.ref_torque_nm; }},
      {"EC1.EngineMomentOfInertia", [](const BusView& v) { return v.inertia_kgm2; }},
      {"CCVS1.WheelBasedVehicleSpeed", [](const BusView& v) { return v.wheel_speed_kmh; }},
      {"CCVS1.ParkingBrakeSwitch", [](const BusView&) { return 0.0; }},
      {"CCVS1.TwoSpeedAxleSwitch", [](const BusView&) { return 0.0; }},
      {"CCVS1.CruiseControlPauseSwitch", [](const BusView&) { return 0.0; }},
      {"CCVS1.CruiseControlActive", [](const BusView& v) { return b(v.cruise_active); }},
      {"CCVS1.CruiseControlEnableSwitch", [](const BusView& v) { return b(v.cruise_active); }},
      {"CCVS1.BrakeSwitch", [](const BusView& v) { return b(v.brake_switch); }},
      {"CCVS1.ClutchSwitch", [](const BusView& v) { return b(v.clutch_switch); }},
      {"CCVS1.CruiseControlSetSpeed", [](const BusView& v) { return v.cruise_set_kmh; }},
      {"CCVS1.PtoGovernorState", [](const BusView&) { return 0.0; }},
      {"CCVS1.CruiseControlStates", [](const BusView& v) { return v.cruise_active ? 1.0 : 0.0; }},
      {"LFE1.EngineFuelRate", [](const BusView& v) { return v.fuel_lph; }},
      {"LFE1.EngineInstantaneousFuelEconomy",
       [](const BusView& v) -> std::optional<double> {
         if (v.fuel_lph <= 0.05) return std::nullopt;  // an ECU sends n/a when coasting on fuel cut
         return std::min(v.wheel_speed_kmh / v.fuel_lph, 125.0);
       }},
      {"ETC1.TransmissionDrivelineEngaged", [](const BusView& v) { return b(v.driveline_engaged); }},
      {"ETC1.TransmissionShiftInProcess", [](const BusView& v) { return b(v.shift_in_process); }},
      {"ETC1.TransmissionOutputShaftSpeed", [](const BusView& v) { return v.output_shaft_rpm; }},
      {"ETC1.PercentClutchSlip", [](const BusView&) { return 0.0; }},
      {"ETC1.TransmissionInputShaftSpeed",
       [](const BusView& v) { return v.driveline_engaged ? v.engine_rpm : v.output_shaft_rpm * v.gear_ratio; }},
      {"ETC2.TransmissionSelectedGear", [](const BusView& v) { return static_cast<double>(v.selected_gear); }},
      {"ETC2.ActualGearRatio",
       [](const BusView& v) -> std::optional<double> {
         if (v.gear == 0) return std::nullopt;
         return v.gear_ratio;
       }},
      {"ETC2.CurrentGear", [](const BusView& v) { return static_cast<double>(v.gear); }},
      {"AMB.BarometricPressure", [](const BusView& v) { return v.pressure_kpa; }},
      {"AMB.AmbientAirTemperature", [](const BusView& v) { return v.ambient_c; }},
      {"AMB.EngineAirInletTemperature", [](const BusView& v) { return v.intake_c; }},
      {"VD.TotalVehicleDistance", [](const BusView& v) { return v.total_distance_m / 1000.0; }},
      {"VD.TripDistance", [](const BusView& v) { return v.trip_distance_m / 1000.0; }},
      {"VDHR.HighResolutionTotalVehicleDistance", [](const BusView& v) { return v.total_distance_m; }},
      {"VDHR.HighResolutionTripDistance", [](const BusView& v) { return v.trip_distance_m; }},
      {"VP1.Latitude", [](const BusView& v) { return v.lat_deg; }},
      {"VP1.Longitude", [](const BusView& v) { return v.lon_deg; }},
      {"FD1.EstimatedPercentFanSpeed", [](const BusView& v) { return v.fan_on ? 100.0 : 8.0; }},
      {"FD1.FanDriveState", [](const BusView& v) { return v.fan_on ? 4.0 : 0.0; }},
      {"FD1.FanSpeed", [](const BusView& v) { return v.fan_rpm; }},
      {"EBC1.EbsBrakeSwitch", [](const BusView& v) { return b(v.brake_switch); }},
      {"EBC1.AbsActive", [](const BusView&) { return 0.0; }},
      {"EBC1.AsrEngineControlActive", [](const BusView&) { return 0.0; }},
      {"EBC1.AsrBrakeControlActive", [](const BusView&) { return 0.0; }},
      {"EBC1.AbsFullyOperational", [](const BusView&) { return 1.0; }},
      {"EBC1.BrakePedalPosition", [](const BusView& v) { return v.brake_switch ? 20.0 : 0.0; }},
      {"EBC2.FrontAxleSpeed", [](const BusView& v) { return v.front_axle_speed_kmh; }},
      {"EBC2.RelativeSpeedFrontAxleLeftWheel", [](const BusView&) { return 0.0; }},
      {"EBC2.RelativeSpeedFrontAxleRightWheel", [](const BusView&) { return 0.0; }},
      {"EBC2.RelativeSpeedRearAxle1LeftWheel", [](const BusView&) { return 0.0; }},
      {"EBC2.RelativeSpeedRearAxle1RightWheel", [](const BusView&) { return 0.0; }},
      {"EBC2.RelativeSpeedRearAxle2LeftWheel", [](const BusView&) { return 0.0; }},
      {"EBC2.RelativeSpeedRearAxle2RightWheel", [](const BusView&) { return 0.0; }},
      {"ET1.EngineCoolantTemperature", [](const BusView& v) { return v.coolant_c; }},
      {"ET1.EngineFuelTemperature1", [](const BusView&) { return 40.0; }},
      {"ET1.EngineOilTemperature1", [](const BusView& v) { return v.coolant_c + 8.0; }},
      {"DM1.ProtectLampStatus", [](const BusView&) { return 0.0; }},
      {"DM1.AmberWarningLampStatus", [](const BusView&) { return 0.0; }},
      {"DM1.RedStopLampStatus", [](const BusView&) { return 0.0; }},
      {"DM1.MalfunctionIndicatorLampStatus", [](const BusView&) { return 0.0; }},
      // No active DTC is sent as SPN 0, FMI 0, count 0.
      {"DM1.Dtc1SpnLow16", [](const BusView&) { return 0.0; }},
      {"DM1.Dtc1Fmi", [](const BusView&) { return 0.0; }},
      {"DM1.Dtc1SpnHigh3", [](const BusView&) { return 0.0; }},
      {"DM1.Dtc1OccurrenceCount", [](const BusView&) { return 0.0; }},
      {"DM1.Dtc1SpnConversionMethod", [](const BusView&) { return 0.0; }},
  };
  return g;
}

constexpr double kBamPacketGap_s = 0.05;  // J1939-21 allows 50-200 ms between BAM packets

double frame_bits(std::size_t bytes) {
  // 29-bit data frame: 67 bits of overhead and data, plus worst-average stuffing of ~10 %.
  return (67.0 + 8.0 * static_cast<double>(bytes)) * 1.1;
}

}  // namespace

J1939Bus::J1939Bus(const j1939::Database& db, BusOptions options, Rng rng) : db_(db), options_(std::move(options)), rng_(rng) {
  std::map<std::uint8_t, double> ecu_rate;  // one oscillator per ECU, shared by its messages
  for (const Sender& s : kSenders) {
    const j1939::MessageDef* def = db_.find_name(s.message);
    if (def == nullptr || def->cycle_time_ms == 0) continue;
    Schedule sch;
    sch.def = def;
    sch.sa = s.sa;
    sch.priority = s.priority;
    sch.period_s = def->cycle_time_ms / 1000.0;
    if (!ecu_rate.contains(s.sa)) ecu_rate[s.sa] = 1.0 + rng_.uniform(-1.0, 1.0) * options_.ecu_drift_ppm * 1e-6;
    sch.rate = ecu_rate[s.sa];
    sch.next_ecu_s = rng_.uniform(0.0, sch.period_s);  // ECUs power up at different moments
    sch.getters = bind(*def);
    schedules_.push_back(std::move(sch));
  }
}

double J1939Bus::due_s(const Schedule& s) const {
  const double periodic = s.next_ecu_s / s.rate;
  return s.bam_packet > 0 ? std::min(periodic, s.bam_next_s) : periodic;
}

double J1939Bus::next_due_s() const {
  double t = std::numeric_limits<double>::infinity();
  for (const auto& s : schedules_) t = std::min(t, due_s(s));
  return t;
}

std::vector<const SignalGetter*> J1939Bus::bind(const j1939::MessageDef& def) {
  std::vector<const SignalGetter*> out;
  const auto& g = getters();
  for (const auto& sig : def.signals) {
    const auto it = g.find(def.name + "." + sig.name);
    out.push_back(it == g.end() ? nullptr : &it->second);
  }
  return out;
}

std::vector<std::uint8_t> J1939Bus::compose(const Schedule& s, const BusView& view) const {
  // Unused bytes and bits are sent as ones, which reads as "not available".
  std::vector<std::uint8_t> data(std::max<std::size_t>(s.def->length, 8), 0xFF);
  for (std::size_t i = 0; i < s.def->signals.size(); ++i) {
    const SignalGetter* getter = s.getters[i];
    if (getter == nullptr) continue;
    const auto& sig = s.def->signals[i];
    if (const auto v = (*getter)(view)) {
      j1939::encode(sig, *v, data);
    } else {
      j1939::encode_state(sig, j1939::SignalState::not_available, data);
    }
  }
  return data;
}

std::vector<std::uint8_t> J1939Bus::compose(const std::string& message, const BusView& view) const {
  Schedule s;
  s.def = db_.find_name(message);
  if (s.def == nullptr) return {};
  s.getters = bind(*s.def);
  return compose(s, view);
}

void J1939Bus::transmit(double ready_s, std::uint32_t id, std::span<const std::uint8_t> data,
                        const std::function<void(const CanFrame&)>& emit) {
  const double start = std::max(ready_s, bus_free_s_);
  bus_free_s_ = start + frame_bits(data.size()) / options_.bitrate_bps;
  const double rx = bus_free_s_ + options_.rx_latency.count() + options_.rx_jitter.count() * rng_.uniform();
  // Kernel receive stamps follow the order frames arrive in.
  const auto ns = std::max(static_cast<std::int64_t>(std::llround(rx * 1e9)), last_stamp_ns_);
  last_stamp_ns_ = ns;
  CanFrame f;
  f.t = capture_time_from_ns(ns);
  f.id = id;
  f.kind = CanFrameKind::extended;
  f.id29 = true;
  f.len = static_cast<std::uint8_t>(data.size());
  std::copy(data.begin(), data.end(), f.data.begin());
  emit(f);
}

void J1939Bus::run_until(double t_s, const BusView& view, const std::function<void(const CanFrame&)>& emit) {
  for (;;) {
    Schedule* next = nullptr;
    double when = t_s;
    for (auto& s : schedules_) {
      const double d = due_s(s);
      // Among frames due together the lower priority number wins arbitration.
      if (d <= when && (next == nullptr || d < when || s.priority < next->priority)) {
        next = &s;
        when = d;
      }
    }
    if (next == nullptr) return;
    Schedule& s = *next;
    const double ready = when + options_.task_jitter.count() * rng_.uniform();
    if (s.bam_packet > 0 && s.bam_next_s <= s.next_ecu_s / s.rate) {
      std::array<std::uint8_t, 8> dt{};
      dt.fill(0xFF);
      dt[0] = static_cast<std::uint8_t>(s.bam_packet);
      const std::size_t from = static_cast<std::size_t>(s.bam_packet - 1) * 7;
      for (std::size_t i = 0; i < 7 && from + i < s.bam_data.size(); ++i) dt[1 + i] = s.bam_data[from + i];
      transmit(ready, j1939::make_can_id(7, j1939::kPgnTpDt, 0xFF, s.sa), dt, emit);
      const std::size_t packets = (s.bam_data.size() + 6) / 7;
      s.bam_packet = static_cast<std::size_t>(s.bam_packet) < packets ? s.bam_packet + 1 : 0;
      s.bam_next_s = when + kBamPacketGap_s;
      continue;
    }
    s.next_ecu_s += s.period_s;
    std::vector<std::uint8_t> data = compose(s, view);
    if (data.size() <= 8) {
      transmit(ready, j1939::make_can_id(s.priority, s.def->pgn, 0xFF, s.sa), data, emit);
      continue;
    }
    const auto size = static_cast<std::uint16_t>(data.size());
    const auto packets = static_cast<std::uint8_t>((data.size() + 6) / 7);
    const std::array<std::uint8_t, 8> cm{j1939::tp_control::kBam,
                                         static_cast<std::uint8_t>(size & 0xFF),
                                         static_cast<std::uint8_t>(size >> 8),
                                         packets,
                                         0xFF,
                                         static_cast<std::uint8_t>(s.def->pgn & 0xFF),
                                         static_cast<std::uint8_t>((s.def->pgn >> 8) & 0xFF),
                                         static_cast<std::uint8_t>(s.def->pgn >> 16)};
    transmit(ready, j1939::make_can_id(7, j1939::kPgnTpCm, 0xFF, s.sa), cm, emit);
    s.bam_data = std::move(data);
    s.bam_packet = 1;
    s.bam_next_s = when + kBamPacketGap_s;
  }
}

}  // namespace roadload::sim
