// The timeline `roadload replay --origin` hands to roadloadd: written and read back exactly, and a
// capture time mapped back onto the recording's timeline where it came from.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "roadload/io/replay_origin.hpp"
#include "scratch.hpp"

namespace roadload::io {
namespace {

std::string temp_path(const char* name) { return test::scratch_path(name, ".toml").string(); }

TEST(ReplayOrigin, WrittenAndReadBackExactly) {
  const ReplayTiming t{capture_time_from_ns(1'413'817'200'123'456'789), capture_time_from_ns(987'654'321'012), 20};
  const std::string path = temp_path("origin");
  ASSERT_FALSE(write_replay_origin(path, {t, {}}).has_value());
  auto back = read_replay_origin(path);
  ASSERT_TRUE(back.ok()) << back.error().to_string();
  EXPECT_EQ(back.value().timing.recorded_origin, t.recorded_origin);
  EXPECT_EQ(back.value().timing.capture_origin, t.capture_origin);
  EXPECT_EQ(back.value().timing.rate, 20);
  EXPECT_TRUE(back.value().faults.empty());
}

TEST(ReplayOrigin, CarriesTheFaultsToTheDaemon) {
  const ReplayTiming t{capture_time_from_ns(1), capture_time_from_ns(2), 5};
  auto faults = parse_replay_faults("gnss-outage@30+10,accel-overflow@45,drop=0.01");
  ASSERT_TRUE(faults.ok()) << faults.error().to_string();
  const std::string path = temp_path("origin-faults");
  ASSERT_FALSE(write_replay_origin(path, {t, faults.value()}).has_value());
  auto back = read_replay_origin(path);
  ASSERT_TRUE(back.ok()) << back.error().to_string();
  ASSERT_EQ(back.value().faults.gnss_outages.size(), 1u);
  EXPECT_EQ(back.value().faults.gnss_outages[0].at, Nanoseconds{30'000'000'000});
  EXPECT_EQ(back.value().faults.gnss_outages[0].length, Nanoseconds{10'000'000'000});
  ASSERT_EQ(back.value().faults.accel_overflows.size(), 1u);
  EXPECT_DOUBLE_EQ(back.value().faults.drop_fraction, 0.01);
}

TEST(ReplayOrigin, BadFaultsInTheFileAreNamed) {
  const std::string path = temp_path("origin-badfaults");
  std::ofstream(path) << "recorded_origin_ns = 1\ncapture_origin_ns = 2\nrate = 1\nfaults = \"gnss-outage@x\"\n";
  auto r = read_replay_origin(path);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().field, "faults");
  EXPECT_NE(r.error().message.find("gnss-outage@x"), std::string::npos) << r.error().message;
}

TEST(ReplayOrigin, MalformedFileNamesTheKey) {
  const std::string path = temp_path("origin-bad");
  std::ofstream(path) << "recorded_origin_ns = 1.5\ncapture_origin_ns = 2\nrate = 1\n";
  auto r = read_replay_origin(path);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().field, "recorded_origin_ns");
  EXPECT_EQ(r.error().line, 1);
}

TEST(ReplayTiming, CaptureTimeMapsBackOntoTheRecording) {
  const ReplayTiming t{capture_time_from_ns(5'000'000'000), capture_time_from_ns(77'000'000'000), 20};
  for (std::int64_t ms : {0, 1, 250, 3'600'000}) {
    const CaptureTime recorded = t.recorded_origin + Nanoseconds{ms * 1'000'000};
    EXPECT_NEAR(static_cast<double>(to_ns(t.recorded(t.capture(recorded)))), static_cast<double>(to_ns(recorded)), 20.0) << ms;
  }
  EXPECT_EQ(to_ns(t.capture(t.recorded_origin + Nanoseconds{20'000'000'000})), 78'000'000'000);
}

}  // namespace
}  // namespace roadload::io
