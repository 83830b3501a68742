// The estimator's tractive force, computed from what the simulated truck says on J1939 (EEC1,
// EEC3, EC1, ETC2), against the plant's true tractive force: the force model and the codec agree
// with the physics up to the resolution J1939 gives them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "roadload/drive_signals.hpp"
#include "roadload/engine_loss_calibration.hpp"
#include "roadload/j1939/assembler.hpp"
#include "sim_fixture.hpp"
#include "vehicles.hpp"

namespace roadload::sim {
namespace {

class TractionSink final : public SampleSink {
 public:
  TractionSink(const j1939::Database& db, const Simulation& sim, bool drop_ec1, const model::TruckModel& truck)
      : db_(db), sim_(sim), signals_(db), drop_ec1_(drop_ec1), truck_(truck) {}
  void frame(const CanFrame& f) override {
    // Dropping the transport frames loses EC1, the only multi-packet message.
    if (drop_ec1_ && (j1939::pgn_of(f.id) == j1939::kPgnTpCm || j1939::pgn_of(f.id) == j1939::kPgnTpDt)) return;
    const auto m = assembler_.push(f);
    if (!m) return;
    signals_.push(*m);
    if (m->pgn != db_.find_name("EEC1")->pgn) return;
    const TractionEstimate e = traction(signals_, truck_, m->t);
    last_reason = e.reason;
    if (e.reason != Unusable::none) return;
    const double err = e.tractive_n - sim_.plant().state().tractive_n;
    sum += err;
    sum2 += err * err;
    truth_sum += sim_.plant().state().tractive_n;
    ++n;
  }
  void accel(const AccelSample&) override {}
  void gnss(const GnssFix&) override {}
  void weather(const WeatherSample&) override {}

  double sum = 0, sum2 = 0, truth_sum = 0;
  std::size_t n = 0;
  Unusable last_reason = Unusable::none;

 private:
  const j1939::Database& db_;
  const Simulation& sim_;
  j1939::MessageAssembler assembler_;
  DriveSignals signals_;
  bool drop_ec1_;
  model::TruckModel truck_;
};

struct Outcome {
  double sum = 0, sum2 = 0, truth_sum = 0;
  std::size_t n = 0;
  Unusable last_reason = Unusable::none;
};

Outcome drive(const char* scenario, double seconds, bool drop_ec1,
              const model::TruckModel& truck = model::truck_model(roadload::shipped::mnroad_vehicle())) {
  const j1939::Database db = test::core_database();
  Scenario sc = test::builtin(scenario);
  sc.duration = Seconds{seconds};
  sc.accelerometers = 0;
  Simulation sim(sc, 2, db);
  TractionSink sink(db, sim, drop_ec1, truck);
  sim.run(sink, nullptr);
  return {sink.sum, sink.sum2, sink.truth_sum, sink.n, sink.last_reason};
}

TEST(TractionFromJ1939, MatchesThePlantsTractiveForceWithinJ1939Resolution) {
  const Outcome sink = drive("mnroad-mainline-30mph", 90, false);
  ASSERT_GT(sink.n, 3000u);
  const double mean = sink.sum / static_cast<double>(sink.n);
  const double rms = std::sqrt(sink.sum2 / static_cast<double>(sink.n));
  std::printf("tractive force from J1939 vs plant: %zu samples, mean truth %.0f N, bias %.1f N, rms %.1f N\n", sink.n,
              sink.truth_sum / static_cast<double>(sink.n), mean, rms);
  // EEC3 friction and parasitic torque come in whole percent: +-0.5 % of 2,386 N m each, about
  // +-105 N each at the wheels in 8th gear.
  EXPECT_LT(std::abs(mean), 210.0);
  EXPECT_LT(rms, 250.0);
}

// The engine's losses measured standing in neutral (the engine-losses scenario) replace EEC3's
// whole percent: what is left is EEC1's 1/8 % and the calibration's interpolation.
TEST(TractionFromJ1939, CalibratedEngineLossesRemoveEec3sRounding) {
  const j1939::Database db = test::core_database();
  const Scenario standing = test::builtin("engine-losses");
  const test::MemorySink held = test::drive_without_accelerometers(standing, 5, db);
  EngineLossFrames frames(db);
  for (const CanFrame& f : held.frames) frames.push(f);
  model::TruckModel truck = model::truck_model(roadload::shipped::mnroad_vehicle());
  truck.engine_losses = engine_loss_map(frames.finish());
  ASSERT_EQ(truck.engine_losses.size(), standing.hold_rpm.size());

  const Outcome as_sent = drive("mnroad-mainline-30mph", 90, false);
  const Outcome calibrated = drive("mnroad-mainline-30mph", 90, false, truck);
  ASSERT_EQ(calibrated.n, as_sent.n);
  const double bias_sent = as_sent.sum / static_cast<double>(as_sent.n);
  const double bias_cal = calibrated.sum / static_cast<double>(calibrated.n);
  std::printf("tractive force bias at 30 mph: EEC3 as sent %.1f N, with the engine-loss calibration %.1f N\n", bias_sent, bias_cal);
  // 1 N m at the flywheel is 8.7 N at the wheels in 8th gear; the calibration's sigma is 0.9 N m.
  EXPECT_GT(std::abs(bias_sent), 80.0);
  EXPECT_LT(std::abs(bias_cal), 20.0);
}

TEST(TractionFromJ1939, WithoutEc1TheTorqueHasNoScaleAndSaysSo) {
  const Outcome sink = drive("th66-55mph", 10, true);
  EXPECT_EQ(sink.n, 0u);
  EXPECT_EQ(sink.last_reason, Unusable::no_reference_torque);
  EXPECT_STREQ(to_string(sink.last_reason), "no reference torque (EC1 SPN 544 never received)");
}

}  // namespace
}  // namespace roadload::sim
