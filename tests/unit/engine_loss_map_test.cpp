// The engine-loss table: linear between calibrated speeds, nothing outside them, speeds in order.
#include <gtest/gtest.h>

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
  EXPECT_DOUBLE_EQ(m.sigma_nm(), 0.9);
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

}  // namespace
}  // namespace roadload::model
