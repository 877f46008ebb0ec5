// glarecam sweep and its fits against the simulator's ground truth, `make demo` in small: the
// simulated rig sweeps α for the standard module, and the sweep's fits must reproduce the
// simulator's module model (capture/sim/module_model.h) within 2 %. Slow under the sanitizers:
// in simulator_truth_tests, not in pipeline_tests (tests/CMakeLists.txt).
#include <gtest/gtest.h>

#include <cmath>

#include "capture/sim/module_model.h"
#include "pipeline/glare_fits.h"
#include "pipeline/sweep.h"
#include "support/sim_support.h"

namespace glarecam::pipeline {
namespace {

// The tolerance on the axes and the luminance. What the pipeline actually reaches here is
// ~0.1 % (sub-pixel contours, fitted peak), so 2 % also leaves room for noise seeds.
constexpr double kTruthTolerance = 0.02;

TEST(SweepTruth, FitsOfASimulatedSweepReproduceTheModuleModel) {
  testing::TempDir dir;
  const std::vector<double> alphas{5, 15, 30, 45, 55, 65, 72, 80};
  unsigned seed = 1;
  for (double alpha : alphas) {
    // 480x400 over 24°: 20 px per degree, a 5° ellipse ~100 px across, as on the rig.
    capture::SimulationOptions options = testing::smallScene(alpha, 480, 400);
    options.horizontal_fov_deg = 24.0;
    options.seed = seed++;
    testing::writeSmallStack(dir / ("stacks/alpha-" + std::to_string(int(alpha))), options);
  }
  SweepOptions options;
  options.output_directory = dir / "sweep";
  options.show_progress = false;
  auto summary = runSweep(findStacks({dir / "stacks"}), options);
  ASSERT_TRUE(summary) << summary.error().message;
  ASSERT_EQ(summary->table.rows.size(), alphas.size());
  auto fits = fitSweep(summary->table);
  ASSERT_TRUE(fits) << fits.error().message;
  ASSERT_TRUE(fits->vertical.logistic && fits->horizontal.logistic);

  auto model = capture::moduleModel("standard");
  ASSERT_TRUE(model);
  // Curves, not parameters: the horizontal logistic is ill-conditioned (docs/method.md), so its
  // parameters are not individually determined, but the curve is. Every degree of the range.
  for (int alpha = 5; alpha <= 80; ++alpha) {
    EXPECT_NEAR(fits->lmaxCdM2(alpha) / model->lmax_cd_m2(alpha), 1.0, kTruthTolerance)
        << "Lmax at " << alpha << "°";
    EXPECT_NEAR(fits->vertical.logistic->curve(alpha) / model->vertical_deg(alpha), 1.0,
                kTruthTolerance)
        << "vertical at " << alpha << "°";
    EXPECT_NEAR(fits->horizontal.logistic->curve(alpha) / model->horizontal_deg(alpha), 1.0,
                kTruthTolerance)
        << "horizontal at " << alpha << "°";
  }
  // The well-conditioned parameters themselves.
  EXPECT_FALSE(fits->cosineIsBetter());  // the truth is biquadratic
  EXPECT_NEAR(fits->biquadratic.curve.c / model->lmax_cd_m2.c, 1.0, kTruthTolerance);
  EXPECT_NEAR(fits->vertical.logistic->curve.b / model->vertical_deg.b, 1.0, kTruthTolerance);
  EXPECT_NEAR(fits->vertical.logistic->curve.c / model->vertical_deg.c, 1.0, kTruthTolerance);
}

}  // namespace
}  // namespace glarecam::pipeline
