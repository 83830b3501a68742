// Same scenario and seed give byte-identical recordings and truth; another seed does not.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "roadload/recording/writer.hpp"
#include "roadload/sim/recording_sink.hpp"
#include "sim_fixture.hpp"

namespace roadload::sim {
namespace {

namespace fs = std::filesystem;

fs::path simulate(const std::string& tag, std::uint64_t seed) {
  const fs::path dir = fs::temp_directory_path() / ("roadload-determinism-" + tag);
  fs::remove_all(dir);
  Scenario sc = test::builtin("th10-55mph");
  sc.duration = Seconds{8.0};
  sc.effects.set(Effect::wind_gusts, 1.0);
  sc.effects.set(Effect::fan_engagement, 0.2);
  const j1939::Database db = test::core_database();
  Simulation sim(sc, seed, db);
  auto w = recording::RecordingWriter::create((dir / "rec").string(), sim.metadata());
  EXPECT_TRUE(w.ok());
  fs::create_directories(dir / "truth");
  TruthRecorder truth(sim.route(), sim.plant().truck());
  EXPECT_FALSE(truth.open((dir / "truth").string()).has_value());
  RecordingSink sink(w.value());
  sim.run(sink, &truth);
  EXPECT_FALSE(w.value().close().has_value());
  EXPECT_FALSE(truth.finish(sim.truth_toml()).has_value());
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Determinism, SameSeedSameBytesOtherSeedOtherBytes) {
  const fs::path a = simulate("a", 42), b = simulate("b", 42), c = simulate("c", 43);
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(a)) {
    if (!entry.is_regular_file()) continue;
    const fs::path rel = fs::relative(entry.path(), a);
    const std::string bytes = slurp(entry.path());
    EXPECT_FALSE(bytes.empty()) << rel;
    EXPECT_EQ(bytes, slurp(b / rel)) << rel << " differs between two runs with the same seed";
    ++files;
  }
  EXPECT_EQ(files, 9);  // meta, can, accel, gnss, weather; series, axles, cells, truth.toml
  EXPECT_NE(slurp(a / "rec" / "accel.csv"), slurp(c / "rec" / "accel.csv"));
  // The road is the scenario's, not the seed's: the recordings describe the same truck and road.
  // Only the run's id, a hash of what makes the run, the seed among it, differs.
  const auto without_id = [](std::string text) {
    const auto at = text.find("recording_id = ");
    return at == std::string::npos ? text : text.erase(at, text.find('\n', at) - at + 1);
  };
  const std::string meta_a = slurp(a / "rec" / "meta.toml"), meta_c = slurp(c / "rec" / "meta.toml");
  EXPECT_NE(meta_a, meta_c);
  EXPECT_EQ(without_id(meta_a), without_id(meta_c));
}

}  // namespace
}  // namespace roadload::sim
