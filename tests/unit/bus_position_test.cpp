// Position from the truck's bus: VP1's latitude and longitude, VDS's altitude when fresh, through
// the built-in definitions.
#include "roadload/bus_position.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>

#include "roadload/definitions.hpp"

namespace roadload {
namespace {

// The message points into `data`, which the caller keeps.
j1939::Message message(j1939::Pgn pgn, std::int64_t t_ms, const std::array<std::uint8_t, 8>& data) {
  j1939::Message m;
  m.t = capture_time_from_ns(t_ms * 1'000'000);
  m.pgn = pgn;
  m.data = data;
  return m;
}

std::array<std::uint8_t, 8> vp1(double lat, double lon) {
  std::array<std::uint8_t, 8> d{};
  const auto la = static_cast<std::uint32_t>(std::llround((lat + 210) / 1e-7));
  const auto lo = static_cast<std::uint32_t>(std::llround((lon + 210) / 1e-7));
  for (int i = 0; i < 4; ++i) {
    d[i] = static_cast<std::uint8_t>(la >> (8 * i));
    d[4 + i] = static_cast<std::uint8_t>(lo >> (8 * i));
  }
  return d;
}

std::array<std::uint8_t, 8> vds(double altitude_m) {
  std::array<std::uint8_t, 8> d{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0, 0};
  const auto a = static_cast<std::uint16_t>(std::lround((altitude_m + 2500) / 0.125));
  d[6] = static_cast<std::uint8_t>(a & 0xFF);
  d[7] = static_cast<std::uint8_t>(a >> 8);
  return d;
}

class BusPositionTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_FALSE(load_dbc_file(db_, core_dbc_path())); }
  j1939::Database db_;
};

TEST_F(BusPositionTest, Vp1AloneIsATwoDimensionalFix) {
  BusPosition bus(db_);
  const auto data = vp1(45.1234567, -93.7654321);
  const auto f = bus.push(message(65267, 1000, data));
  ASSERT_TRUE(f);
  EXPECT_NEAR(f->lat_deg, 45.1234567, 1e-7);
  EXPECT_NEAR(f->lon_deg, -93.7654321, 1e-7);
  EXPECT_EQ(f->mode, GnssFixMode::fix_2d);
  EXPECT_TRUE(std::isnan(f->alt_m));
}

TEST_F(BusPositionTest, AFreshAltitudeMakesItThreeDimensional) {
  BusPosition bus(db_);
  const auto alt = vds(281.375);
  EXPECT_FALSE(bus.push(message(65256, 1000, alt)));
  const auto pos = vp1(45.0, -93.0);
  const auto f = bus.push(message(65267, 1200, pos));
  ASSERT_TRUE(f);
  EXPECT_EQ(f->mode, GnssFixMode::fix_3d);
  EXPECT_DOUBLE_EQ(f->alt_m, 281.375);
  const auto stale = bus.push(message(65267, 4000, pos));  // the altitude is 3 s old
  ASSERT_TRUE(stale);
  EXPECT_EQ(stale->mode, GnssFixMode::fix_2d);
}

TEST_F(BusPositionTest, NoPlaceOnEarthIsNoFix) {
  BusPosition bus(db_);
  const auto beyond = vp1(100.0, 0.0);  // in the DBC's range, not on Earth
  EXPECT_FALSE(bus.push(message(65267, 0, beyond)));
  const std::array<std::uint8_t, 8> missing{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
  EXPECT_FALSE(bus.push(message(65267, 0, missing)));
}

}  // namespace
}  // namespace roadload
