// Simulated stacks: deterministic for a seed, following the module and the limit curve, refusing
// angles outside the method.
#include "capture/sim/simulated_stack.h"

#include <gtest/gtest.h>

#include <cmath>

#include "capture/sim/module_model.h"
#include "pipeline/limit_curve.h"
#include "support/sim_support.h"

namespace glarecam::capture {
namespace {

TEST(SimulatedStack, IsDeterministicForASeedAndDiffersAcrossSeeds) {
  auto a = simulateStack(testing::smallScene(40.0, 64, 48));
  auto b = simulateStack(testing::smallScene(40.0, 64, 48));
  SimulationOptions other = testing::smallScene(40.0, 64, 48);
  other.seed = 2;
  auto c = simulateStack(other);
  ASSERT_TRUE(a && b && c);
  ASSERT_EQ(a->frames.size(), b->frames.size());
  std::size_t differing = 0;
  for (std::size_t f = 0; f < a->frames.size(); ++f) {
    for (std::size_t i = 0; i < a->frames[f].pixelCount(); ++i) {
      ASSERT_EQ(a->frames[f].data()[i], b->frames[f].data()[i]);
      differing += a->frames[f].data()[i] != c->frames[f].data()[i];
    }
  }
  EXPECT_GT(differing, 100u);
  EXPECT_EQ(a->truthJson(), b->truthJson());
}

TEST(SimulatedStack, FollowsTheModuleAndTheLimitCurve) {
  auto stack = simulateStack(testing::smallScene(70.0));
  ASSERT_TRUE(stack);
  auto module = moduleModel("standard");
  EXPECT_DOUBLE_EQ(stack->truth.peak_cd_m2, module->lmax_cd_m2(70.0));
  EXPECT_DOUBLE_EQ(stack->truth.limit_cd_m2, *pipeline::glareLimitCdM2(70.0));
  ASSERT_TRUE(stack->truth.limit_axes);
  EXPECT_NEAR(stack->truth.limit_axes->vertical_deg, module->vertical_deg(70.0), 1e-9);
  EXPECT_NEAR(stack->truth.limit_axes->horizontal_deg, module->horizontal_deg(70.0), 1e-9);
  // 12-bit raw values, six or more frames, the brightest pixel unsaturated in the shortest.
  EXPECT_GE(stack->frames.size(), 6u);
  std::uint16_t brightest = 0;
  for (std::size_t i = 0; i < stack->frames[0].pixelCount(); ++i)
    brightest = std::max(brightest, stack->frames[0].data()[i]);
  EXPECT_LT(brightest, stack->manifest.calibration->saturation_dn);
  for (const auto& frame : stack->frames) {
    for (std::size_t i = 0; i < frame.pixelCount(); ++i) ASSERT_LE(frame.data()[i], 4095);
  }
}

TEST(SimulatedStack, RefusesAnglesOutsideTheMethod) {
  SimulationOptions options = testing::smallScene(85.0);
  auto stack = simulateStack(options);
  ASSERT_FALSE(stack);
  EXPECT_EQ(stack.error().code, ErrorCode::kBadInput);
}

}  // namespace
}  // namespace glarecam::capture
