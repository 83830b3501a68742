// Dynamic rolling resistance from the simulated accelerometers (seed report Eq. 2.7-2.8): damper
// power per cell and per trip against the plant's true damper dissipation, the tire figures beside
// the true tire dissipation, and the joint line with the panel length it gives. The truck is placed
// by the plant's true position: this test is about the spectra, positioning is the analyzer's.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <vector>

#include "roadload/recording/vehicle_setup.hpp"
#include "roadload/running_stats.hpp"
#include "roadload/spectra/modes.hpp"
#include "roadload/vibration.hpp"
#include "sim_fixture.hpp"

namespace roadload::sim {
namespace {

constexpr double kFtToM = 0.3048;

struct Powers {
  double damper_w = 0, tire_w = 0;
};

class VibrationSink final : public test::PlantStepSink {
 public:
  VibrationSink(const Simulation& sim, VibrationAnalysis& va)
      : PlantStepSink(sim), va_(va), cells_(sim.route().def().cells.size() * va.layout().axles.size()) {}
  // Mean over the time axle i was in cell c, summed over axles, as truth/cells.csv has it.
  Powers truth_cell(std::size_t c) const {
    Powers p;
    const std::size_t n = va_.layout().axles.size();
    for (std::size_t i = 0; i < n; ++i) {
      p.damper_w += cells_[c * n + i].damper.mean;
      p.tire_w += cells_[c * n + i].tire.mean;
    }
    return p;
  }
  Powers truth_trip() const { return {trip_damper_.mean, trip_tire_.mean}; }
  // The least time any axle spent in cell c.
  double seconds_in_cell(std::size_t c) const {
    const std::size_t n = va_.layout().axles.size();
    double least = 1e300;
    for (std::size_t i = 0; i < n; ++i) least = std::min(least, cells_[c * n + i].seconds);
    return least;
  }

 private:
  struct Acc {
    RunningStats damper, tire;
    double seconds = 0;
  };
  void sample(const AccelSample& s) override { va_.push(s); }
  int cell_of(const TruckState& st, std::size_t axle) const { return cell_under(st, va_.layout().axles[axle].position_m); }
  void step(const TruckState& st) override {
    const std::size_t n = va_.layout().axles.size();
    std::array<int, kMaxContactAxles> cells{};
    double damper = 0, tire = 0;
    for (std::size_t i = 0; i < n; ++i) {
      cells[i] = cell_of(st, i);
      damper += st.axles[i].damper_power_w;
      tire += st.axles[i].tire_power_w;
      if (cells[i] >= 0) {
        cells_[static_cast<std::size_t>(cells[i]) * n + i].damper.add(st.axles[i].damper_power_w);
        cells_[static_cast<std::size_t>(cells[i]) * n + i].tire.add(st.axles[i].tire_power_w);
        cells_[static_cast<std::size_t>(cells[i]) * n + i].seconds += st.t_s - last_observed_s_;
      }
    }
    last_observed_s_ = st.t_s;
    trip_damper_.add(damper);
    trip_tire_.add(tire);
    if (st.t_s >= last_placed_s_ + 0.02) {  // placements at 50 Hz, as often as a fast wheel-speed message
      last_placed_s_ = st.t_s;
      va_.set_axle_cells(capture_time_from_ns(std::llround(st.t_s * 1e9)), std::span(cells.data(), n), st.speed_mps, st.x_m);
    }
  }

