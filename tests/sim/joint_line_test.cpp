// Jointed concrete puts a spectral line at v/L into the simulated accelerometers: 2.93 Hz at
// 30 mph on 15 ft panels, 2.88 Hz at 55 mph on 28 ft panels (seed report Figs. 6.7, 6.10).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "roadload/sim/units.hpp"
#include "sim_fixture.hpp"
#include "welch.hpp"

namespace roadload::sim {
namespace {

// A straight road of one concrete surface: the route and scenario written as a user would.
std::string write_scenario(const std::string& name, double panel_m, double speed_mph) {
  const auto dir = std::filesystem::temp_directory_path() / ("roadload-joint-" + name);
  std::filesystem::create_directories(dir / "scenarios");
  std::filesystem::create_directories(dir / "routes");
  std::ofstream(dir / "routes" / "joints.toml") << "name = \"joints\"\ndefault_iri_m_per_km = 1.0\n"
                                                   "[[point]]\nlat_deg = 45.0\nlon_deg = -93.0\nelev_m = 250\n"
                                                   "[[point]]\nlat_deg = 45.0\nlon_deg = -92.95\nelev_m = 250\n"
                                                   "[[cell]]\nid = \"C1\"\nstart_m = 0\nlength_m = 3900\n"
                                                   "surface = \"concrete\"\ncrr = 0.0055\njoint_spacing_m = "
                                                << panel_m << "\n";
  const auto path = dir / "scenarios" / "joints.toml";
  std::ofstream(path) << "name = \"joints\"\nroute = \"joints\"\nspeed_mph = " << speed_mph
                      << "\nstart_m = 50\nduration_s = 100\n[effects]\njoint-faulting = 0.002\n";
  return path.string();
}

double peak_frequency(double panel_m, double speed_mph) {
  auto sc = load_scenario(write_scenario(std::to_string(speed_mph), panel_m, speed_mph), ROADLOAD_CONFIG_DIR);
  EXPECT_TRUE(sc.ok()) << (sc.ok() ? "" : sc.error().to_string());
  sc.value().accelerometers = 1;  // TLF1, the front axle
  const j1939::Database db = test::core_database();
  Simulation sim(sc.value(), 11, db);
  test::MemorySink sink;
  sim.run(sink, nullptr);
  // Block means of 12 samples (1200 -> 100 Hz) are the decimation a logger would do.
  std::vector<double> z;
  for (std::size_t i = 0; i + 12 <= sink.accels.size(); i += 12) {
    double s = 0;
    for (std::size_t k = 0; k < 12; ++k) s += sink.accels[i + k].z_mps2;
    z.push_back(s / 12);
  }
  const roadload::test::Psd psd = roadload::test::welch(z, 100.0, 4096);
  double best_f = 0, best = 0;
  for (std::size_t k = 0; k < psd.freq.size(); ++k) {
    if (psd.freq[k] > 2.0 && psd.freq[k] < 4.0 && psd.density[k] > best) {
      best = psd.density[k];
      best_f = psd.freq[k];
    }
  }
  std::printf("panel %.3f m at %.0f mph: PSD peak in 2-4 Hz at %.4f Hz\n", panel_m, speed_mph, best_f);
  return best_f;
}

TEST(JointLine, FifteenFootPanelsAt30MphGive2p93Hz) {
  const double expected = 30 * kMps_per_mph / (15 * kM_per_ft);
  EXPECT_NEAR(expected, 2.933, 0.001);
  EXPECT_NEAR(peak_frequency(15 * kM_per_ft, 30), expected, 100.0 / 4096);
}

TEST(JointLine, TwentyEightFootPanelsAt55MphGive2p88Hz) {
  const double expected = 55 * kMps_per_mph / (28 * kM_per_ft);
  EXPECT_NEAR(expected, 2.881, 0.001);
  EXPECT_NEAR(peak_frequency(28 * kM_per_ft, 55), expected, 100.0 / 4096);
}

}  // namespace
}  // namespace roadload::sim
