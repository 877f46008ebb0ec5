#include "capture/sim/surface_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "capture/sim/simulated_stack.h"
#include "core/source_illuminance.h"
#include "support/sim_support.h"
#include "surface/lobe_contours.h"
#include "surface/surface_catalogue.h"

namespace glarecam::capture {
namespace {

// The analytic case: a Gaussian lobe in the angular plane (surface/brdf_model.h) under a point
// source is L = E·f_peak·cos α · exp(-x²/2σh² - y²/2σv²), whose contour at L has the full axes
// 2σ·sqrt(2 ln(L_peak / L)) in closed form.
std::shared_ptr<const surface::BrdfModel> gaussianSurface() {
  return std::make_shared<surface::GaussianLobeBrdf>(surface::GaussianLobeParameters{
      .peak_brdf_sr = 100, .sigma_horizontal_deg = 2, .sigma_vertical_deg = 1.5});
}

double closedFormAxis(double sigma_deg, double peak, double level) {
  return 2 * sigma_deg * std::sqrt(2 * std::log(peak / level));
}

TEST(SurfaceScene, TruthOfAGaussianLobeIsItsClosedFormWithBackgroundScaleAndSource) {
  constexpr double kAlphaDeg = 30, kBackground = 3000, kScale = 0.8, kLit = 0.7, kLimit = 60'000;
  auto scene = SurfaceScene::create(gaussianSurface(), {.alpha_deg = kAlphaDeg,
                                                        .background_cd_m2 = kBackground,
                                                        .peak_scale = kScale,
                                                        .sun_half_angle_deg = 0});
  ASSERT_TRUE(scene) << scene.error().message;
  const SceneTruths truths = scene->truth(kLimit, kLit);
  const double surface_peak =
      kDefaultReferenceIlluminanceLx * 100 * std::cos(kAlphaDeg * M_PI / 180);
  const double peak = kBackground + kScale * surface_peak;
  // The bisection goes to 1e-10°; the peak's golden section to ~1e-9 relative.
  EXPECT_NEAR(truths.reference.peak_cd_m2 / peak, 1, 1e-9);
  EXPECT_NEAR(truths.as_lit.peak_cd_m2 / (kLit * peak), 1, 1e-9);
  const double limit_level = (kLimit - kBackground) / kScale;
  ASSERT_TRUE(truths.reference.limit_axes);
  EXPECT_NEAR(truths.reference.limit_axes->vertical_deg,
              closedFormAxis(1.5, surface_peak, limit_level), 1e-6);
  EXPECT_NEAR(truths.reference.limit_axes->horizontal_deg,
              closedFormAxis(2, surface_peak, limit_level), 1e-6);
  // As lit, the limit is crossed where kLit·(B + s·L) = limit.
  const double lit_level = (kLimit / kLit - kBackground) / kScale;
  ASSERT_TRUE(truths.as_lit.limit_axes);
  EXPECT_NEAR(truths.as_lit.limit_axes->vertical_deg, closedFormAxis(1.5, surface_peak, lit_level),
              1e-6);
  const double half_level = (peak / 2 - kBackground) / kScale;
  ASSERT_TRUE(truths.reference.fwhm_axes);
  EXPECT_NEAR(truths.reference.fwhm_axes->horizontal_deg,
              closedFormAxis(2, surface_peak, half_level), 1e-6);
  // A limit only the background reaches has no contour; one above the peak neither.
  EXPECT_FALSE(scene->truth(kBackground / 2, 1).reference.limit_axes);
  EXPECT_FALSE(scene->truth(2 * peak, 1).reference.limit_axes);
}

TEST(SurfaceScene, TruthNamesTheAxesAsTheMeasurementDoesWhenRotated) {
  auto scene = SurfaceScene::create(
      gaussianSurface(), {.alpha_deg = 30, .orientation_deg = 90, .sun_half_angle_deg = 0});
  ASSERT_TRUE(scene);
  const SceneTruths truths = scene->truth(100'000, 1);
  ASSERT_TRUE(truths.reference.limit_axes);
  // The lobe's own horizontal (σ 2°) now lies along the image vertical.
  EXPECT_GT(truths.reference.limit_axes->vertical_deg, truths.reference.limit_axes->horizontal_deg);
}

// The rendered picture against the surface's luminance computed independently (by the incidence,
// surface/lobe_contours.h): at the peak and across the lobe, for the physical surfaces. The grid
// convolves by shifting the picture, which equals integrating over the incidence to first order
// in the disc's 0.27°; with the bicubic sampling that leaves < 0.2 % of the peak (measured
// ≤ 0.05 %).
TEST(SurfaceScene, RenderedPictureMatchesTheIndependentLuminanceUnderTheDisc) {
  for (const char* name : {"standard", "glare-reduced"}) {
    auto model = surface::surfaceModel(name);
    ASSERT_TRUE(model);
    std::shared_ptr<const surface::BrdfModel> shared(std::move(*model));
    constexpr double kAlphaDeg = 40;
    auto scene = SurfaceScene::create(shared, {.alpha_deg = kAlphaDeg});
    ASSERT_TRUE(scene);
    constexpr int kWidth = 201, kHeight = 161;
    const Intrinsics k = pinholeIntrinsics(kWidth, kHeight, 20.0);
    const calibration::CameraModel camera(k);
    const FloatImage image = scene->render(camera, kWidth, kHeight);
    const surface::LobeContours peak = surface::lobePeak(*shared, kAlphaDeg);
    const calibration::AngularPlane plane(calibration::rayFromDirection({0, 0}));
    for (int y = 10; y < kHeight; y += 25)
      for (int x = 10; x < kWidth; x += 25) {
        const calibration::PlanePointDeg p =
            plane.toPlane(camera.ray({static_cast<double>(x), static_cast<double>(y)}));
        const double expected = surface::luminanceAt(*shared, kAlphaDeg, p);
        EXPECT_NEAR(image.at(x, y), expected, 2e-3 * peak.peak_cd_m2)
            << name << " at pixel " << x << "," << y;
      }
  }
}

TEST(SurfaceScene, RefusesWhatItCannotRender) {
  EXPECT_FALSE(SurfaceScene::create(nullptr, {.alpha_deg = 30}));
  EXPECT_FALSE(SurfaceScene::create(gaussianSurface(), {.alpha_deg = 95}));
  EXPECT_FALSE(SurfaceScene::create(gaussianSurface(), {.alpha_deg = 30, .peak_scale = 0}));
  EXPECT_FALSE(SurfaceScene::create(gaussianSurface(), {.alpha_deg = 30, .background_cd_m2 = NAN}));
}

// A stack of each surface processed by the glare analysis reproduces the surface's own truth:
// the sensor's noise and the picture's grid leave ~0.5 % on the maximum (the quadratic cap
// under-reads a GGX tip by ~0.4 %) and a few hundredths of a degree on the axes (a 5° ellipse
// 60 px across here); 1.5 % bounds both with room for seeds. The glare-reduced lobe's contours
// at 60° are egg-shaped, where the fitted ellipse and the extents through the peak differ by
// ~0.2 % of 18°, on 8 px a degree: the tolerance covers it.
TEST(SurfaceScene, ProcessedStacksOfEachSurfaceMatchTheirTruth) {
  testing::TempDir dir;
  struct Case {
    const char* surface;
    double alpha_deg, fov_deg;
  };
  // The glare-reduced lobe is 18° by 14° at its limit: a wider view keeps it whole.
  for (const Case& c :
       {Case{"standard", 10, 16}, Case{"standard", 60, 16}, Case{"glare-reduced", 60, 40}}) {
    SimulationOptions options = testing::smallScene(c.alpha_deg, 320, 256);
    options.horizontal_fov_deg = c.fov_deg;
    options.surface = c.surface;
    const auto path = dir / (std::string(c.surface) + std::to_string(int(c.alpha_deg)));
    const SimulatedStack stack = testing::writeSmallStack(path, options);
    EXPECT_EQ(stack.manifest.id->rfind("sim-surface-" + std::string(c.surface), 0), 0u);
    testing::expectProcessedMatchesTruth(path, stack.truth, 0.015);
  }
}

TEST(SurfaceScene, AnUnknownSurfaceIsBadInput) {
  SimulationOptions options = testing::smallScene(30);
  options.surface = "no-such-surface";
  const auto scene = renderSimulatedScene(options);
  ASSERT_FALSE(scene);
  EXPECT_EQ(scene.error().code, ErrorCode::kBadInput);
  options.surface = "curves:no-such-module";
  EXPECT_FALSE(renderSimulatedScene(options));
}

}  // namespace
}  // namespace glarecam::capture
