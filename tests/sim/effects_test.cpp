// Every effect is a switch that changes what the sensors see, and none of them is named in what
// a recording carries: a diagnosis has to find them blind.
#include <gtest/gtest.h>

#include <cstring>

#include "roadload/recording/metadata.hpp"
#include "sim_fixture.hpp"

namespace roadload::sim {
namespace {

struct Observed {
  std::uint64_t digest = 1469598103934665603ULL;  // FNV-1a over everything the sensors wrote
  std::string meta;
  double crr_mean = 0;                                 // truth
  double roll_force_n = 0;                             // truth: mean rolling force over the run
  double reported_torque = 0;                          // mean EEC1 actual torque, % (as sent)
  double indicated_torque = 0;                         // truth, % of reference
  double engine_rpm = 0, accessory_nm = 0, ac_nm = 0;  // truth at the end
  double reported_speed_kmh = 0;                       // mean CCVS1 wheel-based speed (as sent)
  double speed_mps = 0, drive_radius_m = 0;            // truth at the end
  std::size_t frames = 0;

  void mix(const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) digest = (digest ^ b[i]) * 1099511628211ULL;
  }
};

class TruthSink final : public SampleSink {
 public:
  explicit TruthSink(Observed& o) : o_(o) {}
  void frame(const CanFrame& f) override {
    o_.mix(&f.t, sizeof f.t);
    o_.mix(&f.id, sizeof f.id);
    o_.mix(f.data.data(), f.len);
    if ((f.id >> 8 & 0x3FFFF) == 0xF004) {  // EEC1: byte 3 is actual torque, offset -125
      torque_sum_ += f.data[2] - 125.0;
      ++torque_n_;
    }
    if ((f.id >> 8 & 0x3FFFF) == 0xFEF1) {  // CCVS1: bytes 2-3 are wheel-based speed, 1/256 km/h
      speed_sum_ += (f.data[1] | f.data[2] << 8) / 256.0;
      ++speed_n_;
    }
    ++o_.frames;
  }
  void accel(const AccelSample& s) override {
    o_.mix(&s.t, sizeof s.t);
    o_.mix(&s.x_mps2, sizeof(double) * 3);
  }
  void gnss(const GnssFix& s) override {
    o_.mix(&s.t, sizeof s.t);
    o_.mix(&s.alt_m, sizeof s.alt_m);
  }
  void weather(const WeatherSample& s) override {
    o_.mix(&s.t, sizeof s.t);
    o_.mix(&s.air_temp_c, sizeof(double) * 4);
  }
  double torque() const { return torque_n_ > 0 ? torque_sum_ / static_cast<double>(torque_n_) : 0.0; }
  double speed() const { return speed_n_ > 0 ? speed_sum_ / static_cast<double>(speed_n_) : 0.0; }

