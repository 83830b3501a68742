// Eq. 2.1 on a simulated drive: the contact force per axle estimated from the recording's
// accelerometers (with their offsets, gains, cross-axis errors and noise) and its metadata alone,
// against the plant's true tire force. The truth is the same quantity as truth/axles.csv
// (fz_<axle>_n, TruckState::axles[i].tire_force_n), read here at every physics step.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <vector>

#include "roadload/contact_forces.hpp"
#include "sim_fixture.hpp"

namespace roadload::sim {
namespace {

// Feeds the estimator as samples arrive and reads the plant's truth at each new physics step.
// The truck's position comes from the plant (true x and grade): this test is about the forces,
// positioning is the analyzer's.
class ContactSink final : public test::PlantStepSink {
 public:
  ContactSink(const Simulation& sim, ContactForces& cf, double warmup_s)
      : PlantStepSink(sim),
        cf_(cf),
        warmup_s_(warmup_s),
        truth_trip_(cf.axle_count()),
        truth_cells_(sim.route().def().cells.size() * cf.axle_count()) {}

  const RunningStats& truth_trip(std::size_t axle) const { return truth_trip_[axle]; }
  const RunningStats& truth_cell(std::size_t cell, std::size_t axle) const { return truth_cells_[cell * cf_.axle_count() + axle]; }

 private:
  void step(const TruckState& st) override {
    place(st);
    if (st.t_s >= warmup_s_) observe_truth(st);
  }
  void sample(const AccelSample& s) override { cf_.push(s); }
  int cell_of(const TruckState& st, std::size_t axle) const { return cell_under(st, cf_.layout().axles[axle].position_m); }
  void place(const TruckState& st) {
    std::array<int, kMaxContactAxles> cells{};
    for (std::size_t i = 0; i < cf_.axle_count(); ++i) cells[i] = cell_of(st, i);
    cf_.set_axle_cells(capture_time_from_ns(std::llround(st.t_s * 1e9)), std::span(cells.data(), cf_.axle_count()), st.grade_rad,
                       st.speed_mps);
  }
  void observe_truth(const TruckState& st) {
    for (std::size_t i = 0; i < cf_.axle_count(); ++i) {
      // Layout order is the truck's axle order (front, drive1, drive2, trailer1, trailer2).
      const double fz = st.axles[i].tire_force_n;
      truth_trip_[i].add(fz);
      if (const int c = cell_of(st, i); c >= 0) truth_cells_[static_cast<std::size_t>(c) * cf_.axle_count() + i].add(fz);
    }
  }

  ContactForces& cf_;
  double warmup_s_;
  std::vector<RunningStats> truth_trip_;
  std::vector<RunningStats> truth_cells_;
};

TEST(ContactForcesFromSimulation, MetadataCarriesEachAxlesUnsprungMass) {
  const j1939::Database db = test::core_database();
  Simulation sim(test::builtin("mnroad-mainline-30mph"), 1, db);
  const recording::Metadata m = sim.metadata();
  const TruckParams& t = sim.plant().truck();
  for (const auto& a : t.axles) {
    const auto it = m.vehicle.find(a.name + "_unsprung_kg");
    ASSERT_NE(it, m.vehicle.end()) << a.name;
    EXPECT_DOUBLE_EQ(it->second, a.vertical.unsprung_kg) << a.name;
  }
  const AxleLayout l = test::axle_layout(m);
  ASSERT_EQ(l.axles.size(), t.axles.size());
  for (std::size_t i = 0; i < l.axles.size(); ++i) {
    EXPECT_EQ(l.axles[i].name, t.axles[i].name);
    EXPECT_DOUBLE_EQ(l.axles[i].sprung_kg, t.axles[i].vertical.sprung_kg) << t.axles[i].name;
  }
}

// 60 s of the Mainline at 30 mph, seed 1: per axle, the estimated dynamic-force standard deviation
// within 10 % of the true tire force's, and the mean within 1 %. Drive2 and trailer2 have no frame
// sensor of their own and use drive1's and trailer1's: their sprung term is the neighbour's body.
TEST(ContactForcesFromSimulation, MainlineAt30MphMatchesTheTrueTireForcePerAxle) {
  const j1939::Database db = test::core_database();
  Scenario sc = test::builtin("mnroad-mainline-30mph");
  sc.duration = Seconds{60.0};
  Simulation sim(sc, 1, db);
  const ContactConfig config;
  ContactForces cf(test::axle_layout(sim.metadata()), sim.route().def().cells.size(), config);
  ContactSink sink(sim, cf, config.warmup.count());
  sim.run(sink, nullptr);

  for (std::size_t i = 0; i < cf.axle_count(); ++i) {
    const AxleContact& a = cf.layout().axles[i];
    const AxleForceStats est = cf.trip(i);
    const RunningStats& truth = sink.truth_trip(i);
    const double std_err = est.dynamic.std_n / truth.std() - 1.0;
    const double mean_err = est.fz.mean_n / truth.mean - 1.0;
    std::printf(
        "%-8s frame %-8s  F_z mean %8.0f N (truth %8.0f, %+.3f %%)  dynamic std %6.0f N (truth %6.0f, %+.1f %%)  paired %llu\n",
        a.name.c_str(), a.frame_of.c_str(), est.fz.mean_n, truth.mean, 100 * mean_err, est.dynamic.std_n, truth.std(), 100 * std_err,
        static_cast<unsigned long long>(cf.counters(i).paired));
    EXPECT_LT(std::abs(std_err), 0.10) << a.name;
    EXPECT_LT(std::abs(mean_err), 0.01) << a.name;
    EXPECT_EQ(cf.counters(i).stale_frame, 0u) << a.name;
    EXPECT_GT(cf.counters(i).paired, 50000u) << a.name;
  }
  EXPECT_EQ(cf.unknown_sensor_samples(), 0u);

  // Per cell, for the cells an axle spent at least 10 s in: the same comparison, printed.
  for (std::size_t c = 0; c < cf.cell_count(); ++c) {
    for (std::size_t i = 0; i < cf.axle_count(); ++i) {
      const RunningStats& truth = sink.truth_cell(c, i);
      const AxleForceStats est = cf.cell(c, i);
      if (est.fz.count < 12000 || truth.n < 24000) continue;
      std::printf("cell %-3s %-8s  F_z mean %+.3f %%  std %+.1f %%\n", sim.route().def().cells[c].id.c_str(),
                  cf.layout().axles[i].name.c_str(), 100 * (est.fz.mean_n / truth.mean - 1.0),
                  100 * (est.fz.std_n / truth.std() - 1.0));
      EXPECT_LT(std::abs(est.fz.mean_n / truth.mean - 1.0), 0.01);
    }
  }
}

}  // namespace
}  // namespace roadload::sim