  VibrationAnalysis& va_;
  double last_observed_s_ = 0, last_placed_s_ = -1;
  std::vector<Acc> cells_;
  RunningStats trip_damper_, trip_tire_;
};

struct DriveResult {
  std::vector<std::pair<std::string, double>> cell_ratio;  // damper estimate / truth per full cell
  double trip_damper_ratio = 0;
  PavementGroups groups;
  std::vector<spectra::JointLine> guided, blind;  // per group
};

DriveResult run_drive(const std::string& scenario, std::uint64_t seed, double joint_faulting_m = -1) {
  const j1939::Database db = test::core_database();
  Scenario sc = test::builtin(scenario);
  if (joint_faulting_m >= 0) sc.effects.set(Effect::joint_faulting, joint_faulting_m);
  Simulation sim(sc, seed, db);
  const auto& cells = sim.route().def().cells;
  DriveResult r;
  r.groups = test::pavement_groups(sc);
  VibrationAnalysis va(test::axle_layout(sim.metadata()), recording::accelerometers(sim.metadata()), cells.size(),
                       r.groups.cell_group, r.groups.names.size());
  VibrationSink sink(sim, va);
  sim.run(sink, nullptr);

  const auto& sp = va.suspension();
  double trip_damper = 0, trip_eq27 = 0, trip_defl = 0;
  for (std::size_t a = 0; a < sp.axle_count(); ++a) {
    const auto p = sp.trip_power(a);
    trip_damper += p.damper_w;
    trip_eq27 += p.tire_eq27_w;
    trip_defl += p.tire_deflection_w;
  }
  const Powers truth = sink.truth_trip();
  r.trip_damper_ratio = trip_damper / truth.damper_w;
  std::printf("%s seed %llu: trip damper %.1f W (truth %.1f, %+.1f %%); tire Eq. 2.7 %.1f W, from deflection %.1f W (truth %.1f)\n",
              scenario.c_str(), static_cast<unsigned long long>(seed), trip_damper, truth.damper_w, 100 * (r.trip_damper_ratio - 1),
              trip_eq27, trip_defl, truth.tire_w);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    double est = 0, segs = 1e9;
    for (std::size_t a = 0; a < sp.axle_count(); ++a) {
      est += sp.cell_power(c, a).damper_w;
      segs = std::min(segs, sp.cell_power(c, a).segments);
    }
    const Powers t = sink.truth_cell(c);
    // Cells crossed whole, and by the spectra for 90 % of the time (not in a sensor's warm-up).
    const double hop_s = static_cast<double>(spectra::hop(sp.welch())) / sp.welch().fs_hz;
    if (segs * hop_s < 0.9 * sink.seconds_in_cell(c)) continue;
    r.cell_ratio.emplace_back(cells[c].id, est / t.damper_w);
  }
  const auto& modes = va.modes();
  const double bin = spectra::bin_hz(modes.spatial_welch());
  for (std::size_t g = 0; g < r.groups.names.size(); ++g) {
    std::vector<std::vector<double>> spatial;
    for (std::size_t s = 0; s < modes.sensor_count(); ++s) spatial.push_back(modes.spatial_density(s, static_cast<int>(g)));
    spectra::JointConfig guided;
    guided.expected_panel_m = r.groups.panel_m[g];
    r.blind.push_back(spectra::find_joint_line(spatial, bin));
    r.guided.push_back(r.groups.panel_m[g] > 0 ? spectra::find_joint_line(spatial, bin, guided) : spectra::JointLine{});
    std::printf("  %-18s blind: %s %.3f m (%.1f sigma)   guided: %s %.3f m (%.1f sigma)\n", r.groups.names[g].c_str(),
                r.blind.back().found ? "found" : "none ", r.blind.back().panel_m, r.blind.back().significance,
                r.guided.back().found ? "found" : "none ", r.guided.back().panel_m, r.guided.back().significance);
  }
  return r;
}

double worst_cell_error(const DriveResult& r) {
  double worst = 0;
  for (const auto& [cell, ratio] : r.cell_ratio) worst = std::max(worst, std::abs(ratio - 1));
  return worst;
}

// Seed report Sect. 6.3: damper power per cell within 5 % and per trip within 2 % of the plant's
// true dissipation. The scenario's joints (3.3 mm faulting, fitted to Table 6.5 by the gap tool)
// give the 15 ft line the report saw at 2.9 Hz: found blind, the panel within 3 %; the bituminous
// cells between the concrete ones show none.
TEST(VibrationFromSimulation, MainlineAt30MphDamperPowerAndThe15FtJoints) {
  const DriveResult r = run_drive("mnroad-mainline-30mph", 1);
  EXPECT_NEAR(r.trip_damper_ratio, 1.0, 0.02);
  EXPECT_GE(r.cell_ratio.size(), 25u);
  EXPECT_LT(worst_cell_error(r), 0.05);
  bool fifteen_ft = false;
  for (std::size_t g = 0; g < r.groups.names.size(); ++g) {
    if (r.groups.panel_m[g] == 0) {
      EXPECT_FALSE(r.blind[g].found) << r.groups.names[g];
    }
    if (r.groups.panel_m[g] != 15 * kFtToM) continue;
    fifteen_ft = true;
    ASSERT_TRUE(r.blind[g].found) << r.groups.names[g];
    EXPECT_NEAR(r.blind[g].panel_m, 15 * kFtToM, 0.03 * 15 * kFtToM);
  }
  EXPECT_TRUE(fifteen_ft);
}

// Joints that neither fault nor curl do not excite the truck: no line anywhere, blind.
TEST(VibrationFromSimulation, MainlineAt30MphWithoutFaultingShowsNoJointLine) {
  const DriveResult r = run_drive("mnroad-mainline-30mph", 1, 0.0);
  for (std::size_t g = 0; g < r.groups.names.size(); ++g) EXPECT_FALSE(r.blind[g].found) << r.groups.names[g];
}

// TH 10's 43-year-old concrete (3.3 mm faulting, 28 ft panels): the line found blind.
TEST(VibrationFromSimulation, Th10At55Mph) {
  const DriveResult r = run_drive("th10-55mph", 1);
  EXPECT_NEAR(r.trip_damper_ratio, 1.0, 0.02);
  EXPECT_LT(worst_cell_error(r), 0.05);
  ASSERT_EQ(r.groups.names.size(), 1u);
  ASSERT_TRUE(r.blind[0].found);
  EXPECT_NEAR(r.blind[0].panel_m, 28 * kFtToM, 0.03 * 28 * kFtToM);
}

TEST(VibrationFromSimulation, Th66At55MphHasNoJointLine) {
  const DriveResult r = run_drive("th66-55mph", 1);
  EXPECT_NEAR(r.trip_damper_ratio, 1.0, 0.02);
  for (const auto& j : r.blind) EXPECT_FALSE(j.found);
}

}  // namespace
}  // namespace roadload::sim
