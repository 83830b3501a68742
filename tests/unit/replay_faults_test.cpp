// The --faults grammar of `roadload replay`: every kind read with its times, and each mistake
// named by its item.
#include <gtest/gtest.h>

#include "roadload/io/replay_faults.hpp"

namespace roadload::io {
namespace {

constexpr Nanoseconds s(double v) { return Nanoseconds{static_cast<std::int64_t>(v * 1e9)}; }

TEST(ReplayFaults, ReadsEveryKind) {
  const auto f = parse_replay_faults(
      "drop=0.01,dup=0.005,seed=9,error@12.5,busoff@30+2,tp-truncate@40,gnss-outage@50+10,accel-overflow@65,clock-step@70=-3.5,"
      "busoff@20+1");
  ASSERT_TRUE(f.ok()) << f.error().to_string();
  const ReplayFaults& v = f.value();
  EXPECT_DOUBLE_EQ(v.drop_fraction, 0.01);
  EXPECT_DOUBLE_EQ(v.duplicate_fraction, 0.005);
  EXPECT_EQ(v.seed, 9u);
  EXPECT_EQ(v.error_frames, std::vector<Nanoseconds>{s(12.5)});
  ASSERT_EQ(v.bus_off.size(), 2u);
  EXPECT_EQ(v.bus_off[0].at, s(20));  // in time order
  EXPECT_EQ(v.bus_off[1].length, s(2));
  EXPECT_EQ(v.tp_truncations, std::vector<Nanoseconds>{s(40)});
  ASSERT_EQ(v.gnss_outages.size(), 1u);
  EXPECT_EQ(v.gnss_outages[0].length, s(10));
  EXPECT_EQ(v.accel_overflows, std::vector<Nanoseconds>{s(65)});
  ASSERT_EQ(v.clock_steps.size(), 1u);
  EXPECT_EQ(v.clock_steps[0].by, s(-3.5));
  EXPECT_FALSE(v.empty());
  EXPECT_TRUE(parse_replay_faults("").value().empty());
}

TEST(ReplayFaults, EachMistakeIsNamedByItsItem) {
  const std::pair<const char*, const char*> cases[] = {
      {"drop=2", "drop=2"},
      {"dup", "dup"},
      {"error@", "error@"},
      {"busoff@30", "busoff@30"},
      {"gnss-outage@5+0", "gnss-outage@5+0"},
      {"clock-step@5", "clock-step@5"},
      {"error@5+1", "error@5+1"},
      {"meteor@5", "meteor@5"},
      {"drop=0.1,,dup=0.1", ""},
      {"seed=1.5", "seed=1.5"},
      {"error@-1", "error@-1"},
  };
  for (const auto& [spec, item] : cases) {
    const auto f = parse_replay_faults(spec);
    ASSERT_FALSE(f.ok()) << spec;
    EXPECT_EQ(f.error().file, "--faults");
    EXPECT_EQ(f.error().field, item) << spec;
    EXPECT_FALSE(f.error().message.empty());
  }
}

}  // namespace
}  // namespace roadload::io
