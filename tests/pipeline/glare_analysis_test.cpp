// The glare analysis' contour ladder (docs/method.md, "Reference illuminance and the contour
// ladder"): its fixed levels, its rungs ascending with the limit and half-maximum rungs among
// them (those the limit and FWHM ellipses themselves), each rung the ellipse a measurement at its
// level on the whole image gives (the ladder measures on a crop of the image: the same to
// rounding), the scale's uncertainty in the fixed rungs' σ only, and the switch that turns it off.
#include "pipeline/glare_analysis.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "support/sim_support.h"

namespace glarecam::pipeline {
namespace {

TEST(ContourLadder, ThreeLevelsADecadeFromTenThousandToBelowThePeak) {
  EXPECT_EQ(ladderLevelsCdM2(2e6),
            (std::vector<double>{1e4, 2.15e4, 4.64e4, 1e5, 2.15e5, 4.64e5, 1e6}));
  EXPECT_EQ(ladderLevelsCdM2(1e5), (std::vector<double>{1e4, 2.15e4, 4.64e4}));  // not at it
  EXPECT_TRUE(ladderLevelsCdM2(1e4).empty());
  EXPECT_TRUE(ladderLevelsCdM2(std::nan("")).empty());
  EXPECT_EQ(ladderLevelsCdM2(1e300).size(), kMaxLadderRungs);
  for (const double level : {1e4, 2.15e4, 4.64e5, 1e7}) EXPECT_TRUE(isLadderLevel(level)) << level;
  for (const double level : {1e3, 3e4, 2.154e4, 0.0, -1e4}) EXPECT_FALSE(isLadderLevel(level));
  EXPECT_EQ(contourKindFromString("half_maximum"), ContourKind::kHalfMaximum);
  EXPECT_FALSE(contourKindFromString("fwhm"));
}

struct Analysed {
  testing::RenderedScene scene;
  LuminancePeak peak;
  GlareAnalysis analysis;
};

// A lobe of 1e6 cd/m² with its 10 000 cd/m² contour a fifth of the frame across (the ladder's
// crop then a fraction of the image), 1 % pixel noise.
Analysed analyseLobe(const GlareAnalysisOptions& options) {
  testing::SceneSpec spec;
  spec.lobe = testing::lobeAtLimit(100'000, 1e6, 5.0, 6.5, 1000.0);
  spec.relative_noise = 0.01;
  Analysed a{testing::renderScene(spec), {}, {}};
  a.peak = findLuminancePeak(a.scene.merged);
  a.analysis =
      analyseGlare(a.scene.merged, calibration::CameraModel(a.scene.intrinsics), a.peak, options);
  return a;
}

void expectSameEllipse(const GlareEllipse& a, const GlareEllipse& b, const std::string& what) {
  // The crop shifts the pixel coordinates by whole pixels: the rays agree to ~1e-13.
  constexpr double kRelative = 1e-9;
  const auto near = [&](double x, double y, const char* name) {
    EXPECT_NEAR(x, y, kRelative * std::max(1.0, std::abs(y))) << what << ": " << name;
  };
  near(a.vertical_deg, b.vertical_deg, "vertical");
  near(a.horizontal_deg, b.horizontal_deg, "horizontal");
  near(a.orientation_deg, b.orientation_deg, "orientation");
  near(a.solid_angle_sr, b.solid_angle_sr, "solid angle");
  near(a.vertical_uncertainty_deg, b.vertical_uncertainty_deg, "σ vertical");
  near(a.horizontal_uncertainty_deg, b.horizontal_uncertainty_deg, "σ horizontal");
  near(a.solid_angle_uncertainty_sr, b.solid_angle_uncertainty_sr, "σ solid angle");
  near(a.centre_px.x, b.centre_px.x, "centre x");
  near(a.centre_px.y, b.centre_px.y, "centre y");
  EXPECT_EQ(a.regions, b.regions) << what;
  EXPECT_EQ(a.region_pixels, b.region_pixels) << what;
  EXPECT_EQ(a.smoothing_radius_px, b.smoothing_radius_px) << what;
  EXPECT_EQ(a.truncated, b.truncated) << what;
  ASSERT_EQ(a.contour_px.size(), b.contour_px.size()) << what;
  near(a.contour_px.front().x, b.contour_px.front().x, "first contour point");
}

TEST(ContourLadder, RungsAscendAndEachIsTheEllipseMeasuredOnTheWholeImage) {
  // The limit at a ladder level: its rung and the fixed rung at 1e5 are the same contour.
  const Analysed a = analyseLobe({.limit_cd_m2 = 1e5, .thresholds_cd_m2 = {}});
  const std::vector<double> fixed = ladderLevelsCdM2(a.peak.value_cd_m2);
  ASSERT_EQ(a.analysis.ladder.size(), fixed.size() + 2);  // + limit + half maximum
  int limits = 0, halves = 0;
  for (std::size_t i = 0; i < a.analysis.ladder.size(); ++i) {
    const ContourRung& rung = a.analysis.ladder[i];
    if (i > 0) {
      EXPECT_LE(a.analysis.ladder[i - 1].measurement.level_cd_m2, rung.measurement.level_cd_m2);
    }
    // Measured alone on the whole image, the same level gives the same status and ellipse.
    const double u = rung.kind == ContourKind::kHalfMaximum ? a.peak.relative_uncertainty : 0.0;
    const EllipseMeasurement alone =
        measureGlareEllipse(a.scene.merged, calibration::CameraModel(a.scene.intrinsics), a.peak,
                            rung.measurement.level_cd_m2, u);
    EXPECT_EQ(rung.measurement.status, alone.status) << rung.measurement.level_cd_m2;
    if (!rung.measurement.ellipse) {
      // Only the rung just below the peak may be too small to fit.
      EXPECT_GT(rung.measurement.level_cd_m2, a.peak.value_cd_m2 / 2);
      continue;
    }
    ASSERT_TRUE(alone.ellipse);
    expectSameEllipse(*rung.measurement.ellipse, *alone.ellipse,
                      fmt::format("{} at {:g}", toString(rung.kind), rung.measurement.level_cd_m2));
    if (rung.kind == ContourKind::kLimit) {
      ++limits;
      // The limit's rung is the limit ellipse, and the fixed rung at its level (just before it)
      // the same contour.
      expectSameEllipse(*rung.measurement.ellipse, *a.analysis.limit->ellipse, "limit rung");
      ASSERT_GT(i, 0u);
      EXPECT_EQ(a.analysis.ladder[i - 1].kind, ContourKind::kLadder);
      expectSameEllipse(*a.analysis.ladder[i - 1].measurement.ellipse, *a.analysis.limit->ellipse,
                        "fixed rung at the limit");
    }
    if (rung.kind == ContourKind::kHalfMaximum) {
      ++halves;
      expectSameEllipse(*rung.measurement.ellipse, *a.analysis.fwhm.ellipse, "half maximum");
    }
  }
  EXPECT_EQ(limits, 1);
  EXPECT_EQ(halves, 1);
  // Each rung inside the one below it.
  for (std::size_t i = 1; i < a.analysis.ladder.size(); ++i) {
    const auto& upper = a.analysis.ladder[i].measurement.ellipse;
    const auto& lower = a.analysis.ladder[i - 1].measurement.ellipse;
    if (upper && lower) {
      EXPECT_LE(upper->solid_angle_sr, lower->solid_angle_sr * (1 + 1e-9));
    }
  }
}

TEST(ContourLadder, TheScaleUncertaintyWidensTheFixedRungsOnly) {
  const Analysed plain = analyseLobe({.limit_cd_m2 = 3e4, .thresholds_cd_m2 = {}});
  const Analysed scaled =
      analyseLobe({.limit_cd_m2 = 3e4, .thresholds_cd_m2 = {}, .scale_relative_uncertainty = 0.05});
  ASSERT_EQ(plain.analysis.ladder.size(), scaled.analysis.ladder.size());
  for (std::size_t i = 0; i < plain.analysis.ladder.size(); ++i) {
    ASSERT_EQ(plain.analysis.ladder[i].measurement.status,
              scaled.analysis.ladder[i].measurement.status);
    if (!plain.analysis.ladder[i].measurement.ellipse) continue;
    const GlareEllipse& p = *plain.analysis.ladder[i].measurement.ellipse;
    const GlareEllipse& s = *scaled.analysis.ladder[i].measurement.ellipse;
    EXPECT_DOUBLE_EQ(p.vertical_deg, s.vertical_deg);
    if (plain.analysis.ladder[i].kind == ContourKind::kHalfMaximum) {
      EXPECT_DOUBLE_EQ(p.vertical_uncertainty_deg, s.vertical_uncertainty_deg);
    } else {
      EXPECT_GT(s.vertical_uncertainty_deg, 1.5 * p.vertical_uncertainty_deg)
          << plain.analysis.ladder[i].measurement.level_cd_m2;
    }
  }
}

TEST(ContourLadder, OffLeavesTheOtherEllipsesAsTheyAre) {
  const Analysed on = analyseLobe({.limit_cd_m2 = 3e4, .thresholds_cd_m2 = {2e5}});
  const Analysed off =
      analyseLobe({.limit_cd_m2 = 3e4, .thresholds_cd_m2 = {2e5}, .ladder = false});
  EXPECT_TRUE(off.analysis.ladder.empty());
  expectSameEllipse(*on.analysis.limit->ellipse, *off.analysis.limit->ellipse, "limit");
  expectSameEllipse(*on.analysis.fwhm.ellipse, *off.analysis.fwhm.ellipse, "fwhm");
  expectSameEllipse(*on.analysis.thresholds[0].ellipse, *off.analysis.thresholds[0].ellipse,
                    "threshold");
}

TEST(ContourLadder, BelowTenThousandThereIsOnlyTheHalfMaximum) {
  testing::SceneSpec spec;
  spec.lobe = testing::lobeAtLimit(3000, 8000, 5.0, 6.5, 100.0);
  const testing::RenderedScene scene = testing::renderScene(spec);
  const LuminancePeak peak = findLuminancePeak(scene.merged);
  const GlareAnalysis analysis =
      analyseGlare(scene.merged, calibration::CameraModel(scene.intrinsics), peak,
                   {.limit_cd_m2 = 3e4, .thresholds_cd_m2 = {}});
  ASSERT_EQ(analysis.ladder.size(), 2u);
  EXPECT_EQ(analysis.ladder[0].kind, ContourKind::kHalfMaximum);
  EXPECT_EQ(analysis.ladder[1].kind, ContourKind::kLimit);
  EXPECT_EQ(analysis.ladder[1].measurement.status, EllipseStatus::kBelowLevel);
}

}  // namespace
}  // namespace glarecam::pipeline
