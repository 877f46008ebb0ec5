#include "pipeline/limit_curve.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glarecam::pipeline {
namespace {

TEST(LimitCurve, MatchesTheMethodsTablePoints) {
  EXPECT_EQ(glareLimitCdM2(0.0), 30'000.0);
  EXPECT_EQ(glareLimitCdM2(35.0), 30'000.0);
  EXPECT_EQ(glareLimitCdM2(50.0), 30'000.0);
  EXPECT_NEAR(*glareLimitCdM2(60.0), 40'000.0, 1e-6);
  EXPECT_NEAR(*glareLimitCdM2(70.0), 100'000.0, 1e-6);
  EXPECT_NEAR(*glareLimitCdM2(80.0), 400'000.0, 1e-6);
}

TEST(LimitCurve, InterpolatesLogLinearly) {
  // Halfway between 70° and 80° is the geometric mean of 100 000 and 400 000.
  EXPECT_NEAR(*glareLimitCdM2(75.0), 200'000.0, 1e-6);
  EXPECT_NEAR(*glareLimitCdM2(55.0), std::sqrt(30'000.0 * 40'000.0), 1e-6);
  EXPECT_NEAR(*glareLimitCdM2(65.0), std::sqrt(40'000.0 * 100'000.0), 1e-6);
}

TEST(LimitCurve, IsUndefinedOutsideTheMethodsRange) {
  EXPECT_FALSE(glareLimitCdM2(80.01));
  EXPECT_FALSE(glareLimitCdM2(89.0));
  EXPECT_FALSE(glareLimitCdM2(-1.0));
  EXPECT_FALSE(glareLimitCdM2(std::nan("")));
}

}  // namespace
}  // namespace glarecam::pipeline
