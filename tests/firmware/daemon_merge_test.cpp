// The estimator and the writer take every source's items in capture-time order even when the
// scheduler starves a source thread for longer than the merge delay: they wait until each source
// has delivered what it stamped, so a stalled CAN thread changes nothing the live filter computes
// and a thread late to its first read leaves the recording in order.
#include <gtest/gtest.h>

#include <algorithm>

#include "drive_fixture.hpp"
#include "roadload/recording/reader.hpp"

namespace roadload::firmware::test {
namespace {

// Three of the scenario's eight accelerometers: the merge's order needs several sources, not the
// estimator's full load.
constexpr std::size_t kAccelerometers = 3;

// The daemon's setup with the recording synced once an hour, not each second of the drive (five
// times a wall second at the test's pace): a sync stalled by other tests' disk writes would hold
// the writer, and the replayed sources with it, past the merge's wait. What these tests check is
// the merge's order, not the recording's durability (daemon_records_drive_test).
DaemonSetup merge_setup(const SimulatedDrive& drive, const std::string& dir) {
  DaemonSetup setup = daemon_setup(drive, dir);
  if (setup.recording) setup.recording->fsync_interval = std::chrono::hours(1);
  return setup;
}

// Delivers what `inner` delivers, but once, after `stall_after` items, blocks in read() for
// `stall` of wall time: a thread the scheduler did not run.
template <typename T>
class StallingSource final : public io::Source<T> {
 public:
  StallingSource(std::unique_ptr<io::Source<T>> inner, std::size_t stall_after, std::chrono::milliseconds stall)
      : inner_(std::move(inner)), stall_after_(stall_after), stall_(stall) {}
  std::size_t read(std::span<T> out, Nanoseconds timeout) override {
    if (!stalled_ && inner_->status().items >= stall_after_) {
      stalled_ = true;
      std::this_thread::sleep_for(stall_);
    }
    return inner_->read(out, timeout);
  }
  const io::SourceStatus& status() const override { return inner_->status(); }
  const char* name() const override { return inner_->name(); }

