// roadloadd's settings: the shipped config/roadloadd.toml states the built-in defaults, bad values
// are refused with the file, line and key, and the command line overrides the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "roadload/firmware/command_line.hpp"
#include "roadload/firmware/config.hpp"
#include "scratch.hpp"

namespace roadload::firmware {
namespace {

std::string body(const DaemonConfig& c) {
  const std::string text = format_config(c);
  return text.substr(text.find('\n') + 1);  // without the "settings from" line
}

std::string write_temp(const std::string& text) {
  const auto path = test::scratch_path("roadloadd-config", ".toml");
  std::ofstream(path) << text;
  return path.string();
}

TEST(DaemonConfig, ShippedFileStatesTheBuiltInDefaults) {
  auto c = load_config(std::string(ROADLOAD_CONFIG_DIR "/roadloadd.toml"));
  ASSERT_TRUE(c.ok()) << c.error().to_string();
  EXPECT_EQ(body(c.value()), body(DaemonConfig{}));
}

TEST(DaemonConfig, UnknownKeyIsRefusedWithItsLine) {
  auto c = load_config(write_temp("[recording]\nfsync_interval_s = 2\nfsync_intervall_s = 3\n"));
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.error().line, 3);
  EXPECT_EQ(c.error().field, "recording.fsync_intervall_s");
}

TEST(DaemonConfig, OutOfRangeValueNamesTheField) {
  auto c = load_config(write_temp("[[can]]\ninterface = \"can0\"\n[[can]]\ninterface = \"can0\"\n"));
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.error().field, "can[1].interface");
  auto q = load_config(write_temp("[recording]\nsegment_max_mib = 100\nquota_mib = 150\n"));
  ASSERT_FALSE(q.ok());
  EXPECT_EQ(q.error().field, "recording.quota_mib");
}

TEST(DaemonConfig, CompressionLevelIsAWholeNumberUpTo19) {
  auto plain = load_config(write_temp("[recording]\ncompression_level = 0\n"));
  ASSERT_TRUE(plain.ok()) << plain.error().to_string();
  EXPECT_EQ(plain.value().recording.compression_level, 0);
  for (const char* text :
       {"[recording]\ncompression_level = 20\n", "[recording]\ncompression_level = 2.5\n", "[recording]\ncompression_level = -1\n"}) {
    auto c = load_config(write_temp(text));
    ASSERT_FALSE(c.ok()) << text;
    EXPECT_EQ(c.error().field, "recording.compression_level") << c.error().to_string();
  }
}

TEST(DaemonConfig, TheTrucksCalibrationIsReadAndCheckedForRange) {
  auto c = load_config(
      write_temp("[estimator]\nengine_losses = \"/etc/roadload/losses.csv\"\ncda_m2 = 6.22\ncda_sigma_m2 = 0.03\n"
                 "cda_torque_correlation = -0.64\n"));
  ASSERT_TRUE(c.ok()) << c.error().to_string();
  EXPECT_EQ(c.value().estimator.engine_losses, "/etc/roadload/losses.csv");
  EXPECT_DOUBLE_EQ(c.value().estimator.cda_m2, 6.22);
  EXPECT_DOUBLE_EQ(c.value().estimator.cda_sigma_m2, 0.03);
  EXPECT_DOUBLE_EQ(c.value().estimator.cda_torque_correlation, -0.64);
  auto beyond = load_config(write_temp("[estimator]\ncda_torque_correlation = 1.5\n"));
  ASSERT_FALSE(beyond.ok());
  EXPECT_EQ(beyond.error().field, "estimator.cda_torque_correlation");
  auto bad = load_config(write_temp("[estimator]\ncda_m2 = 62\n"));
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().field, "estimator.cda_m2");
}

TEST(DaemonConfig, CommandLineOverridesTheFile) {
  const std::string file = write_temp("[[can]]\ninterface = \"can1\"\n[recording]\ndata_dir = \"/data\"\n");
  auto cl = parse_command_line({"--data-dir", "/tmp/x", "--config", file, "--can", "vcan0", "--can", "vcan1"});
  ASSERT_TRUE(cl.ok()) << cl.error().to_string();
  const DaemonConfig& c = cl.value().config;
  ASSERT_EQ(c.can.size(), 2u);
  EXPECT_EQ(c.can[0].interface, "vcan0");
  EXPECT_EQ(c.can[1].interface, "vcan1");
  EXPECT_EQ(c.recording.data_dir, "/tmp/x");
  EXPECT_EQ(c.source, file);
}

TEST(DaemonConfig, CommandLineErrorsNameTheOption) {
  auto bad = parse_command_line({"--replay-rate", "fast"});
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().field, "--replay-rate");
  auto unknown = parse_command_line({"--cann", "vcan0"});
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().field, "--cann");
  auto needs = parse_command_line({"--replay-can"});
  ASSERT_FALSE(needs.ok());
  EXPECT_EQ(needs.error().field, "replay.can");
  // The next option is not an option's value.
  auto swallowed = parse_command_line({"--can", "--no-gnss"});
  ASSERT_FALSE(swallowed.ok());
  EXPECT_EQ(swallowed.error().field, "--can");
}

TEST(DaemonConfig, SizesThatWouldOverflowAreRefused) {
  for (const char* text : {"[recording]\nsegment_max_mib = inf\nquota_mib = inf\n", "[recording]\nquota_mib = 1e300\n",
                           "[recording]\nsegment_max_mib = nan\n"}) {
    auto c = load_config(write_temp(text));
    ASSERT_FALSE(c.ok()) << text;
    EXPECT_TRUE(c.error().field == "recording.segment_max_mib" || c.error().field == "recording.quota_mib") << c.error().to_string();
  }
}

// Replay needs a recording folder; a can.log alone has CAN and nothing else to replay.
TEST(DaemonConfig, ReplayOfSomethingThatIsNoRecordingIsRefused) {
  auto missing = parse_command_line({"--replay", "/nonexistent/recording"});
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().field, "replay.recording");
  const std::string file = write_temp("(1.000000) can0 18FEF100#0011223344556677\n");
  auto plain = parse_command_line({"--replay", file});
  ASSERT_FALSE(plain.ok());
  EXPECT_NE(plain.error().message.find("--replay-can"), std::string::npos) << plain.error().to_string();
  EXPECT_TRUE(parse_command_line({"--replay", file, "--replay-can"}).ok());
}

}  // namespace
}  // namespace roadload::firmware
