// The field a contour is traced in: the quadratic Savitzky-Golay window's weights (exact on a
// quadratic ln L, a unit sum), the noise decision, and pullBack() against finite differences.
#include "pipeline/level_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/sim_support.h"
#include "support/test_support.h"

namespace glarecam::pipeline {
namespace {

calibration::MergedImage lobeImage(int width, int height, double noise, unsigned seed) {
  calibration::MergedImage merged =
      testing::measuredImage(width, height, static_cast<float>(noise));
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double r2 = (x - 40.3) * (x - 40.3) / 300.0 + (y - 30.6) * (y - 30.6) / 200.0;
      merged.luminance_cd_m2.at(x, y) =
          static_cast<float>(1e5 * std::exp(-0.5 * r2) * (1 + noise * gauss(rng)));
    }
  return merged;
}

TEST(LevelField, WindowWeightsSumToOneAndKeepAQuadraticExactly) {
  for (int r = 1; r <= 6; ++r) {
    const SavitzkyGolayWindow w = savitzkyGolayWindow(r);
    double sum = 0, sum_i2 = 0, squares = 0;
    for (int j = -r; j <= r; ++j)
      for (int i = -r; i <= r; ++i) {
        sum += w.weight(i, j);
        sum_i2 += w.weight(i, j) * (i * i);
        squares += w.weight(i, j) * w.weight(i, j);
      }
    EXPECT_NEAR(sum, 1.0, 1e-12) << r;
    EXPECT_NEAR(sum_i2, 0.0, 1e-12) << r;
    EXPECT_NEAR(w.noise_gain, std::sqrt(squares), 1e-12) << r;
  }
  EXPECT_NEAR(savitzkyGolayWindow(1).noise_gain, std::sqrt(5.0) / 3, 1e-12);
}

TEST(LevelField, NoiseFreeQuadraticLnLIsLeftAsItIs) {
  const auto merged = lobeImage(80, 60, 0.0, 1);
  const LevelField field(merged, savitzkyGolayWindow(3), {10, 10, 70, 50});
  for (int y = 10; y < 50; ++y)
    for (int x = 10; x < 70; ++x)
      EXPECT_NEAR(field.values().at(x, y) / merged.luminance_cd_m2.at(x, y), 1.0, 1e-5)
          << x << "," << y;
}

// d(field)/d(merged pixel) by pullBack against central differences of the field itself.
TEST(LevelField, PullBackIsTheFieldsDerivative) {
  auto merged = lobeImage(80, 60, 0.02, 2);
  const PixelBox box{20, 15, 60, 45};
  const SavitzkyGolayWindow window = savitzkyGolayWindow(2);
  const LevelField field(merged, window, box);
  const std::size_t p = 30 * 80 + 41;
  ASSERT_TRUE(field.isSmoothed(p));
  const auto terms = field.pullBack({{p, {1.0, 2.0, -1.0}}});
  ASSERT_EQ(terms.size(), 25u);
  for (const auto& term : terms) {
    const float original = merged.luminance_cd_m2.data()[term.pixel];
    const double step = 1e-3 * original;
    merged.luminance_cd_m2.data()[term.pixel] = static_cast<float>(original + step);
    const double up = LevelField(merged, window, box).values().data()[p];
    merged.luminance_cd_m2.data()[term.pixel] = static_cast<float>(original - step);
    const double down = LevelField(merged, window, box).values().data()[p];
    merged.luminance_cd_m2.data()[term.pixel] = original;
    const double derivative = (up - down) / (2 * step);
    // 1 %: the field is float (7 digits), the differences are of 1e-3 steps.
    EXPECT_NEAR(term.sensitivity[0], derivative, 1e-2 * std::abs(derivative));
    EXPECT_NEAR(term.sensitivity[1], 2 * derivative, 2e-2 * std::abs(derivative));
    EXPECT_NEAR(term.sensitivity[2], -derivative, 1e-2 * std::abs(derivative));
  }
}

// The decision: a Gaussian lobe's ln L falls 2 ln(P / level) / r per pixel at radius r; noise of
// that order needs a window, the narrowest that brings it to kMaxNoiseToStep, never wider than a
// quarter of the radius.
TEST(LevelField, AWindowOnlyWhereTheNoiseRivalsThePixelStep) {
  // r = 40 px (5027 pixels), the FWHM (ln 2): a step of 3.5 % a pixel.
  const std::size_t pixels = 5027;
  const double step = 2 * std::log(2.0) / 40.0;
  EXPECT_NEAR(noiseToStep(2.0, 1.0, pixels, 0.01), 0.01 / step, 1e-3);
  EXPECT_EQ(windowFor(noiseToStep(2.0, 1.0, pixels, 0.001), pixels).radius, 0);  // 0.03
  const SavitzkyGolayWindow window = windowFor(0.5, pixels);
  EXPECT_GT(window.radius, 0);
  EXPECT_LE(window.noise_gain * 0.5, kMaxNoiseToStep);
  EXPECT_GT(savitzkyGolayWindow(window.radius - 1).noise_gain * 0.5, kMaxNoiseToStep);
  // Too small a lobe for any window: none.
  EXPECT_EQ(windowFor(5.0, 30).radius, 0);
  // Never wider than a quarter of the radius, nor than kMaxSmoothingRadius.
  EXPECT_LE(windowFor(50.0, pixels).radius, 10);
  EXPECT_EQ(windowFor(50.0, 10'000'000).radius, kMaxSmoothingRadius);
  // Nothing to measure: no window.
  EXPECT_EQ(noiseToStep(1.0, 1.0, pixels, 0.01), 0);
  EXPECT_EQ(noiseToStep(2.0, 1.0, pixels, std::nan("")), 0);
}

// A window whose pixels are not all measured (a bound pixel, the image's edge) leaves the pixel
// as merged.
TEST(LevelField, IncompleteWindowsKeepTheMergedValue) {
  auto merged = lobeImage(80, 60, 0.02, 3);
  merged.bound.at(41, 30) = static_cast<std::uint8_t>(calibration::PixelBound::kLowerBound);
  const LevelField field(merged, savitzkyGolayWindow(2), {0, 0, 80, 60});
  EXPECT_FALSE(field.isSmoothed(30 * 80 + 41));
  EXPECT_FALSE(field.isSmoothed(30 * 80 + 43));  // the bound pixel is in its window
  EXPECT_TRUE(field.isSmoothed(30 * 80 + 44));
  EXPECT_FALSE(field.isSmoothed(1 * 80 + 40));  // the window leaves the image
  EXPECT_EQ(field.values().at(43, 30), merged.luminance_cd_m2.at(43, 30));
  EXPECT_NE(field.values().at(44, 30), merged.luminance_cd_m2.at(44, 30));
}

}  // namespace
}  // namespace glarecam::pipeline
