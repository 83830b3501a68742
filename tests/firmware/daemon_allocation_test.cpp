// Once running, roadloadd's data path allocates nothing: source threads, rings, recorder and the
// live estimator (J1939 decode, CRR filter, spectra) handle a simulated drive with a counter of
// every heap allocation open.
#include <gtest/gtest.h>

#include "allocation_counter.hpp"
#include "drive_fixture.hpp"

namespace roadload::firmware::test {
namespace {

TEST(DaemonAllocation, NoHeapAllocationPerSampleOnceRunning) {
  const SimulatedDrive drive(30);
  const std::string dir = temp_dir("roadloadd-alloc");
  std::atomic<bool> gate{false};
  const Pace pace = start_pace(drive);
  PaceClock clock(pace);
  Daemon daemon(daemon_setup(drive, dir), memory_sources(drive, pace, gate, 0.5), clock);
  daemon.start();
  // The first half (3 s at 5x) settles everything that allocates once: segment files, spectra,
  // the filter.
  std::this_thread::sleep_for(std::chrono::seconds(4));
  std::size_t allocations = 0;
  {
    const roadload::test::CountAllocations count;
    gate = true;
    wait_for(daemon);
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    allocations = count.count();
  }
  daemon.stop();
  const StatusReport r = daemon.report();
  const std::size_t second_half = drive.sink.frames.size() - drive.sink.frames.size() / 2 + drive.sink.accels.size() -
                                  drive.sink.accels.size() / 2;
  EXPECT_GT(second_half, 140'000u);
  EXPECT_EQ(r.recording.lines_lost, 0u);
  for (const SourceReport& s : r.sources) EXPECT_EQ(s.ring_dropped, 0u) << s.name;
  EXPECT_EQ(allocations, 0u) << "over " << second_half << " samples";
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace roadload::firmware::test
