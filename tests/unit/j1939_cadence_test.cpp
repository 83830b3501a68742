// Gaps and repeats in periodic J1939 messages: a jittery 10 ms stream is clean, each lost frame is
// one gap, each frame sent twice one repeat, transport bursts are not judged, and a real truck's
// idle trace shows none.
#include <gtest/gtest.h>

#include <random>

#include "roadload/j1939/cadence.hpp"
#include "roadload/j1939/id.hpp"
#include "roadload/recording/reader.hpp"

namespace roadload::j1939 {
namespace {

CanFrame frame(double t_s, Pgn pgn, std::uint8_t sa, std::uint8_t counter) {
  CanFrame f;
  f.t = capture_time_from_ns(static_cast<std::int64_t>(t_s * 1e9));
  f.id = make_can_id(3, pgn, kGlobalAddress, sa);
  f.len = 8;
  f.data[0] = counter;
  return f;
}

// EEC1 every 10 ms and CCVS1 every 100 ms, each stamp jittered by up to 1 ms.
std::vector<CanFrame> periodic_traffic(double seconds) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.001, 0.001);
  std::vector<CanFrame> frames;
  for (int k = 0; k * 0.01 < seconds; ++k) {
    frames.push_back(frame(1 + k * 0.01 + jitter(rng), 61444, 0x00, static_cast<std::uint8_t>(k)));
    if (k % 10 == 0) frames.push_back(frame(1 + k * 0.01 + 0.003 + jitter(rng), 65265, 0x00, static_cast<std::uint8_t>(k / 10)));
  }
  return frames;
}

TEST(J1939Cadence, JitteryPeriodicTrafficIsClean) {
  CadenceMonitor m;
  for (const CanFrame& f : periodic_traffic(20)) m.push(f);
  EXPECT_EQ(m.counters().gaps, 0u);
  EXPECT_EQ(m.counters().repeats, 0u);
  EXPECT_EQ(m.counters().untracked, 0u);
}

TEST(J1939Cadence, EachLostFrameIsAGapAndEachDoubledFrameARepeat) {
  std::vector<CanFrame> frames = periodic_traffic(20);
  CadenceMonitor m;
  std::size_t lost = 0, doubled = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i > 200 && i % 97 == 0) {
      ++lost;
      continue;
    }
    m.push(frames[i]);
    // Apart from the losses: a repeat right after a gap looks like a stalled sender catching up.
    if (i > 200 && i % 89 == 0 && i % 97 > 4 && i % 97 < 93) {
      CanFrame again = frames[i];
      again.t += Nanoseconds{50'000};
      m.push(again);
      ++doubled;
    }
  }
  ASSERT_GT(lost, 10u);
  EXPECT_EQ(m.counters().gaps, lost);
  EXPECT_EQ(m.counters().repeats, doubled);
}

// A sender that stalls for 45 ms every second and then sends its backlog at once loses nothing.
TEST(J1939Cadence, AStalledSenderCatchingUpIsNotLoss) {
  std::vector<CanFrame> frames = periodic_traffic(20);
  for (CanFrame& f : frames) {
    const std::int64_t ns = to_ns(f.t);
    const std::int64_t in_second = ns % 1'000'000'000;
    if (in_second > 500'000'000 && in_second < 545'000'000) f.t = capture_time_from_ns(ns - in_second + 545'000'000);
  }
  CadenceMonitor m;
  for (const CanFrame& f : frames) m.push(f);
  EXPECT_EQ(m.counters().gaps, 0u);
  EXPECT_EQ(m.counters().repeats, 0u);
}

// After two seconds at the truck's pace, the rest replayed at full speed: stamps 10 us apart, as
// read, not as sent, with frames missing. Not judged, and counted so.
TEST(J1939Cadence, TrafficFasterThanAnyBusIsNotJudged) {
  std::vector<CanFrame> frames = periodic_traffic(20);
  std::size_t fast = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (frames[i].t < capture_time_from_ns(3'000'000'000)) continue;
    frames[i].t = capture_time_from_ns(3'000'000'000 + static_cast<std::int64_t>(fast++) * 10'000);
  }
  CadenceMonitor m;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i % 50 != 0 || frames[i].t < capture_time_from_ns(3'000'000'000)) m.push(frames[i]);  // 2 % lost
  }
  EXPECT_EQ(m.counters().gaps, 0u);
  EXPECT_EQ(m.counters().repeats, 0u);
  EXPECT_GT(m.counters().too_fast, fast * 9 / 10);
}

TEST(J1939Cadence, TransportBurstsAreNotJudged) {
  CadenceMonitor m;
  for (int k = 0; k < 100; ++k) {
    // A BAM announcement every second, its packets 50 ms apart, then a pause.
    m.push(frame(k, 0xEC00, 0x00, 32));
    for (int p = 1; p <= 3; ++p) m.push(frame(k + 0.05 * p, 0xEB00, 0x00, static_cast<std::uint8_t>(p)));
  }
  EXPECT_EQ(m.counters().gaps, 0u);
  EXPECT_EQ(m.counters().repeats, 0u);
}

TEST(J1939Cadence, ARealTrucksIdleTraceHasNoGapsOrRepeats) {
  auto reader = recording::RecordingReader::open(ROADLOAD_TEST_DATA "/traces/css-truck-idle.log", recording::kCanStream);
  ASSERT_TRUE(reader.ok()) << reader.error().to_string();
  CadenceMonitor m;
  std::size_t frames = 0;
  while (const recording::Record* r = reader.value().next()) {
    if (const auto* f = std::get_if<CanFrame>(r)) {
      m.push(*f);
      ++frames;
    }
  }
  ASSERT_GT(frames, 1000u);
  EXPECT_EQ(m.counters().gaps, 0u) << frames << " frames";
  EXPECT_EQ(m.counters().repeats, 0u);
}

}  // namespace
}  // namespace roadload::j1939
