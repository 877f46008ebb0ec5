#include "pipeline/glare_ellipse.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>

#include "core/angles.h"
#include "pipeline/glare_analysis.h"
#include "support/sim_support.h"

namespace glarecam::pipeline {
namespace {

using testing::lobeAtLimit;
using testing::renderScene;
using testing::SceneSpec;

struct Measured {
  LuminancePeak peak;
  GlareAnalysis analysis;
  testing::RenderedScene scene;
};

Measured analyse(const SceneSpec& spec) {
  Measured m;
  m.scene = renderScene(spec);
  m.peak = findLuminancePeak(m.scene.merged);
  m.analysis = analyseGlare(m.scene.merged, calibration::CameraModel(m.scene.intrinsics), m.peak,
                            {.limit_cd_m2 = spec.limit_cd_m2, .thresholds_cd_m2 = {}});
  return m;
}

void expectAxes(const std::optional<GlareEllipse>& measured,
                const std::optional<capture::EllipseAxes>& truth, double tolerance,
                const char* what) {
  ASSERT_TRUE(truth.has_value()) << what;
  ASSERT_TRUE(measured.has_value()) << what;
  EXPECT_NEAR(measured->vertical_deg / truth->vertical_deg, 1.0, tolerance)
      << what << ": vertical " << measured->vertical_deg << " vs " << truth->vertical_deg;
  EXPECT_NEAR(measured->horizontal_deg / truth->horizontal_deg, 1.0, tolerance)
      << what << ": horizontal " << measured->horizontal_deg << " vs " << truth->horizontal_deg;
}

// Accuracy of the full analysis against the scene's analytic truth. The tolerances:
// axes within 1 % (2 % far off-axis under strong distortion and for a tiny lobe's FWHM), the
// maximum within 1 % (2 % for the tiny lobe).
constexpr double kAxisTolerance = 0.01;
constexpr double kHardAxisTolerance = 0.02;
constexpr double kPeakTolerance = 0.01;
constexpr double kTinyPeakTolerance = 0.02;

TEST(GlareEllipse, CentredLobeMatchesTruth) {
  SceneSpec spec;
  spec.lobe = lobeAtLimit(30'000, 594'000, 5.0, 5.7);  // Table III at 5°
  const Measured m = analyse(spec);
  EXPECT_NEAR(m.peak.value_cd_m2 / m.scene.truth.peak_cd_m2, 1.0, kPeakTolerance);
  ASSERT_TRUE(m.analysis.limit.has_value());
  expectAxes(m.analysis.limit->ellipse, m.scene.truth.limit_axes, kAxisTolerance, "limit");
  expectAxes(m.analysis.fwhm.ellipse, m.scene.truth.fwhm_axes, kAxisTolerance, "fwhm");
  const GlareEllipse& e = *m.analysis.limit->ellipse;
  EXPECT_EQ(e.regions, 1);
  EXPECT_TRUE(e.ellipticity_ok);
  EXPECT_FALSE(e.truncated);
  EXPECT_NEAR(e.centre_px.x, m.scene.centre_px.x, 0.05);
  EXPECT_NEAR(e.centre_px.y, m.scene.centre_px.y, 0.05);
  EXPECT_NEAR(e.centre_direction.horizontal_deg, 0.0, 0.01);
  // Horizontal is the major axis here: orientation near 0.
  EXPECT_NEAR(e.orientation_deg, 0.0, 1.0);
  EXPECT_DOUBLE_EQ(e.major_deg, e.horizontal_deg);
  // Solid angle of a small ellipse: pi a b (in radians) to well under 1 %.
  const double a = radians(e.major_deg / 2), b = radians(e.minor_deg / 2);
  EXPECT_NEAR(e.solid_angle_sr / (M_PI * a * b), 1.0, 0.005);
}

TEST(GlareEllipse, BelowLimitHasOnlyFwhm) {
  SceneSpec spec;
  spec.lobe = lobeAtLimit(30'000, 594'000, 5.0, 5.7);
  spec.lobe.peak_cd_m2 = 25'000;
  const Measured m = analyse(spec);
  ASSERT_TRUE(m.analysis.limit.has_value());
  EXPECT_EQ(m.analysis.limit->status, EllipseStatus::kBelowLevel);
  EXPECT_FALSE(m.analysis.limit->ellipse.has_value());
  EXPECT_NEAR(m.peak.value_cd_m2 / m.scene.truth.peak_cd_m2, 1.0, kPeakTolerance);
  expectAxes(m.analysis.fwhm.ellipse, m.scene.truth.fwhm_axes, kAxisTolerance, "fwhm-below");
}

TEST(GlareEllipse, RotatedOffCentreLobeAtHighAlpha) {
  SceneSpec spec;
  spec.limit_cd_m2 = 100'000;  // alpha 70
  spec.lobe = lobeAtLimit(100'000, 11.9e6, 8.2, 3.6);
  spec.lobe.orientation_deg = 15;
  spec.lobe.centre_direction_deg = {11.0, -7.0};
  const Measured m = analyse(spec);
  EXPECT_NEAR(m.peak.value_cd_m2 / m.scene.truth.peak_cd_m2, 1.0, kPeakTolerance);
  ASSERT_TRUE(m.analysis.limit.has_value());
  expectAxes(m.analysis.limit->ellipse, m.scene.truth.limit_axes, kAxisTolerance, "limit-rot");
  expectAxes(m.analysis.fwhm.ellipse, m.scene.truth.fwhm_axes, kAxisTolerance, "fwhm-rot");
  const GlareEllipse& e = *m.analysis.limit->ellipse;
  EXPECT_NEAR(e.orientation_deg, -75.0, 0.5);
  EXPECT_NEAR(e.centre_direction.horizontal_deg, 11.0, 0.01);
  EXPECT_NEAR(e.centre_direction.vertical_deg, -7.0, 0.01);
}

// Turned by 60°, the module's long (vertical) axis lies closer to the horizontal: measurement
// and truth both call it horizontal.
TEST(GlareEllipse, LobeTurnedPast45DegreesSwapsItsAxesNames) {
  SceneSpec spec;
  spec.limit_cd_m2 = 100'000;
  spec.lobe = lobeAtLimit(100'000, 11.9e6, 8.2, 3.6);
  spec.lobe.orientation_deg = 60;
  const Measured m = analyse(spec);
  ASSERT_TRUE(m.analysis.limit && m.analysis.limit->ellipse);
  EXPECT_NEAR(m.scene.truth.limit_axes->horizontal_deg, 8.2, 1e-9);
  expectAxes(m.analysis.limit->ellipse, m.scene.truth.limit_axes, kAxisTolerance, "turned 60");
  EXPECT_NEAR(m.analysis.limit->ellipse->orientation_deg, -30.0, 0.5);
}

TEST(GlareEllipse, StrongBarrelDistortionFarOffAxis) {
  SceneSpec spec;
  spec.horizontal_fov_deg = 70;
  spec.distortion = {-0.28, 0.08, 0, 0, 0};
  spec.lobe = lobeAtLimit(30'000, 839'000, 6.3, 5.0);
  spec.lobe.orientation_deg = -10;
  spec.lobe.centre_direction_deg = {25.0, 16.0};
  const Measured m = analyse(spec);
  EXPECT_NEAR(m.peak.value_cd_m2 / m.scene.truth.peak_cd_m2, 1.0, kPeakTolerance);
  ASSERT_TRUE(m.analysis.limit.has_value());
  expectAxes(m.analysis.limit->ellipse, m.scene.truth.limit_axes, kHardAxisTolerance, "limit-dist");
  expectAxes(m.analysis.fwhm.ellipse, m.scene.truth.fwhm_axes, kHardAxisTolerance, "fwhm-dist");
}

TEST(GlareEllipse, TinyLobe) {
  SceneSpec spec;
  spec.lobe = lobeAtLimit(30'000, 594'000, 0.6, 0.65);  // about 10 px at 16 px/deg
  const Measured m = analyse(spec);
  EXPECT_NEAR(m.peak.value_cd_m2 / m.scene.truth.peak_cd_m2, 1.0, kTinyPeakTolerance);
  ASSERT_TRUE(m.analysis.limit.has_value());
  expectAxes(m.analysis.limit->ellipse, m.scene.truth.limit_axes, kAxisTolerance, "limit-tiny");
  expectAxes(m.analysis.fwhm.ellipse, m.scene.truth.fwhm_axes, kHardAxisTolerance, "fwhm-tiny");
}

// The baseline: a binary mask + findContours + fitEllipse runs its contour through the
// centres of the region's edge pixels, half a pixel inside the true iso-line on each side: about
// one pixel short on a full axis, 10 % of a 10 px axis. The sub-pixel contour is not.
TEST(GlareEllipse, BinaryMaskBaselineIsBiasedWhereTheSubPixelContourIsNot) {
  SceneSpec spec;
  spec.lobe = lobeAtLimit(30'000, 594'000, 0.6, 0.65);  // about 10 px at 15.4 px/deg
  const Measured m = analyse(spec);
  ASSERT_TRUE(m.analysis.limit && m.analysis.limit->ellipse);
  const FloatImage& image = m.scene.merged.luminance_cd_m2;
  const cv::Mat luminance(image.height(), image.width(), CV_32F, const_cast<float*>(image.data()));
  cv::Mat mask;
  cv::threshold(luminance, mask, spec.limit_cd_m2, 255, cv::THRESH_BINARY);
  mask.convertTo(mask, CV_8U);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  ASSERT_EQ(contours.size(), 1u);
  const cv::RotatedRect binary = cv::fitEllipse(contours.front());
  // Pixels per degree at the image centre, where the lobe is: fx in px per radian.
  const double px_per_deg = m.scene.intrinsics.fx * radians(1.0);
  const double truth_major_px = m.scene.truth.limit_axes->horizontal_deg * px_per_deg;
  const double binary_error =
      std::max(binary.size.width, binary.size.height) / truth_major_px - 1.0;
  const double our_error =
      m.analysis.limit->ellipse->horizontal_deg / m.scene.truth.limit_axes->horizontal_deg - 1.0;
  EXPECT_LT(binary_error, -0.05) << "binary " << binary_error;
  EXPECT_LT(std::abs(our_error), 0.01) << "sub-pixel " << our_error;
}

TEST(GlareEllipse, NoisyLobe) {
  SceneSpec spec;
  spec.lobe = lobeAtLimit(30'000, 594'000, 5.0, 5.7);
  spec.relative_noise = 0.02;
  for (unsigned seed = 1; seed <= 3; ++seed) {
    spec.seed = seed;
    const Measured m = analyse(spec);
    EXPECT_NEAR(m.peak.value_cd_m2 / m.scene.truth.peak_cd_m2, 1.0, kPeakTolerance);
    ASSERT_TRUE(m.analysis.limit.has_value());
    expectAxes(m.analysis.limit->ellipse, m.scene.truth.limit_axes, kAxisTolerance, "limit-noisy");
    expectAxes(m.analysis.fwhm.ellipse, m.scene.truth.fwhm_axes, kAxisTolerance, "fwhm-noisy");
    EXPECT_EQ(m.analysis.limit->ellipse->regions, 1);
    EXPECT_TRUE(m.analysis.limit->ellipse->ellipticity_ok);
  }
}

double standardDeviation(const std::vector<double>& values) {
  const double mean = std::accumulate(values.begin(), values.end(), 0.0) / values.size();
  double sum = 0;
  for (const double v : values) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / static_cast<double>(values.size() - 1));
}

TEST(GlareEllipse, ReportedUncertaintyMatchesMonteCarloScatter) {
  SceneSpec spec;
  spec.width = 320;
  spec.height = 256;
  spec.horizontal_fov_deg = 20;  // same 16 px/deg as the other scenes, smaller image
  spec.lobe = lobeAtLimit(30'000, 594'000, 5.0, 5.7);
  spec.relative_noise = 0.02;
  constexpr int kTrials = 100;
  // Per ellipse: vertical, horizontal, orientation, solid angle.
  std::vector<double> values[8];
  double reported[8] = {};
  for (int trial = 0; trial < kTrials; ++trial) {
    spec.seed = 1000 + static_cast<unsigned>(trial);
    const Measured m = analyse(spec);
    ASSERT_TRUE(m.analysis.limit && m.analysis.limit->ellipse && m.analysis.fwhm.ellipse);
    const GlareEllipse* ellipses[2] = {&*m.analysis.limit->ellipse, &*m.analysis.fwhm.ellipse};
    for (int e = 0; e < 2; ++e) {
      const GlareEllipse& g = *ellipses[e];
      const double measured[4] = {g.vertical_deg, g.horizontal_deg, g.orientation_deg,
                                  g.solid_angle_sr};
      const double sigma[4] = {g.vertical_uncertainty_deg, g.horizontal_uncertainty_deg,
                               g.orientation_uncertainty_deg, g.solid_angle_uncertainty_sr};
      for (int q = 0; q < 4; ++q) {
        values[4 * e + q].push_back(measured[q]);
        reported[4 * e + q] += sigma[q] * sigma[q] / kTrials;  // mean variance
      }
    }
  }
  // A standard deviation from 100 samples is itself uncertain by about 7 % (from 40, 11 %: seeds
  // 1000-1039 happened to scatter a third less than 160 seeds do), and the linear propagation
  // ignores second-order terms: the reported value (the root of the mean variance) must be
  // within 0.7x..1.4x of the observed scatter (4 sigma of the estimate on either side). The lobe
  // is 14 % longer than wide, so its orientation is well determined. At 2 % per pixel the limit
  // contour is traced through a smoothing window (level_field.h), the FWHM's not.
  const char* names[8] = {"limit vertical",    "limit horizontal", "limit orientation",
                          "limit solid angle", "FWHM vertical",    "FWHM horizontal",
                          "FWHM orientation",  "FWHM solid angle"};
  for (int i = 0; i < 8; ++i) {
    const double observed = standardDeviation(values[i]);
    EXPECT_GT(std::sqrt(reported[i]), 0.7 * observed) << names[i];
    EXPECT_LT(std::sqrt(reported[i]), 1.4 * observed) << names[i];
  }
}

TEST(GlareEllipse, NoUncertaintyWithoutNoise) {
  SceneSpec spec;
  spec.lobe = lobeAtLimit(30'000, 594'000, 5.0, 5.7);
  const Measured m = analyse(spec);
  ASSERT_TRUE(m.analysis.limit && m.analysis.limit->ellipse);
  EXPECT_EQ(m.analysis.limit->ellipse->vertical_uncertainty_deg, 0.0);
}

GlareAnalysis analyseMerged(const calibration::MergedImage& merged, const Intrinsics& intrinsics,
                            double limit_cd_m2) {
  return analyseGlare(merged, calibration::CameraModel(intrinsics), findLuminancePeak(merged),
                      {.limit_cd_m2 = limit_cd_m2, .thresholds_cd_m2 = {}});
}

TEST(GlareEllipse, HotPixelNeitherBecomesTheMaximumNorARegion) {
  SceneSpec spec;
  spec.lobe = lobeAtLimit(30'000, 594'000, 5.0, 5.7);
  spec.relative_noise = 0.01;
  auto scene = renderScene(spec);
  scene.merged.luminance_cd_m2.at(40, 40) = 5.0e7;  // a stuck pixel far brighter than the lobe
  const GlareAnalysis analysis = analyseMerged(scene.merged, scene.intrinsics, 30'000);
  ASSERT_TRUE(analysis.limit && analysis.limit->ellipse);
  const GlareEllipse& e = *analysis.limit->ellipse;
  EXPECT_EQ(e.regions, 1);
  EXPECT_NEAR(e.centre_px.x, scene.centre_px.x, 0.5);
  EXPECT_NEAR(e.vertical_deg / scene.truth.limit_axes->vertical_deg, 1.0, kAxisTolerance);
}

TEST(GlareEllipse, NoiseDipInsideDoesNotSplitTheRegion) {
  SceneSpec spec;
  spec.lobe = lobeAtLimit(30'000, 594'000, 5.0, 5.7);
  auto scene = renderScene(spec);
  // A dead pixel and a short dark scratch inside the limit region.
  const int cx = static_cast<int>(scene.centre_px.x), cy = static_cast<int>(scene.centre_px.y);
  for (int x = cx + 20; x < cx + 24; ++x) scene.merged.luminance_cd_m2.at(x, cy) = 100.0f;
  const GlareAnalysis analysis = analyseMerged(scene.merged, scene.intrinsics, 30'000);
  ASSERT_TRUE(analysis.limit && analysis.limit->ellipse);
  EXPECT_EQ(analysis.limit->ellipse->regions, 1);
  EXPECT_NEAR(analysis.limit->ellipse->horizontal_deg / scene.truth.limit_axes->horizontal_deg, 1.0,
              kAxisTolerance);
}

TEST(GlareEllipse, SecondLobeCountsAsASecondRegion) {
  SceneSpec spec;
  spec.lobe = lobeAtLimit(30'000, 594'000, 5.0, 5.7);
  auto scene = renderScene(spec);
  spec.lobe = lobeAtLimit(30'000, 200'000, 2.0, 2.0);
  spec.lobe.centre_direction_deg = {-12.0, 6.0};
  const auto second = renderScene(spec);
  for (std::size_t i = 0; i < scene.merged.luminance_cd_m2.pixelCount(); ++i)
    scene.merged.luminance_cd_m2.data()[i] += second.merged.luminance_cd_m2.data()[i];
  const GlareAnalysis analysis = analyseMerged(scene.merged, scene.intrinsics, 30'000);
  ASSERT_TRUE(analysis.limit && analysis.limit->ellipse);
  EXPECT_EQ(analysis.limit->ellipse->regions, 2);
  // The ellipse is the brighter lobe's.
  EXPECT_NEAR(analysis.limit->ellipse->centre_direction.horizontal_deg, 0.0, 0.05);
}

TEST(GlareEllipse, SquarePlateauIsFlaggedAsNotElliptical) {
  SceneSpec spec;
  spec.lobe = lobeAtLimit(30'000, 594'000, 5.0, 5.7);
  auto scene = renderScene(spec);
  FloatImage& image = scene.merged.luminance_cd_m2;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      image.at(x, y) = std::abs(x - 320) <= 40 && std::abs(y - 256) <= 40 ? 1e5f : 1e3f;
  image.at(320, 256) = 2e5f;
  image.at(321, 256) = 2e5f;
  const GlareAnalysis analysis = analyseMerged(scene.merged, scene.intrinsics, 30'000);
  ASSERT_TRUE(analysis.limit && analysis.limit->ellipse);
  // A square's best ellipse misses it by about 11 % of its half-size (glare_ellipse.h).
  EXPECT_FALSE(analysis.limit->ellipse->ellipticity_ok);
  EXPECT_GT(analysis.limit->ellipse->shape_residual_fraction, 0.05);
}

TEST(GlareEllipse, RegionCutByTheImageBorderIsFlaggedTruncated) {
  SceneSpec spec;
  spec.lobe = lobeAtLimit(30'000, 594'000, 5.0, 5.7);
  spec.lobe.centre_direction_deg = {18.5, 0.0};  // the limit contour crosses the right edge
  const Measured m = analyse(spec);
  ASSERT_TRUE(m.analysis.limit && m.analysis.limit->ellipse);
  EXPECT_TRUE(m.analysis.limit->ellipse->truncated);
  // Fitted on the visible arc only, still close to the truth (noise-free scene).
  EXPECT_NEAR(m.analysis.limit->ellipse->vertical_deg / m.scene.truth.limit_axes->vertical_deg, 1.0,
              kAxisTolerance);
}

TEST(GlareEllipse, DarkImageHasNoEllipses) {
  SceneSpec spec;
  spec.lobe = lobeAtLimit(30'000, 594'000, 5.0, 5.7);
  auto scene = renderScene(spec);
  std::fill(scene.merged.bound.data(), scene.merged.bound.data() + scene.merged.bound.pixelCount(),
            static_cast<std::uint8_t>(calibration::PixelBound::kUpperBound));
  const GlareAnalysis analysis = analyseMerged(scene.merged, scene.intrinsics, 30'000);
  EXPECT_EQ(analysis.fwhm.status, EllipseStatus::kPeakIsBound);
  EXPECT_FALSE(analysis.fwhm.ellipse);
  // Upper bounds above the limit decide nothing: no limit ellipse drawn from dark pixels.
  ASSERT_TRUE(analysis.limit.has_value());
  EXPECT_EQ(analysis.limit->status, EllipseStatus::kPeakIsBound);
  EXPECT_FALSE(analysis.limit->ellipse);
  // ...but an upper bound below a level settles it: the true maximum is lower still.
  const GlareAnalysis high = analyseMerged(scene.merged, scene.intrinsics, 1e7);
  EXPECT_EQ(high.limit->status, EllipseStatus::kBelowLevel);
}

TEST(GlareEllipse, SolidAngleOfAConeIsExact) {
  // A circular cone of half-angle theta: 2 pi (1 - cos theta).
  for (const double half_deg : {0.5, 5.0, 30.0}) {
    const double expected = 2 * M_PI * (1 - std::cos(radians(half_deg)));
    EXPECT_NEAR(ellipseSolidAngleSr(half_deg, half_deg) / expected, 1.0, 1e-12);
  }
}

}  // namespace
}  // namespace glarecam::pipeline
