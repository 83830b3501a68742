// The simulated ECUs' frames decode back to the simulated values within one resolution step, and
// the bus behaves as a J1939 network: repetition rates, EC1 by BAM, time-ordered stamps.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "roadload/j1939/assembler.hpp"
#include "roadload/sim/j1939_bus.hpp"
#include "sim_fixture.hpp"

namespace roadload::sim {
namespace {

BusView sample_view() {
  BusView v;
  v.engine_rpm = 1339.37;
  v.actual_torque_pct = 41.43;
  v.demand_torque_pct = 40.6;
  v.friction_torque_pct = 7.9;
  v.parasitic_torque_pct = 1.7;
  v.load_pct = 38.2;
  v.engine_controlled = true;
  v.wheel_speed_kmh = 102.99;
  v.front_axle_speed_kmh = 102.97;
  v.cruise_active = true;
  v.cruise_set_kmh = 103;
  v.fuel_lph = 38.47;
  v.gear = 10;
  v.selected_gear = 10;
  v.gear_ratio = 0.73;
  v.driveline_engaged = true;
  v.output_shaft_rpm = 1834.6;
  v.pressure_kpa = 98.13;
  v.ambient_c = 14.61;
  v.intake_c = 19.3;
  v.total_distance_m = 412345678.9;
  v.trip_distance_m = 1234.5;
  v.lat_deg = 45.2496943;
  v.lon_deg = -93.6862171;
  v.coolant_c = 88;
  v.ref_torque_nm = 2386;
  v.inertia_kgm2 = 3.824;
  return v;
}

TEST(J1939RoundTrip, EverySentSignalDecodesWithinOneStep) {
  const j1939::Database db = test::core_database();
  J1939Bus bus(db, BusOptions{}, Rng(1));
  const BusView v = sample_view();
  const std::map<std::string, double> expected = {
      {"EEC1.EngineSpeed", v.engine_rpm},
      {"EEC1.DriversDemandEnginePercentTorque", v.demand_torque_pct},
      {"EEC3.NominalFrictionPercentTorque", v.friction_torque_pct},
      {"EEC3.EstimatedEngineParasiticLossesPercentTorque", v.parasitic_torque_pct},
      {"CCVS1.WheelBasedVehicleSpeed", v.wheel_speed_kmh},
      {"CCVS1.CruiseControlSetSpeed", v.cruise_set_kmh},
      {"LFE1.EngineFuelRate", v.fuel_lph},
      {"ETC1.TransmissionOutputShaftSpeed", v.output_shaft_rpm},
      {"ETC2.ActualGearRatio", v.gear_ratio},
      {"ETC2.CurrentGear", 10},
      {"AMB.BarometricPressure", v.pressure_kpa},
      {"AMB.AmbientAirTemperature", v.ambient_c},
      {"VDHR.HighResolutionTotalVehicleDistance", v.total_distance_m},
      {"VD.TotalVehicleDistance", v.total_distance_m / 1000},
      {"VP1.Latitude", v.lat_deg},
      {"VP1.Longitude", v.lon_deg},
      {"EBC2.FrontAxleSpeed", v.front_axle_speed_kmh},
      {"ET1.EngineCoolantTemperature", v.coolant_c},
      {"EC1.EngineReferenceTorque", v.ref_torque_nm},
      {"EC1.EngineMomentOfInertia", v.inertia_kgm2},
  };
  for (const auto& [key, value] : expected) {
    const std::string message = key.substr(0, key.find('.'));
    const std::string signal = key.substr(key.find('.') + 1);
    const j1939::MessageDef* def = db.find_name(message);
    ASSERT_NE(def, nullptr) << message;
    const auto data = bus.compose(message, v);
    const auto it = std::find_if(def->signals.begin(), def->signals.end(), [&](const auto& s) { return s.name == signal; });
    ASSERT_NE(it, def->signals.end()) << key;
    const auto got = j1939::decode(*it, data).get();
    ASSERT_TRUE(got.has_value()) << key;
    EXPECT_LE(std::abs(*got - value), it->factor * 0.5 + 1e-9) << key << " decoded " << *got << " sent " << value;
  }
  // Actual torque travels as whole percent plus an eighth-percent fraction.
  const j1939::MessageDef* eec1 = db.find_name("EEC1");
  const auto data = bus.compose("EEC1", v);
  double torque = 0;
  for (const auto& s : eec1->signals) {
    if (s.name == "ActualEnginePercentTorque" || s.name == "ActualEnginePercentTorqueFraction") {
      torque += j1939::decode(s, data).get().value();
    }
  }
  EXPECT_LE(std::abs(torque - v.actual_torque_pct), 0.0625 + 1e-9);
}

TEST(J1939RoundTrip, UnsentSignalsReadNotAvailable) {
  const j1939::Database db = test::core_database();
  J1939Bus bus(db, BusOptions{}, Rng(1));
  BusView v = sample_view();
  v.fuel_lph = 0.0;  // coasting on fuel cut: instantaneous economy is not available
  const j1939::MessageDef* lfe1 = db.find_name("LFE1");
  const auto data = bus.compose("LFE1", v);
  for (const auto& s : lfe1->signals) {
    if (s.name == "EngineFuelRate") continue;
    EXPECT_EQ(j1939::decode(s, data).state, j1939::SignalState::not_available) << s.name;
  }
}

TEST(J1939Bus, RepetitionRatesBamAndOrderedStamps) {
  const j1939::Database db = test::core_database();
  J1939Bus bus(db, BusOptions{}, Rng(5));
  std::vector<CanFrame> frames;
  const BusView v = sample_view();
  for (int k = 1; k <= 12000; ++k) bus.run_until(k * 0.001, v, [&](const CanFrame& f) { frames.push_back(f); });
  std::map<j1939::Pgn, int> count;
  j1939::MessageAssembler assembler;
  std::optional<double> ref_torque;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i > 0) {
      ASSERT_GE(to_ns(frames[i].t), to_ns(frames[i - 1].t));
    }
    ++count[j1939::pgn_of(frames[i].id)];
    if (auto m = assembler.push(frames[i]); m && m->reassembled && m->pgn == db.find_name("EC1")->pgn) {
      for (const auto& s : db.find_name("EC1")->signals) {
        if (s.name == "EngineReferenceTorque") ref_torque = j1939::decode(s, m->data).get();
      }
    }
  }
  // 12 s: ETC1 at 10 ms, EEC1 at 20 ms, CCVS1 at 100 ms, AMB at 1 s (+- one for start phase and drift).
  EXPECT_NEAR(count[db.find_name("ETC1")->pgn], 1200, 1);
  EXPECT_NEAR(count[db.find_name("EEC1")->pgn], 600, 1);
  EXPECT_NEAR(count[db.find_name("CCVS1")->pgn], 120, 1);
  EXPECT_NEAR(count[db.find_name("AMB")->pgn], 12, 1);
  ASSERT_TRUE(ref_torque.has_value()) << "EC1 never reassembled from its BAM";
  EXPECT_EQ(*ref_torque, 2386.0);
}

}  // namespace
}  // namespace roadload::sim
