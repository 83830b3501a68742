// Bad scenario and route files stop with file, line and field, and never crash.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sim_fixture.hpp"

namespace roadload::sim {
namespace {

namespace fs = std::filesystem;

class ScenarioFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("roadload-scenario-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "scenarios");
    fs::create_directories(dir_ / "routes");
    write("routes/r.toml",
          "name = \"r\"\n[[point]]\nlat_deg = 45\nlon_deg = -93\nelev_m = 250\n"
          "[[point]]\nlat_deg = 45\nlon_deg = -92.99\nelev_m = 251\n"
          "[[cell]]\nid = \"A\"\nstart_m = 10\nlength_m = 100\nsurface = \"bituminous\"\ncrr = 0.006\n");
  }
  void write(const std::string& rel, const std::string& text) { std::ofstream(dir_ / rel) << text; }
  Parsed<Scenario> load(const std::string& text) {
    write("scenarios/s.toml", text);
    return load_scenario((dir_ / "scenarios" / "s.toml").string(), ROADLOAD_CONFIG_DIR);
  }
  fs::path dir_;
};

TEST_F(ScenarioFile, AGoodFileLoadsWithItsRouteAndEffects) {
  auto s = load("name = \"s\"\nroute = \"r\"\nspeed_mph = 30\n[effects]\nwind-gusts = 0.5\n");
  ASSERT_TRUE(s.ok()) << s.error().to_string();
  EXPECT_EQ(s.value().route.cells.size(), 1u);
  EXPECT_TRUE(s.value().effects.on(Effect::wind_gusts));
  EXPECT_DOUBLE_EQ(s.value().effects.magnitude(Effect::wind_gusts), 0.5);
  EXPECT_NEAR(s.value().end_m, 788.47, 0.01);  // 0.01 deg of longitude at 45 N on WGS84: 78,846.8 m per degree
}

TEST_F(ScenarioFile, UnknownEffectNamesFileLineAndField) {
  auto s = load("name = \"s\"\nroute = \"r\"\nspeed_mph = 30\n[effects]\nwind-gust = 0.5\n");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().line, 5);
  EXPECT_EQ(s.error().field, "effects.wind-gust");
  EXPECT_NE(s.error().to_string().find("s.toml:5: effects.wind-gust"), std::string::npos) << s.error().to_string();
}

