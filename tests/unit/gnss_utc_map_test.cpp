// UTC on the capture clock from a GNSS receiver (docs/gnss.md). Simulated here: a 10 Hz receiver
// whose fixes reach the daemon 80 ms after their epoch plus 0-150 ms of serial line, gpsd and
// scheduling, and a PPS edge each second stamped with +-2 us of jitter. The fixes alone must place
// UTC within the half-width they claim; PPS to its jitter, and only while edges keep coming.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>

#include "roadload/gnss/utc_map.hpp"

namespace roadload::gnss {
namespace {

constexpr std::int64_t kMs = 1'000'000;
constexpr std::int64_t kOffset = 1'717'254'000'000'000'000 - 3'600'000 * kMs;  // UTC - capture: booted an hour ago

TEST(UtcMap, KnowsNothingBeforeTheFirstFix) {
  const UtcMap map;
  EXPECT_EQ(map.offset().source, UtcSource::none);
  EXPECT_EQ(map.offset().sigma_ns, 0);
}

// The least-delayed fix of the window bounds the offset from below; the receiver's own output delay
// is unknown, so the truth lies anywhere in [bound, bound + max_fix_latency].
TEST(UtcMap, FixTimesPlaceUtcWithinTheLatencyTheyClaim) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::int64_t> jitter(0, 150 * kMs);
  UtcMap map;
  std::int64_t worst = 0;
  for (std::int64_t epoch = 0; epoch < 600'000 * kMs; epoch += 100 * kMs) {  // 10 minutes at 10 Hz
    const CaptureTime read = capture_time_from_ns(epoch + 80 * kMs + jitter(rng));
    map.observe_fix(epoch + kOffset, read);
    const UtcOffset o = map.offset();
    ASSERT_EQ(o.source, UtcSource::fix_time);
    worst = std::max<std::int64_t>(worst, std::llabs(o.utc_minus_capture_ns - kOffset));
  }
  const UtcMapConfig cfg;
  std::printf("fix times: worst offset error %.1f ms, sigma %.1f ms\n", static_cast<double>(worst) / 1e6,
              static_cast<double>(map.offset().sigma_ns) / 1e6);
  EXPECT_LE(worst, cfg.max_fix_latency_ns / 2) << "ns: the truth left the interval the map claims";
  EXPECT_NEAR(static_cast<double>(map.offset().sigma_ns), static_cast<double>(cfg.max_fix_latency_ns) / std::sqrt(12.0), 1.0);
  EXPECT_EQ(map.counters().fixes, 6000u);
}

TEST(UtcMap, PpsGovernsWhileEdgesComeAndFixesTakeOverWhenTheyStop) {
  std::mt19937_64 rng(12);
  std::uniform_int_distribution<std::int64_t> latency(80 * kMs, 230 * kMs), edge_jitter(-2'000, 2'000);
  UtcMap map;
  std::int64_t worst = 0;
  for (std::int64_t epoch = 0; epoch < 120'000 * kMs; epoch += 100 * kMs) {
    if (epoch % (1'000 * kMs) == 0 && epoch < 60'000 * kMs) {  // the antenna loses PPS after a minute
      ASSERT_TRUE(map.observe_pps(epoch + kOffset, capture_time_from_ns(epoch + edge_jitter(rng))));
    }
    map.observe_fix(epoch + kOffset, capture_time_from_ns(epoch + latency(rng)));
    const UtcOffset o = map.offset();
    if (epoch < 60'000 * kMs) {
      ASSERT_EQ(o.source, UtcSource::pps) << "at " << epoch / kMs << " ms";
      worst = std::max<std::int64_t>(worst, std::llabs(o.utc_minus_capture_ns - kOffset));
    } else if (epoch >= 62'500 * kMs) {
      ASSERT_EQ(o.source, UtcSource::fix_time) << "an edge 2.5 s old still governs at " << epoch / kMs << " ms";
    }
  }
  std::printf("PPS: worst offset error %.1f us over 60 edges\n", static_cast<double>(worst) / 1e3);
  EXPECT_LE(worst, 2'000);
  EXPECT_EQ(map.counters().edges, 60u);
}

// gpsd labels an edge with the second of the fix around it; a late or lost fix can name the wrong
// one, a whole second off. The fixes' bound catches that.
TEST(UtcMap, RefusesAnEdgeLabelledWithTheWrongSecond) {
  UtcMap map;
  for (std::int64_t epoch = 0; epoch < 5'000 * kMs; epoch += 100 * kMs)
    map.observe_fix(epoch + kOffset, capture_time_from_ns(epoch + 120 * kMs));
  EXPECT_FALSE(map.observe_pps(5'000 * kMs + kOffset + 1'000 * kMs, capture_time_from_ns(5'000 * kMs)));
  EXPECT_FALSE(map.observe_pps(5'000 * kMs + kOffset - 1'000 * kMs, capture_time_from_ns(5'000 * kMs)));
  EXPECT_EQ(map.counters().edges_refused, 2u);
  EXPECT_EQ(map.offset().source, UtcSource::fix_time);
  EXPECT_TRUE(map.observe_pps(5'000 * kMs + kOffset, capture_time_from_ns(5'000 * kMs)));
  EXPECT_EQ(map.offset().source, UtcSource::pps);
  EXPECT_EQ(map.offset().utc_minus_capture_ns, kOffset);
}

}  // namespace
}  // namespace roadload::gnss
