// The engine-loss table: linear between calibrated speeds, nothing outside them, speeds in order.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "roadload/model/engine_losses.hpp"

namespace roadload::model {
namespace {

TEST(EngineLossMap, InterpolatesBetweenCalibratedSpeedsAndGuessesNothingOutside) {
  EngineLossMap m;
  EXPECT_FALSE(m.loss_nm(1000).has_value());
  ASSERT_TRUE(m.add({1000, 200, 0.8}));
  ASSERT_TRUE(m.add({1100, 210, 0.9}));
  ASSERT_TRUE(m.add({1300, 250, 0.7}));
  EXPECT_DOUBLE_EQ(*m.loss_nm(1000), 200);
  EXPECT_DOUBLE_EQ(*m.loss_nm(1050), 205);
  EXPECT_DOUBLE_EQ(*m.loss_nm(1150), 220);
  EXPECT_DOUBLE_EQ(*m.loss_nm(1300), 250);
  EXPECT_FALSE(m.loss_nm(999.9).has_value());
  EXPECT_FALSE(m.loss_nm(1300.1).has_value());
}

TEST(EngineLossMap, RefusesSpeedsOutOfOrderAndBeyondItsCapacity) {
  EngineLossMap m;
  ASSERT_TRUE(m.add({1000, 200, 1}));
  EXPECT_FALSE(m.add({1000, 201, 1}));
  EXPECT_FALSE(m.add({900, 190, 1}));
  EXPECT_EQ(m.size(), 1u);
  for (std::size_t i = 1; i < EngineLossMap::kCapacity; ++i) ASSERT_TRUE(m.add({1000.0 + 10.0 * static_cast<double>(i), 200, 1}));
  EXPECT_FALSE(m.add({5000, 300, 1}));
  EXPECT_EQ(m.size(), EngineLossMap::kCapacity);
}

TEST(EngineLossMap, FrictionInterpolatesLikeTheLossAndIsAbsentWhereAPointHasNone) {
  EngineLossMap m;
  ASSERT_TRUE(m.add({1000, 200, 0.8, 150}));
  ASSERT_TRUE(m.add({1100, 210, 0.9, 160}));
  ASSERT_TRUE(m.add({1200, 220, 0.9}));
  EXPECT_DOUBLE_EQ(*m.friction_nm(1050), 155);
  EXPECT_FALSE(m.friction_nm(1150).has_value());
  EXPECT_FALSE(m.friction_nm(999).has_value());
  EXPECT_DOUBLE_EQ(*m.loss_nm(1150), 215);
  EXPECT_DOUBLE_EQ(*m.shifted(1.0, 0.1).friction_nm(1050), 155);
}

TEST(EngineLossMap, OneSpeedIsThatSpeedOnly) {
  EngineLossMap m;
  ASSERT_TRUE(m.add({1200, 224, 0.9}));
  EXPECT_DOUBLE_EQ(*m.loss_nm(1200), 224);
  EXPECT_FALSE(m.loss_nm(1201).has_value());
}

// Each point's error is its own hold's rounding: drawn independently here, the map's error at
// engine speeds spread evenly over its range has the RMS sigma_nm() states, below the largest
// point sigma because interpolation between two points averages their errors.
TEST(EngineLossMap, ItsSigmaIsTheRmsOfTheInterpolatedErrorOverItsRange) {
  const EngineLossPoint points[] = {{1000, 200, 0.8}, {1100, 210, 0.9}, {1300, 250, 0.7}};
  EngineLossMap exact;
  for (const EngineLossPoint& p : points) ASSERT_TRUE(exact.add(p));
  EXPECT_NEAR(exact.sigma_nm(), std::sqrt((100 * (0.64 + 0.81) + 200 * (0.81 + 0.49)) / 3.0 / 300.0), 1e-12);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> unit;
  std::uniform_real_distribution<double> rpm(1000, 1300);
  double sum = 0;
  constexpr int kMaps = 20000, kSpeeds = 10;
  for (int i = 0; i < kMaps; ++i) {
    EngineLossMap drawn;
    for (const EngineLossPoint& p : points) ASSERT_TRUE(drawn.add({p.rpm, p.loss_nm + p.sigma_nm * unit(rng), p.sigma_nm}));
    for (int k = 0; k < kSpeeds; ++k) {
      const double r = rpm(rng);
      const double e = *drawn.loss_nm(r) - *exact.loss_nm(r);
      sum += e * e;
    }
  }
  EXPECT_NEAR(std::sqrt(sum / (kMaps * kSpeeds)), exact.sigma_nm(), 0.01 * exact.sigma_nm());
  EXPECT_LT(exact.sigma_nm(), 0.9);
  EngineLossMap one;
  ASSERT_TRUE(one.add({1000, 200, 0.8}));
  EXPECT_DOUBLE_EQ(one.sigma_nm(), 0.8);
  EXPECT_DOUBLE_EQ(EngineLossMap{}.sigma_nm(), 0.0);
}

}  // namespace
}  // namespace roadload::model
