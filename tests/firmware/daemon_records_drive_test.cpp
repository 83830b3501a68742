// roadloadd's wiring replays a simulated minute of the MnROAD Mainline from memory: the recording
// it writes reads back as the drive itself, stream by stream, and the live filter tracks the truck.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>

#include "drive_fixture.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/recording/writer.hpp"

namespace roadload::firmware::test {
namespace {

// Rows as the recording writes them: the daemon's file must hold exactly these, in this order.
template <typename T>
std::vector<std::string> rows(const std::vector<T>& items) {
  recording::LineBuilder line;
  std::vector<std::string> out;
  for (const T& s : items) out.emplace_back(recording::format_row(s, line));
  return out;
}

// Empty when equal, else the first row that differs, with its neighbours.
std::string first_difference(const std::vector<std::string>& got, const std::vector<std::string>& want) {
  const std::size_t n = std::min(got.size(), want.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (got[i] == want[i]) continue;
    std::string s = "row " + std::to_string(i) + " of " + std::to_string(want.size()) + ":\n";
    for (std::size_t j = i > 2 ? i - 2 : 0; j < std::min(n, i + 3); ++j) s += "  got " + got[j] + "  want " + want[j];
    return s;
  }
  return got.size() == want.size() ? "" : "got " + std::to_string(got.size()) + " rows, want " + std::to_string(want.size());
}

TEST(DaemonRecordsDrive, RecordingReadsBackAsTheDriveAndTheFilterTracksIt) {
  const SimulatedDrive drive(40);
  const std::string dir = temp_dir("roadloadd-drive");
  std::atomic<bool> gate{true};
  const Pace pace = start_pace(drive);
  PaceClock clock(pace);
  Daemon daemon(daemon_setup(drive, dir), memory_sources(drive, pace, gate, 1.0), clock);
  daemon.start();
  wait_for(daemon);
  daemon.stop();
  const StatusReport r = daemon.report();

  std::uint64_t accel_items = 0;
  for (const SourceReport& s : r.sources) {
    if (s.kind == SourceKind::accelerometer) accel_items += s.status.items;
  }
  EXPECT_EQ(r.sources.front().status.items, drive.sink.frames.size());
  EXPECT_EQ(accel_items, drive.sink.accels.size());
  for (const SourceReport& s : r.sources) EXPECT_EQ(s.ring_dropped, 0u) << s.name;
  EXPECT_EQ(r.recording.lines_lost, 0u);
  EXPECT_EQ(r.recording.error, 0);
  EXPECT_EQ(r.recording.lines,
            drive.sink.frames.size() + drive.sink.accels.size() + drive.sink.fixes.size() + drive.sink.weather_samples.size());

  const auto segments = std::vector<std::filesystem::path>(std::filesystem::directory_iterator(dir), {});
  ASSERT_EQ(segments.size(), 1u);
  auto reader = recording::RecordingReader::open(segments[0].string());
  ASSERT_TRUE(reader.ok()) << reader.error().to_string();
  std::vector<CanFrame> frames;
  std::vector<AccelSample> accels;
  std::vector<GnssFix> fixes;
  while (const recording::Record* rec = reader.value().next()) {
    if (const auto* f = std::get_if<CanFrame>(rec)) frames.push_back(*f);
    if (const auto* a = std::get_if<AccelSample>(rec)) accels.push_back(*a);
    if (const auto* g = std::get_if<GnssFix>(rec)) fixes.push_back(*g);
  }
  EXPECT_EQ(reader.value().errors().count(), 0u);
  ASSERT_EQ(frames.size(), drive.sink.frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    ASSERT_EQ(frames[i].id, drive.sink.frames[i].id) << i;
    ASSERT_EQ(frames[i].len, drive.sink.frames[i].len) << i;
    ASSERT_EQ(frames[i].data, drive.sink.frames[i].data) << i;
    // can.log keeps microseconds.
    ASSERT_EQ(to_ns(frames[i].t) / 1000, to_ns(drive.sink.frames[i].t) / 1000) << i;
  }
  // Samples of different parts stamped alike may come in either order; each part's own stay in order.
  auto by_time_then_sensor = [](std::vector<AccelSample> v) {
    std::stable_sort(v.begin(), v.end(),
                     [](const AccelSample& a, const AccelSample& b) { return a.t != b.t ? a.t < b.t : a.sensor < b.sensor; });
    return v;
  };
  for (std::size_t i = 1; i < accels.size(); ++i) {
    ASSERT_LE(accels[i - 1].t, accels[i].t) << "accel.csv row " << i << ": sensor " << int{accels[i - 1].sensor} << " at "
                                            << to_ns(accels[i - 1].t) << " ns, then sensor " << int{accels[i].sensor} << " at "
                                            << to_ns(accels[i].t) << " ns";
  }
  EXPECT_EQ(first_difference(rows(by_time_then_sensor(accels)), rows(by_time_then_sensor(drive.sink.accels))), "");
  EXPECT_EQ(first_difference(rows(fixes), rows(drive.sink.fixes)), "");
  EXPECT_EQ(reader.value().metadata().vehicle, drive.meta.vehicle);

  // The live filter ran on every wheel-speed message and ends at the truck's speed (30 mph).
  ASSERT_TRUE(r.estimate.started);
  EXPECT_NEAR(r.estimate.speed_mps, 13.41, 0.3);
  EXPECT_GT(r.estimate.s_front_m, 450.0);
  EXPECT_LT(r.estimate.crr_lo, r.estimate.crr_hi);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace roadload::firmware::test
