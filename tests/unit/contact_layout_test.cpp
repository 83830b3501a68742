// The contact-force layout: which accelerometers serve which axle, which frame sensor a tandem's
// trailing axle borrows, and what is named when one is missing.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "contact_layout.hpp"

namespace roadload {
namespace {

using namespace contact_test;

TEST(ContactLayout, MapsTheMnroadSensorsAndBorrowsTheTandemFrames) {
  const AxleLayout l = mnroad_layout();
  ASSERT_EQ(l.axles.size(), 5u);
  const char* names[] = {"front", "drive1", "drive2", "trailer1", "trailer2"};
  const int axle_sensor[] = {0, 2, 4, 5, 7};
  const int frame_sensor[] = {1, 3, 3, 6, 6};
  const char* frame_of[] = {"front", "drive1", "drive1", "trailer1", "trailer1"};
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(l.axles[i].name, names[i]);
    EXPECT_EQ(l.axles[i].axle_sensor, axle_sensor[i]) << names[i];
    EXPECT_EQ(l.axles[i].frame_sensor, frame_sensor[i]) << names[i];
    EXPECT_EQ(l.axles[i].frame_of, frame_of[i]) << names[i];
    EXPECT_DOUBLE_EQ(l.axles[i].sprung_kg + l.axles[i].unsprung_kg, l.axles[i].load_kg);
  }
  // The vehicle file's physical unsprung masses (docs/simulator-parameters.md 1.1).
  EXPECT_DOUBLE_EQ(l.axles[0].unsprung_kg, 421.0);
  EXPECT_DOUBLE_EQ(l.axles[1].unsprung_kg, 701.5);
  EXPECT_DOUBLE_EQ(l.axles[3].unsprung_kg, 595.0);
  EXPECT_DOUBLE_EQ(l.axles[1].sprung_kg, 7734.0 - 701.5);
}

TEST(ContactLayout, TakesUnsprungMassesFromTheVehicle) {
  Vehicle v = mnroad_vehicle();
  v.axles[0].unsprung_kg = 178.6;
  v.axles[4].unsprung_kg = 321.1;
  const auto p = placements(kMounts);
  const auto l = build_axle_layout(p, v);
  ASSERT_TRUE(l.ok());
  EXPECT_DOUBLE_EQ(l.value().axles[0].unsprung_kg, 178.6);
  EXPECT_DOUBLE_EQ(l.value().axles[0].sprung_kg, 5307.0 - 178.6);
  EXPECT_DOUBLE_EQ(l.value().axles[4].unsprung_kg, 321.1);
}

TEST(ContactLayout, AnAxleWithItsOwnFrameSensorUsesIt) {
  auto mounts = kMounts;
  mounts.push_back({9, "tractor-drive2-frame-left"});
  const auto p = placements(mounts);
  const auto l = build_axle_layout(p, mnroad_vehicle());
  ASSERT_TRUE(l.ok());
  EXPECT_EQ(l.value().axles[2].frame_sensor, 9);
  EXPECT_EQ(l.value().axles[2].frame_of, "drive2");
  EXPECT_EQ(l.value().axles[1].frame_sensor, 3);
}

TEST(ContactLayout, NamesTheMissingAxleSensor) {
  auto mounts = kMounts;
  std::erase_if(mounts, [](const auto& m) { return m.second == "tractor-drive2-axle-left"; });
  const auto p = placements(mounts);
  const auto l = build_axle_layout(p, mnroad_vehicle(), "rec/meta.toml");
  ASSERT_FALSE(l.ok());
  const std::string msg = l.error().to_string();
  EXPECT_NE(msg.find("rec/meta.toml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("tractor-drive2-axle-left"), std::string::npos) << msg;
  EXPECT_NE(msg.find("drive2"), std::string::npos) << msg;
}

TEST(ContactLayout, NamesTheMissingFrameSensorAndDoesNotBorrowAcrossUnits) {
  auto mounts = kMounts;
  std::erase_if(mounts, [](const auto& m) { return m.second == "trailer-axle1-frame-left"; });
  const auto p = placements(mounts);
  const auto l = build_axle_layout(p, mnroad_vehicle());
  ASSERT_FALSE(l.ok());
  const std::string msg = l.error().to_string();
  EXPECT_NE(msg.find("trailer-axle1-frame-left"), std::string::npos) << msg;
  EXPECT_NE(msg.find("trailer1"), std::string::npos) << msg;
}

TEST(ContactLayout, LenientBuildSkipsAxlesWithoutSensorsAndSaysWhy) {
  auto mounts = kMounts;
  std::erase_if(mounts, [](const auto& m) { return m.second.starts_with("trailer"); });
  const auto p = placements(mounts);
  const auto l = build_axle_layout(p, mnroad_vehicle(), "meta.toml", {.skip_axles_without_sensors = true});
  ASSERT_TRUE(l.ok());
  EXPECT_EQ(l.value().axles.size(), 3u);
  ASSERT_EQ(l.value().skipped.size(), 2u);
  EXPECT_NE(l.value().skipped[0].find("trailer-axle1-left"), std::string::npos) << l.value().skipped[0];
}

TEST(ContactLayout, NamesAVehicleWithoutAxles) {
  const auto p = placements(kMounts);
  const auto l = build_axle_layout(p, Vehicle{});
  ASSERT_FALSE(l.ok());
  EXPECT_EQ(l.error().field, "vehicle");
}

TEST(ContactLayout, RejectsAnUnsprungMassNotBelowTheAxleLoad) {
  Vehicle v = mnroad_vehicle();
  v.axles[1].unsprung_kg = 8000.0;
  const auto p = placements(kMounts);
  const auto l = build_axle_layout(p, v);
  ASSERT_FALSE(l.ok());
  EXPECT_EQ(l.error().field, "vehicle.drive1_unsprung_kg");
}

TEST(ContactLayout, TakesTheRightSideWhenThereIsNoLeftAndIgnoresOtherKinds) {
  const std::vector<SensorPlacement> p = {{0, "gnss", "tractor-front-axle-left"},
                                          {1, "accelerometer", "tractor-front-axle-right"},
                                          {2, "accelerometer", "tractor-front-frame-right"}};
  Vehicle front_only = mnroad_vehicle();
  front_only.axles.resize(1);
  const auto l = build_axle_layout(p, front_only);
  ASSERT_TRUE(l.ok()) << l.error().to_string();
  EXPECT_EQ(l.value().axles[0].axle_sensor, 1);
  EXPECT_EQ(l.value().axles[0].frame_sensor, 2);
}

}  // namespace
}  // namespace roadload
