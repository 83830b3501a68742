// Vehicle files: the shipped MnROAD truck reads as the seed report's Tables 6.1-6.2 describe it and
// turns into the estimator's truck model; a bad value is refused with its file, line and field.
#include "roadload/vehicle_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "roadload/drive_analyzer.hpp"
#include "roadload/model/longitudinal.hpp"
#include "roadload/recording/metadata.hpp"
#include "vehicles.hpp"

namespace roadload {
namespace {

TEST(VehicleFile, TheMnroadTruckIsTheReportsTruck) {
  const Vehicle& v = shipped::mnroad_vehicle();
  EXPECT_EQ(v.name, "mnroad-truck");
  EXPECT_EQ(v.vin, "1HSGSSJT8CJ536729");
  ASSERT_EQ(v.axles.size(), 5u);
  EXPECT_DOUBLE_EQ(v.mass_kg(), 36152.0);                  // Table 6.1
  EXPECT_NEAR(v.cg_behind_front_m(), 9.742, 0.001);        // from Table 6.2's loads
  EXPECT_DOUBLE_EQ(v.engine.reference_torque_nm, 2386.0);  // EC1 SPN 544 of the idle trace
  EXPECT_EQ(v.driveline.gear_ratios.size(), 10u);
  EXPECT_EQ(v.accelerometers.size(), 8u);
  ASSERT_NE(v.drive_axle(), nullptr);
  EXPECT_EQ(v.drive_axle()->name, "drive1");
}

TEST(VehicleFile, TheTruckModelTakesTheDriveTiresAndEveryWheelEnd) {
  const model::TruckModel m = model::truck_model(shipped::mnroad_vehicle());
  EXPECT_DOUBLE_EQ(m.mass_kg, 36152.0);
  EXPECT_DOUBLE_EQ(m.tire_radius_m, 0.5);
  EXPECT_DOUBLE_EQ(m.wheel_inertia_mass_kg, 936.0);  // 18 wheel ends x 13 kg m^2 / 0.5^2
  EXPECT_DOUBLE_EQ(m.final_drive, 3.36);
  EXPECT_DOUBLE_EQ(m.cda_prior_m2, 6.2);
  const AnalyzerConfig c = analyzer_config(shipped::mnroad_vehicle());
  EXPECT_NEAR(c.filter.torque_bias_sigma_nm, 9.741, 0.001);  // EEC3's whole percent at 2,386 N m
  EXPECT_EQ(c.axles.size(), 5u);
  EXPECT_DOUBLE_EQ(c.antenna_behind_front_m, 2.5);
}

class VehicleFileErrors : public ::testing::Test {
 protected:
  // The shipped file with `from` replaced by `to` (the first occurrence), written to a temp file.
  std::string variant(const std::string& from, const std::string& to) {
    std::ifstream in(std::filesystem::path(ROADLOAD_CONFIG_DIR) / "vehicles" / "mnroad-truck.toml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    std::string name = "roadload-vehicle-";
    name.append(::testing::UnitTest::GetInstance()->current_test_info()->name()).append(".toml");
    path_ = std::filesystem::temp_directory_path() / name;
    std::ofstream(path_) << text;
    return path_.string();
  }
  void TearDown() override { std::filesystem::remove(path_); }
  ParseError error_of(const std::string& from, const std::string& to) {
    auto v = load_vehicle_file(variant(from, to));
    EXPECT_FALSE(v.ok()) << "accepted " << to;
    return v.ok() ? ParseError{} : v.error();
  }
  std::filesystem::path path_;
};

TEST_F(VehicleFileErrors, NotANumberIsRefusedWithItsLineAndField) {
  const ParseError e = error_of("cda_m2 = 6.2", "cda_m2 = nan");
  EXPECT_EQ(e.field, "body.cda_m2");
  EXPECT_GT(e.line, 0);
}

TEST_F(VehicleFileErrors, AnImpossibleValueIsRefused) {
  EXPECT_EQ(error_of("load_kg = 5307", "load_kg = 0").field, "axle[0].load_kg");
  EXPECT_EQ(error_of("efficiency = 0.94", "efficiency = 1.5").field, "driveline.efficiency");
  EXPECT_EQ(error_of("unsprung_kg = 421.0", "unsprung_kg = 6000").field, "axle[0].unsprung_kg");
}

TEST_F(VehicleFileErrors, AnUnknownKeyIsATypo) {
  EXPECT_EQ(error_of("lhv_jpkg = 42.8e6", "lhv_jpkg = 42.8e6\nlhv_per_kg = 1").field, "fuel.lhv_per_kg");
}

// Files written before the key read as "not known"; a value it cannot have is still refused.
TEST_F(VehicleFileErrors, TheTireRadiusSpreadMayBeLeftOutButNotImpossible) {
  auto v = load_vehicle_file(variant("tire_radius_sigma_m = 0.004", ""));
  ASSERT_TRUE(v.ok()) << v.error().to_string();
  EXPECT_EQ(v.value().tire_radius_sigma_m, 0.0);
  EXPECT_EQ(format_vehicle(v.value()).find("tire_radius_sigma_m"), std::string::npos);
  EXPECT_EQ(error_of("tire_radius_sigma_m = 0.004", "tire_radius_sigma_m = 0.5").field, "body.tire_radius_sigma_m");
}

TEST_F(VehicleFileErrors, TheTiresCrrSpreadMayBeLeftOutButNotImpossible) {
  auto v = load_vehicle_file(variant("tire_crr_sigma = 0.06", ""));
  ASSERT_TRUE(v.ok()) << v.error().to_string();
  EXPECT_EQ(v.value().tire_crr_sigma, 0.0);
  EXPECT_EQ(format_vehicle(v.value()).find("tire_crr_sigma"), std::string::npos);
  const ParseError e = error_of("tire_crr_sigma = 0.06", "tire_crr_sigma = 0.6");
  EXPECT_EQ(e.field, "body.tire_crr_sigma");
  EXPECT_GT(e.line, 0);
}

TEST_F(VehicleFileErrors, AxlesGoFrontToRear) {
  EXPECT_EQ(error_of("position_m = 16.45", "position_m = 1.0").field, "axle[3].position_m");
}

TEST_F(VehicleFileErrors, EngineMapNeedsEc1sSixPoints) {
  EXPECT_EQ(error_of("full_load_rpm = [650, 900, 1400, 1675, 2086, 2100]", "full_load_rpm = [650, 900]").field,
            "engine.full_load_rpm");
}

TEST_F(VehicleFileErrors, AnAccelerometerMustSitOnAnAxleOfTheTruck) {
  EXPECT_EQ(error_of("axle = \"front\"", "axle = \"fifth\"").field, "accelerometer[0].axle");
}

TEST(VehicleFile, TheSecondShippedTruckIsA30TonneTractorWithAnEighteenSpeed) {
  auto v = load_vehicle_file(resolve_vehicle("tractor-53ft-18speed", ROADLOAD_CONFIG_DIR));
  ASSERT_TRUE(v.ok()) << v.error().to_string();
  EXPECT_NEAR(v.value().mass_kg(), 30240.0, 1e-9);
  EXPECT_EQ(v.value().driveline.gear_ratios.size(), 18u);
  EXPECT_DOUBLE_EQ(v.value().driveline.gear_ratios.back(), 0.73);
  EXPECT_DOUBLE_EQ(v.value().driveline.efficiency_sigma, 0.015);
  EXPECT_GT(v.value().engine.torque_scale_sigma, 0.0);
  EXPECT_GT(v.value().mass_sigma_kg, 0.0);
  ASSERT_NE(v.value().drive_axle(), nullptr);
  EXPECT_EQ(v.value().drive_axle()->name, "drive1");
}

// Written back and read again, a vehicle is the same vehicle: `vehicle identify` writes files this
// way and recordings carry them so.
Vehicle reread(const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("roadload-vehicle-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + ".toml");
  std::ofstream(path) << text;
  auto v = load_vehicle_file(path.string());
  std::filesystem::remove(path);
  EXPECT_TRUE(v.ok()) << v.error().to_string() << "\n" << text;
  return v.ok() ? v.value() : Vehicle{};
}

TEST(VehicleFile, AFormattedVehicleReadsBackExactly) {
  for (const char* name : {"mnroad-truck", "tractor-53ft-18speed"}) {
    auto v = load_vehicle_file(resolve_vehicle(name, ROADLOAD_CONFIG_DIR));
    ASSERT_TRUE(v.ok());
    const std::string text = format_vehicle(v.value());
    const Vehicle back = reread(text);
    EXPECT_EQ(format_vehicle(back), text) << name;
    EXPECT_EQ(back.mass_kg(), v.value().mass_kg());
    EXPECT_EQ(back.driveline.gear_ratios, v.value().driveline.gear_ratios);
    EXPECT_EQ(back.accelerometers.size(), v.value().accelerometers.size());
  }
}

TEST(VehicleFile, NotesBecomeCommentsAboveTheirValues) {
  const std::string text = format_vehicle(shipped::mnroad_vehicle(),
                                          {{"axle[1].tire_radius_m", "GNSS speed against wheel speed\n3 recordings"}});
  const auto at = text.find("# GNSS speed against wheel speed\n# 3 recordings\ntire_radius_m = 0.5\n");
  ASSERT_NE(at, std::string::npos) << text;
  EXPECT_GT(at, text.find("name = \"drive1\""));  // the second axle's
}

TEST(VehicleFile, ARecordingCarriesTheVehicleItWasMadeWith) {
  recording::Metadata m;
  m.clock_source = "simulated";
  m.vehicle["mass_kg"] = 30000;
  m.vehicle_file = shipped::mnroad_vehicle();
  const std::string text = recording::format_metadata(m);
  auto back = recording::parse_metadata(text, "meta.toml");
  ASSERT_TRUE(back.ok()) << back.error().to_string() << "\n" << text;
  ASSERT_TRUE(back.value().vehicle_file.has_value());
  EXPECT_EQ(format_vehicle(*back.value().vehicle_file), format_vehicle(shipped::mnroad_vehicle()));
  EXPECT_DOUBLE_EQ(back.value().vehicle.at("mass_kg"), 30000.0);
}

TEST(VehicleFile, ABadValueInARecordingsVehicleIsNamedThere) {
  recording::Metadata m;
  m.vehicle_file = shipped::mnroad_vehicle();
  std::string text = recording::format_metadata(m);
  const auto at = text.find("efficiency = 0.94");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 17, "efficiency = nan");
  auto back = recording::parse_metadata(text, "rec/meta.toml");
  ASSERT_FALSE(back.ok());
  EXPECT_EQ(back.error().file, "rec/meta.toml");
  EXPECT_EQ(back.error().field, "vehicle.file.driveline.efficiency");
  EXPECT_GT(back.error().line, 0);
}

TEST(VehicleFile, AMissingFileSaysSo) {
  auto v = load_vehicle_file("/nonexistent/vehicle.toml");
  ASSERT_FALSE(v.ok());
  EXPECT_EQ(v.error().file, "/nonexistent/vehicle.toml");
}

}  // namespace
}  // namespace roadload