 private:
  Observed& o_;
  double torque_sum_ = 0, speed_sum_ = 0;
  std::size_t torque_n_ = 0, speed_n_ = 0;
};

Observed observe(std::optional<Effect> effect, double magnitude, double tire_radius_scale = 1.0, double tire_crr_scale = 1.0,
                 Seconds driven_before = kReportWarmUp) {
  static const j1939::Database db = test::core_database();
  Scenario sc = test::builtin("th10-55mph");  // jointed concrete at 31 C: every effect has something to act on
  sc.effects = EffectSet{};
  sc.duration = Seconds{30.0};
  sc.accelerometers = 2;
  if (effect) sc.effects.set(*effect, magnitude);
  sc.tire_radius_scale = tire_radius_scale;
  sc.tire_crr_scale = tire_crr_scale;
  sc.driven_before = driven_before;
  Simulation sim(sc, 9, db);
  Observed o;
  TruthSink sink(o);
  TruthRecorder truth(sim.route(), sim.plant().truck());
  const RunSummary sum = sim.run(sink, &truth);
  o.meta = recording::format_metadata(sim.metadata());
  o.mix(o.meta.data(), o.meta.size());
  o.roll_force_n = sum.ledger.roll_j / sum.ledger.distance_m;
  o.crr_mean = o.roll_force_n / (sim.plant().truck().total_mass_kg() * 9.80665);
  o.reported_torque = sink.torque();
  o.indicated_torque = sim.plant().state().indicated_torque_nm / 2386.0 * 100.0;
  o.engine_rpm = sim.plant().state().engine_rpm;
  o.accessory_nm = sim.plant().state().accessory_torque_nm;
  o.ac_nm = sim.plant().state().ac_torque_nm;
  o.reported_speed_kmh = sink.speed();
  o.speed_mps = sim.plant().state().speed_mps;
  o.drive_radius_m = sim.plant().truck().drive_radius_m();
  return o;
}

TEST(Effects, EveryEffectChangesWhatTheSensorsSeeAndNoneIsNamed) {
  const Observed base = observe(std::nullopt, 0);
  for (const EffectInfo& e : effect_catalog()) {
    const Observed on = observe(e.id, e.typical);
    EXPECT_NE(on.digest, base.digest) << e.name << " left every sensor stream unchanged";
    EXPECT_EQ(on.meta.find(std::string(e.name)), std::string::npos) << e.name << " is named in meta.toml";
    EXPECT_EQ(on.frames, base.frames) << e.name << " changed the bus schedule";
  }
}

TEST(Effects, CrrEffectsMoveTheTrueRollingResistanceTheRightWay) {
  const double base = observe(std::nullopt, 0).crr_mean;
  EXPECT_NEAR(base, 0.0061, 0.0002);
  EXPECT_GT(observe(Effect::tire_warmup, 0.3).crr_mean, base * 1.01);        // 30 min warm: 6.7 % excess
  EXPECT_LT(observe(Effect::temperature_crr, 0.006).crr_mean, base * 0.92);  // 31.1 C vs 14.3 C: -10 %
  EXPECT_GT(observe(Effect::speed_crr, 0.01).crr_mean, base * 1.10);         // 55 vs 30 mph: +11 %
  EXPECT_GT(observe(Effect::tire_pressure, -0.1).crr_mean, base * 1.02);     // -10 % pressure: +3 %
}

// A run that starts 10 minutes after the truck left its yard: most of the cold excess is left, and
// the simulated recording says how long the truck had driven, for the gap's re-simulation.
TEST(Effects, TireWarmupDependsOnTheDrivingBeforeTheRun) {
  const double base = observe(std::nullopt, 0).crr_mean;
  const Observed early = observe(Effect::tire_warmup, 0.3, 1.0, 1.0, Seconds{600.0});
  // 1 + 0.3 exp(-(600 s + t) / 1200 s) over the 30 s run: 1.178 to 1.174.
  EXPECT_NEAR(early.crr_mean / base, 1.176, 0.004);
  EXPECT_NE(early.meta.find("driven_before_s = 600"), std::string::npos) << early.meta;
  EXPECT_NE(observe(std::nullopt, 0).meta.find("driven_before_s = 1800"), std::string::npos);
}

TEST(Effects, TorqueBiasScalesOnlyTheReportedTorque) {
  const Observed base = observe(std::nullopt, 0);
  const Observed biased = observe(Effect::torque_bias, 0.05);
  EXPECT_NEAR(biased.indicated_torque, base.indicated_torque, 0.5);  // the truck is the same
  EXPECT_NEAR(biased.reported_torque / base.reported_torque, 1.05, 0.02);
}

// The compressor takes its power from the crankshaft: the engine makes P / omega more torque for
// the same speed, and the engine's own estimate of its parasitic losses does not know it.
TEST(Effects, AcCompressorLoadsTheEngineAndNotTheWheels) {
  const Observed base = observe(std::nullopt, 0);
  const Observed on = observe(Effect::ac_compressor, 3000.0);
  const double omega = on.engine_rpm * 2.0 * 3.14159265358979 / 60.0;
  EXPECT_NEAR(on.ac_nm, 3000.0 / omega, 0.5);
  EXPECT_NEAR(on.accessory_nm - on.ac_nm, base.accessory_nm, 0.5);
  EXPECT_NEAR(on.indicated_torque - base.indicated_torque, on.ac_nm / 2386.0 * 100.0, 0.3);
  EXPECT_NEAR(on.crr_mean, base.crr_mean, 1e-6);
}

// A water film the weather station does not see: the tires roll harder, nothing else changes.
TEST(Effects, WetRoadRaisesTheRollingResistanceAlone) {
  const Observed base = observe(std::nullopt, 0);
  const Observed wet = observe(Effect::wet_road, 0.5);
  EXPECT_NEAR(wet.crr_mean / base.crr_mean, 1.10, 0.005);
  EXPECT_NEAR(wet.reported_speed_kmh, base.reported_speed_kmh, 0.02);
}

// Worn tires are smaller: the wheels turn faster for the road speed, so the ECUs' speed (worked out
// with the vehicle file's radius) reads high by r_file / r_worn and the cruise control, holding that
// reading, drives the truck slower. They also roll easier.
TEST(Effects, TreadWearMakesTheSpeedometerReadHighAndTheTiresRollEasier) {
  const Observed base = observe(std::nullopt, 0);
  const Observed worn = observe(Effect::tread_wear, 0.5);
  EXPECT_NEAR(base.drive_radius_m - worn.drive_radius_m, 0.5 * 0.017, 1e-9);
  const double scale = base.drive_radius_m / worn.drive_radius_m;
  EXPECT_NEAR(worn.reported_speed_kmh, base.reported_speed_kmh, 0.05);
  EXPECT_NEAR(worn.speed_mps * scale, base.speed_mps, 0.05);
  EXPECT_LT(worn.speed_mps, base.speed_mps - 0.2);
  EXPECT_NEAR(worn.crr_mean / base.crr_mean, 1.0 - 0.25 * 0.5, 0.005);
}

// Tires larger than the vehicle file's (another brand, or an ECU told a smaller size): the same
// speedometer error the other way round, and nothing else.
TEST(Effects, ATruckOnOtherTiresReadsItsSpeedOffAsWornTiresDo) {
  const Observed base = observe(std::nullopt, 0);
  const Observed larger = observe(std::nullopt, 0, 1.01);
  EXPECT_NEAR(larger.drive_radius_m / base.drive_radius_m, 1.01, 1e-12);
  EXPECT_NEAR(larger.reported_speed_kmh, base.reported_speed_kmh, 0.05);
  EXPECT_NEAR(larger.speed_mps, base.speed_mps * 1.01, 0.05);
  EXPECT_NEAR(larger.crr_mean, base.crr_mean, 1e-4);
}

// Another truck's tires on the same pavement (a fleet's): the rolling force is the pavement's CRR
// times the tires' scale, which the cruise control pays for at the same speed.
TEST(Effects, TiresOfHigherRollingResistanceRaiseTheRollingForceByTheirScale) {
  const Observed base = observe(std::nullopt, 0);
  const Observed harder = observe(std::nullopt, 0, 1.0, 1.1);
  EXPECT_NEAR(harder.roll_force_n / base.roll_force_n, 1.1, 1e-3);
  EXPECT_GT(harder.indicated_torque, base.indicated_torque);
  EXPECT_NEAR(harder.reported_speed_kmh, base.reported_speed_kmh, 0.05);
  EXPECT_EQ(harder.meta, base.meta) << "the recording must not tell the tires' scale";
}

}  // namespace
}  // namespace roadload::sim
