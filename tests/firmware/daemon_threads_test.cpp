// roadloadd's threads as an operator sees them in `top -H`: named by role, and one thread for all
// the accelerometers however many there are, which loses none of their samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <string>

#include "drive_fixture.hpp"

namespace roadload::firmware::test {
namespace {

// How many of this process's threads carry each name.
std::map<std::string, int> thread_names() {
  std::map<std::string, int> names;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
    std::ifstream in(task.path() / "comm");
    std::string name;
    if (std::getline(in, name)) ++names[name];
  }
  return names;
}

TEST(DaemonThreads, NamedByRoleWithOneThreadReadingEveryAccelerometerInFull) {
  const SimulatedDrive drive(4, 8);
  const std::string dir = temp_dir("roadloadd-threads");
  std::atomic<bool> gate{true};
  const Pace pace = start_pace(drive);
  PaceClock clock(pace);
  Daemon daemon(daemon_setup(drive, dir), memory_sources(drive, pace, gate, 1.0, StampSource::kernel), clock);
  daemon.start();
  // Each thread names itself once it runs.
  const std::array<const char*, 6> roles = {"rl-accel", "rl-can0", "rl-gnss", "rl-weather", "rl-writer", "rl-estimator"};
  std::map<std::string, int> names;
  for (int i = 0; i < 100 && !std::all_of(roles.begin(), roles.end(), [&](const char* r) { return names.contains(r); }); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    names = thread_names();
  }
  wait_for(daemon);
  // The accelerometers are devices, not replays: their last samples come due with the drive's end.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  daemon.stop();
  for (const char* role : roles) {
    EXPECT_EQ(names.contains(role) ? names.at(role) : 0, 1) << role;
  }
  const StatusReport r = daemon.report();
  EXPECT_EQ(r.recording.lines_lost, 0u);
  std::uint64_t samples = 0;
  for (const SourceReport& s : r.sources) {
    EXPECT_EQ(s.ring_dropped, 0u) << s.name;
    if (s.kind == SourceKind::accelerometer) samples += s.status.items;
  }
  EXPECT_EQ(samples, drive.sink.accels.size());
  EXPECT_EQ(recorded_accel_rows(dir), drive.sink.accels.size());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace roadload::firmware::test
