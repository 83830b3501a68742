// The acquisition rings: order, fullness counted as drops, and a producer and a consumer thread
// exchanging a million items without losing, duplicating or reordering one.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <thread>

#include "allocation_counter.hpp"
#include "roadload/firmware/spsc_ring.hpp"

namespace roadload::firmware {
namespace {

TEST(SpscRing, KeepsOrderAndCountsWhatAFullRingRefuses) {
  SpscRing<int, 4> ring;
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(ring.try_push(i));
  EXPECT_FALSE(ring.try_push(99));
  EXPECT_EQ(ring.dropped(), 1u);
  EXPECT_EQ(ring.size(), 4u);
  int v = -1;
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(ring.try_pop(v));
    EXPECT_EQ(v, i);
  }
  EXPECT_FALSE(ring.try_pop(v));
  EXPECT_TRUE(ring.try_push(5));  // the space freed is reused
  ASSERT_TRUE(ring.try_pop(v));
  EXPECT_EQ(v, 5);
}

TEST(SpscRing, TwoThreadsExchangeAMillionItemsInOrder) {
  constexpr std::uint64_t kItems = 1'000'000;
  auto ring = std::make_unique<SpscRing<std::uint64_t, 1024>>();
  std::uint64_t pushed = 0;
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < kItems;) {
      if (ring->try_push(i)) ++i;
    }
    pushed = kItems;
  });
  std::uint64_t expected = 0, out_of_order = 0, v = 0;
  while (expected < kItems) {
    if (!ring->try_pop(v)) continue;
    out_of_order += v != expected ? 1 : 0;
    expected = v + 1;
  }
  producer.join();
  EXPECT_EQ(pushed, kItems);
  EXPECT_EQ(out_of_order, 0u);
  EXPECT_EQ(ring->pushed(), kItems);  // dropped() counts the refused attempts of the spinning producer
}

TEST(SpscRing, PushAndPopDoNotAllocate) {
  auto ring = std::make_unique<SpscRing<double, 256>>();
  std::size_t allocations = 0;
  {
    test::CountAllocations count;
    double v = 0;
    for (int i = 0; i < 10000; ++i) {
      ring->try_push(i);
      ring->try_pop(v);
    }
    allocations = count.count();
  }
  EXPECT_EQ(allocations, 0u);
}

}  // namespace
}  // namespace roadload::firmware