TEST_F(ScenarioFile, BadValuesAreRejected) {
  EXPECT_EQ(load("name = \"s\"\nroute = \"r\"\nspeed_mph = \"fast\"\n").error().field, "speed_mph");
  EXPECT_EQ(load("name = \"s\"\nroute = \"r\"\nspeed_mph = 300\n").error().field, "speed_mph");
  EXPECT_EQ(load("name = \"s\"\nroute = \"r\"\nspeed_mph = 30\nspeed_limit = 3\n").error().field, "speed_limit");
  EXPECT_EQ(load("name = \"s\"\nroute = \"r\"\nspeed_mph = 30\nroad_seed = 1.5\n").error().field, "road_seed");
  EXPECT_EQ(load("name = \"s\"\nroute = \"r\"\nspeed_mph = 30\naccel_rate_hz = 9000\n").error().field, "accel_rate_hz");
  EXPECT_EQ(load("name = \"s\"\nroute = \"r\"\nspeed_mph = 30\nstart_utc = \"today\"\n").error().field, "start_utc");
  EXPECT_EQ(load("name = \"s\"\nspeed_mph = 30\n").error().field, "route");
  EXPECT_EQ(load("name = \"s\"\nroute = \"r\"\nspeed_mph = 30\nstart_m = 900\n").error().field, "end_m");
  EXPECT_EQ(load("name = \"s\"\nroute = \"r\"\nspeed_mph = 30 30\n").error().field, "syntax");
  const auto tires = load("name = \"s\"\nroute = \"r\"\nspeed_mph = 30\ntire_crr_scale = 2.5\n");
  ASSERT_FALSE(tires.ok());
  EXPECT_EQ(tires.error().field, "tire_crr_scale");
  EXPECT_EQ(tires.error().line, 4);
  EXPECT_NE(tires.error().message.find("0.5-2.0"), std::string::npos) << tires.error().to_string();
  const auto good = load("name = \"s\"\nroute = \"r\"\nspeed_mph = 30\ntire_crr_scale = 1.1\ndriven_before_s = 600\n");
  ASSERT_TRUE(good.ok()) << good.error().to_string();
  EXPECT_DOUBLE_EQ(good.value().tire_crr_scale, 1.1);
  EXPECT_DOUBLE_EQ(good.value().driven_before.count(), 600.0);
  const auto cold = load("name = \"s\"\nroute = \"r\"\nspeed_mph = 30\ndriven_before_s = -5\n");
  ASSERT_FALSE(cold.ok());
  EXPECT_EQ(cold.error().field, "driven_before_s");
  EXPECT_EQ(cold.error().line, 4);
  const std::string city = "name = \"s\"\nroute = \"r\"\nspeed_mph = 30\n[stop_and_go]\n";
  EXPECT_EQ(load(city + "every_m = 500\ncrawl_mph = 40\ncrawl_m = 60\n").error().field, "stop_and_go.crawl_mph");
  EXPECT_EQ(load(city + "every_m = 50\ncrawl_mph = 3\ncrawl_m = 20\n").error().field, "stop_and_go.every_m");
  EXPECT_EQ(load(city + "every_m = 500\ncrawl_mph = 3\ncrawl_m = 600\n").error().field, "stop_and_go.crawl_m");
  EXPECT_EQ(load(city + "every_m = 500\ncrawl_mph = 3\n").error().field, "stop_and_go.crawl_m");
  EXPECT_EQ(load(city + "every_m = 500\ncrawl_mph = 3\ncrawl_m = 60\nlights = 2\n").error().field, "stop_and_go.lights");
}

TEST_F(ScenarioFile, RouteErrorsNameTheRouteFile) {
  write("routes/r.toml", "name = \"r\"\n[[point]]\nlat_deg = 95\nlon_deg = -93\nelev_m = 250\n");
  auto s = load("name = \"s\"\nroute = \"r\"\nspeed_mph = 30\n");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().file.find("routes/r.toml"), std::string::npos);
  EXPECT_EQ(s.error().field, "point");  // fewer than two points

  write("routes/r.toml",
        "name = \"r\"\n[[point]]\nlat_deg = 95\nlon_deg = -93\nelev_m = 250\n"
        "[[point]]\nlat_deg = 45\nlon_deg = -93\nelev_m = 250\n");
  s = load("name = \"s\"\nroute = \"r\"\nspeed_mph = 30\n");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().field, "point[0].lat_deg");
  EXPECT_EQ(s.error().line, 3);

  write("routes/r.toml",
        "name = \"r\"\n[[point]]\nlat_deg = 45\nlon_deg = -93\nelev_m = 250\n"
        "[[point]]\nlat_deg = 45\nlon_deg = -92.99\nelev_m = 250\n"
        "[[cell]]\nid = \"A\"\nstart_m = 10\nlength_m = 5000\nsurface = \"bituminous\"\ncrr = 0.006\n");
  s = load("name = \"s\"\nroute = \"r\"\nspeed_mph = 30\n");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().field, "cell A");
}

TEST(BuiltinScenarios, AllLoad) {
  const auto names = builtin_scenarios(ROADLOAD_CONFIG_DIR);
  for (const char* required : {"mnroad-mainline-30mph", "mnroad-mainline-64mph", "th10-55mph", "th66-55mph"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), required), names.end()) << required;
  }
  for (const auto& n : names) {
    auto s = load_scenario(n, ROADLOAD_CONFIG_DIR);
    EXPECT_TRUE(s.ok()) << n << ": " << (s.ok() ? "" : s.error().to_string());
  }
}

}  // namespace
}  // namespace roadload::sim
