// What RecordingWriter writes, RecordingReader reads back unchanged (to the written precision);
// an anemometer row leaves the quantities it does not measure empty and they read as NaN.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "roadload/recording/reader.hpp"
#include "roadload/recording/writer.hpp"

namespace roadload::recording {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const char* tag) {
  const fs::path d = fs::temp_directory_path() / ("roadload-writer-" + std::to_string(::getpid()) + "-" + tag);
  fs::remove_all(d);
  return d;
}

TEST(RecordingWriter, WritesWhatTheReaderReadsBack) {
  const fs::path dir = fresh_dir("roundtrip");
  Metadata meta;
  meta.created_by = "test";
  meta.clock_source = "simulated";
  meta.utc_offset_ns = 1413817200000000000;
  meta.vehicle["mass_kg"] = 36152.0;
  meta.can_interfaces = {"can0"};
  auto w = RecordingWriter::create(dir.string(), meta);
  ASSERT_TRUE(w.ok()) << w.error().to_string();

  CanFrame f;
  f.t = capture_time_from_ns(1'234'567'000);
  f.id = 0x0CF00400;
  f.id29 = true;
  f.len = 8;
  f.data = {0xF0, 0x7D, 0x84, 0x4A, 0x14, 0x00, 0xF0, 0x84};
  w.value().write(f, "can0");
  w.value().write(AccelSample{capture_time_from_ns(1'300'000'001), 3, 0.123456, -0.000000004, 9.806650});
  GnssFix g;
  g.t = capture_time_from_ns(1'400'000'000);
  g.utc_ns = 1413817201400000000;
  g.lat_deg = 45.249694123;
  g.lon_deg = -93.686217456;
  g.alt_m = 262.125;
  g.speed_mps = 13.411;
  g.course_deg = 295.25;
  g.mode = GnssFixMode::dgps;
  g.hdop = 0.9;
  w.value().write(g);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  w.value().write(WeatherSample{capture_time_from_ns(2'000'000'000), 101, nan, nan, 3.84, 289.5});
  ASSERT_FALSE(w.value().close().has_value());

  auto r = RecordingReader::open(dir.string());
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  EXPECT_DOUBLE_EQ(r.value().metadata().vehicle.at("mass_kg"), 36152.0);
  const Record* rec = r.value().next();
  ASSERT_NE(rec, nullptr);
  const auto& frame = std::get<CanFrame>(*rec);
  EXPECT_EQ(to_ns(frame.t), 1'234'567'000);
  EXPECT_EQ(frame.id, 0x0CF00400u);
  EXPECT_EQ(frame.data[7], 0x84);
  const auto accel = std::get<AccelSample>(*r.value().next());
  EXPECT_EQ(to_ns(accel.t), 1'300'000'001);
  EXPECT_EQ(accel.sensor, 3);
  EXPECT_DOUBLE_EQ(accel.x_mps2, 0.123456);
  EXPECT_EQ(accel.y_mps2, 0.0);  // -4e-9 is written as 0.000000, never "-0.000000"
  const auto fix = std::get<GnssFix>(*r.value().next());
  EXPECT_DOUBLE_EQ(fix.lat_deg, 45.249694123);
  EXPECT_DOUBLE_EQ(fix.alt_m, 262.125);
  EXPECT_EQ(fix.mode, GnssFixMode::dgps);
  const auto wx = std::get<WeatherSample>(*r.value().next());
  EXPECT_EQ(wx.station, 101);
  EXPECT_TRUE(std::isnan(wx.air_temp_c));
  EXPECT_TRUE(std::isnan(wx.pressure_pa));
  EXPECT_DOUBLE_EQ(wx.wind_speed_mps, 3.84);
  EXPECT_EQ(r.value().next(), nullptr);
  EXPECT_EQ(r.value().errors().count(), 0u);

  std::ifstream in(dir / "accel.csv");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str().find("-0.0"), std::string::npos);
  fs::remove_all(dir);
}

TEST(RecordingWriter, UnwritableFolderIsAnErrorNamingIt) {
  auto w = RecordingWriter::create("/proc/roadload-cannot-write-here", Metadata{});
  ASSERT_FALSE(w.ok());
  EXPECT_NE(w.error().to_string().find("/proc/roadload-cannot-write-here"), std::string::npos);
}

}  // namespace
}  // namespace roadload::recording