 private:
  std::unique_ptr<io::Source<T>> inner_;
  std::size_t stall_after_;
  std::chrono::milliseconds stall_;
  bool stalled_ = false;
};

// The live estimate once the drive has been replayed, its CAN thread starved for `can_stall` of
// wall time halfway through. The sources hand out the drive `speedup` times faster than real time
// (1e9: unpaced, as fast as they are read) while the daemon's clock keeps the test's pace.
LiveEstimate live_estimate(const SimulatedDrive& drive, std::chrono::milliseconds can_stall, const std::string& name,
                           double speedup = kPace) {
  const std::string dir = temp_dir(name);
  std::atomic<bool> gate{true};
  const Pace pace = start_pace(drive);
  Pace sources_pace = pace;
  sources_pace.speedup = speedup;
  PaceClock clock(pace);
  DaemonSources sources = memory_sources(drive, sources_pace, gate, 1.0);
  const std::size_t half = drive.sink.frames.size() / 2;
  sources.can.front() = std::make_unique<CanChannel>(
      std::make_unique<StallingSource<CanFrame>>(
          std::make_unique<MemorySource<CanFrame>>(drive.sink.frames, gate, drive.sink.frames.size(), "can0", sources_pace), half,
          can_stall),
      SourceKind::can, "can0");
  Daemon daemon(merge_setup(drive, dir), std::move(sources), clock);
  daemon.start();
  wait_for(daemon);
  daemon.stop();
  std::filesystem::remove_all(dir);
  return daemon.report().estimate;
}

TEST(DaemonMerge, AStarvedCanThreadChangesNothingTheFilterComputes) {
  const SimulatedDrive drive(16, kAccelerometers);
  // 120 ms of wall time is 0.6 s of the drive at the test's pace: three of the daemon's merge delays.
  const LiveEstimate steady = live_estimate(drive, std::chrono::milliseconds(0), "roadloadd-merge-steady");
  const LiveEstimate starved = live_estimate(drive, std::chrono::milliseconds(120), "roadloadd-merge-starved");
  ASSERT_TRUE(steady.started);
  EXPECT_GT(steady.s_front_m, 150.0);
  EXPECT_EQ(starved.s_front_m, steady.s_front_m);
  EXPECT_EQ(starved.speed_mps, steady.speed_mps);
  EXPECT_EQ(starved.crr, steady.crr);
  EXPECT_EQ(starved.crr_hi, steady.crr_hi);
}

// Unpaced, as `roadloadd --replay-rate 0` replays: every source hands out its items as fast as it
// reads them, far ahead of the daemon's clock, so the rings fill and the sources wait for room.
// The CAN thread is starved for a fifth of the merge's wait halfway through, long enough for
// every accelerometer's ring to fill meanwhile. Nothing may go out of order: the filter computes
// exactly what the paced replay does, run after run.
TEST(DaemonMerge, AnUnpacedReplayComputesWhatAPacedOneDoes) {
  const SimulatedDrive drive(16);
  const LiveEstimate paced = live_estimate(drive, std::chrono::milliseconds(0), "roadloadd-merge-paced");
  ASSERT_TRUE(paced.started);
  EXPECT_GT(paced.s_front_m, 150.0);
  for (int i = 0; i < 2; ++i) {
    const LiveEstimate unpaced = live_estimate(drive, std::chrono::milliseconds(200), "roadloadd-merge-unpaced", 1e9);
    EXPECT_EQ(unpaced.s_front_m, paced.s_front_m) << "run " << i;
    EXPECT_EQ(unpaced.speed_mps, paced.speed_mps) << "run " << i;
    EXPECT_EQ(unpaced.crr, paced.crr) << "run " << i;
    EXPECT_EQ(unpaced.crr_hi, paced.crr_hi) << "run " << i;
  }
}

// The lowest-numbered sensor's samples (memory_sources() gives it the first channel) from a
// thread that blocks for `stall` of wall time before its first read.
std::unique_ptr<AccelChannel> late_first_sensor(const SimulatedDrive& drive, const Pace& pace, const std::atomic<bool>& gate,
                                                std::chrono::milliseconds stall) {
  std::uint8_t first = 255;
  for (const AccelSample& a : drive.sink.accels) first = std::min(first, a.sensor);
  std::vector<AccelSample> samples;
  for (const AccelSample& a : drive.sink.accels) {
    if (a.sensor == first) samples.push_back(a);
  }
  return std::make_unique<AccelChannel>(
      std::make_unique<StallingSource<AccelSample>>(
          std::make_unique<MemorySource<AccelSample>>(std::move(samples), gate, drive.sink.accels.size(), "accel", pace), 0, stall),
      SourceKind::accelerometer, "accel0");
}

// The drive has run 2 s when the daemon starts, longer than the merge's wait of 1.5 s, and one
// accelerometer's thread then waits 60 ms before its first read: what it has not delivered yet is
// older than everything the other sensors hand over meanwhile, and older than the wait behind the
// daemon's clock. The others' backlog stays under half their rings (3.4 s). The drive runs at
// twice real time here, not five times: the wait is then 0.75 s of wall time for the late thread's
// first read, which a loaded machine's scheduler (two sanitized tests on two cores) may delay well
// past its 60 ms; at five times, 0.3 s was not always enough in CI.
TEST(DaemonMerge, AThreadLateToItsFirstReadLeavesTheRecordingInOrder) {
  const SimulatedDrive drive(12, kAccelerometers);
  const std::string dir = temp_dir("roadloadd-merge-late-start");
  std::atomic<bool> gate{true};
  // The drive's clock starts once the daemon is built, however long that takes under the sanitizers.
  auto drive_clock = std::chrono::steady_clock::now() + std::chrono::hours(1);
  Pace pace = start_pace(drive);
  pace.speedup = 2;
  pace.start_at = &drive_clock;
  PaceClock clock(pace);
  DaemonSources sources = memory_sources(drive, pace, gate, 1.0);
  sources.accel.front() = late_first_sensor(drive, pace, gate, std::chrono::milliseconds(60));
  DaemonSetup setup = merge_setup(drive, dir);
  setup.max_merge_wait = std::chrono::duration_cast<Nanoseconds>(std::chrono::duration<double>(1.5));
  Daemon daemon(std::move(setup), std::move(sources), clock);
  // No thread runs yet: the clock is set before any reads it.
  drive_clock = std::chrono::steady_clock::now() - std::chrono::milliseconds(1000);
  daemon.start();
  wait_for(daemon);
  daemon.stop();

  const auto segments = std::vector<std::filesystem::path>(std::filesystem::directory_iterator(dir), {});
  ASSERT_EQ(segments.size(), 1u);
  auto reader = recording::RecordingReader::open(segments[0].string(), recording::kAccelStream);
  ASSERT_TRUE(reader.ok()) << reader.error().to_string();
  std::size_t rows = 0;
  CaptureTime last{};
  while (const recording::Record* rec = reader.value().next()) {
    const auto* a = std::get_if<AccelSample>(rec);
    if (a == nullptr) continue;
    ASSERT_LE(last, a->t) << "accel.csv row " << rows << ", sensor " << int{a->sensor};
    last = a->t;
    ++rows;
  }
  EXPECT_EQ(rows, drive.sink.accels.size());
  std::filesystem::remove_all(dir);
}

// An accelerometer thread that hangs before its first read for three of the merge's waits: the
// others stop waiting for it after one, so the live filter runs meanwhile, and every row it holds is still recorded when it comes
// back.
TEST(DaemonMerge, AHungSourceHoldsTheOthersBackOnlyForTheWait) {
  const SimulatedDrive drive(16, kAccelerometers);
  const std::string dir = temp_dir("roadloadd-merge-hung");
  std::atomic<bool> gate{true};
  const Pace pace = start_pace(drive);
  PaceClock clock(pace);
  DaemonSources sources = memory_sources(drive, pace, gate, 1.0);
  // The wait is one wall second at the test's pace (daemon_setup()).
  sources.accel.front() = late_first_sensor(drive, pace, gate, std::chrono::milliseconds(3000));
  Daemon daemon(merge_setup(drive, dir), std::move(sources), clock);
  daemon.start();
  std::this_thread::sleep_for(std::chrono::milliseconds(2200));
  const LiveEstimate during = daemon.report().estimate;
  wait_for(daemon);
  daemon.stop();
  // 2.2 s of wall time is 11 s of the drive, 6 s past the wait: 80 m at 30 mph.
  EXPECT_TRUE(during.started);
  EXPECT_GT(during.s_front_m, 40.0);

  EXPECT_EQ(recorded_accel_rows(dir), drive.sink.accels.size());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace roadload::firmware::test
