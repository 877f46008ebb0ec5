#include "surface/surface_fit.h"

#include <gtest/gtest.h>

#include <cmath>

#include "surface/surface_catalogue.h"

namespace glarecam::surface {
namespace {

// A quick sun disc (3 rings, 49 points): the disc blurs lobes of degrees by 0.1 %.
LobeOptions quickSun() {
  LobeOptions o;
  o.disc_rings = 3;
  return o;
}

TEST(SurfaceFit, RecoversTheParametersOfASurfaceFromItsOwnSweep) {
  // The rows the standard surface itself gives, from a start 30 % off: the fit must find it
  // again, each parameter within 1 % (the rows are exact; only the solver's tolerance remains).
  const MicrofacetParameters truth = standardSurface();
  std::vector<SurfaceFitRow> rows;
  for (double alpha : {5.0, 20.0, 40.0, 60.0, 70.0}) {
    const double limit = alpha <= 50 ? 30'000 : alpha <= 60 ? 40'000 : 100'000;
    const SurfacePrediction p = predict(truth, alpha, limit, quickSun());
    rows.push_back({.alpha_deg = alpha,
                    .limit_cd_m2 = limit,
                    .lmax_cd_m2 = p.lmax_cd_m2,
                    .vertical_deg = p.vertical_deg,
                    .horizontal_deg = p.horizontal_deg});
  }
  SurfaceFitOptions options;
  options.start = truth;
  options.start.width_x_deg *= 1.3;
  options.start.width_y_deg *= 0.7;
  options.start.lobe_weight *= 1.3;
  options.lobe = quickSun();
  const auto fit = fitSurface(rows, options);
  ASSERT_TRUE(fit) << fit.error().message;
  EXPECT_NEAR(fit->parameters.width_x_deg, truth.width_x_deg, 0.01 * truth.width_x_deg);
  EXPECT_NEAR(fit->parameters.width_y_deg, truth.width_y_deg, 0.01 * truth.width_y_deg);
  EXPECT_NEAR(fit->parameters.lobe_weight, truth.lobe_weight, 0.01 * truth.lobe_weight);
  EXPECT_LT(fit->cost, 1e-6);
}

TEST(SurfaceFit, TooFewRowsAreRefused) {
  SurfaceFitOptions options;
  SurfaceFitRow row;
  row.alpha_deg = 10;
  row.limit_cd_m2 = 3e4;
  row.lmax_cd_m2 = 5e5;
  const auto fit = fitSurface({row}, options);
  ASSERT_FALSE(fit);
  EXPECT_EQ(fit.error().code, ErrorCode::kBadInput);
}

}  // namespace
}  // namespace glarecam::surface
