// UTC text from ns since 1970, as the status lines and the results' provenance print it.
#include <gtest/gtest.h>

#include "roadload/utc_text.hpp"

namespace roadload {
namespace {

TEST(UtcText, IsoToTheSecond) {
  EXPECT_EQ(utc_text(0), "1970-01-01T00:00:00Z");
  EXPECT_EQ(utc_text(1'413'817'200'000'000'000), "2014-10-20T15:00:00Z");
  // Fractions of a second are dropped, not rounded; 2024 is a leap year.
  EXPECT_EQ(utc_text(1'709'251'199'999'999'999), "2024-02-29T23:59:59Z");
  EXPECT_EQ(utc_text(1'798'761'599'000'000'000), "2026-12-31T23:59:59Z");
}

}  // namespace
}  // namespace roadload
