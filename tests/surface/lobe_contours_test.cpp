#include "surface/lobe_contours.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glarecam::surface {
namespace {

TEST(LobeContours, APointSourceGivesTheGaussiansClosedForm) {
  // Under a point source L = E cos α f: the contour at T has full axes 2σ √(2 ln(P/T)).
  const GaussianLobeParameters g{
      .peak_brdf_sr = 80, .sigma_horizontal_deg = 2, .sigma_vertical_deg = 1.2, .floor_brdf_sr = 0};
  const GaussianLobeBrdf lobe(g);
  const double alpha = 30, e = 100'000;
  const double peak = e * std::cos(alpha * std::numbers::pi / 180) * g.peak_brdf_sr;
  const double levels[] = {30'000, peak / 2};
  const LobeContours c =
      lobeContours(lobe, alpha, levels, {.illuminance_lx = e, .sun_half_angle_deg = 0});
  EXPECT_NEAR(c.peak_cd_m2, peak, 1e-9 * peak);
  EXPECT_NEAR(c.peak.y_deg, 0, 1e-6);
  for (std::size_t i = 0; i < 2; ++i) {
    const double k = 2 * std::sqrt(2 * std::log(peak / levels[i]));
    // Bisection to 1e-5° on each side.
    EXPECT_NEAR(*c.contours[i].vertical_deg, k * g.sigma_vertical_deg, 1e-4);
    EXPECT_NEAR(*c.contours[i].horizontal_deg, k * g.sigma_horizontal_deg, 1e-4);
  }
}

TEST(LobeContours, TheSunsDiscLowersThePeakOfARoundLobeAsTheIntegralSays) {
  // The mean of exp(-r²/2σ²) over a disc of radius R is (1 - e^{-x}) / x, x = R²/2σ²: with
  // R = 0.2664°, σ 1° the peak drops by 1.76 %. The disc's 6-ring quadrature (216 points) and
  // the change of incidence across it (cos θ_i, the lobe's frame) keep it within 3e-4.
  const GaussianLobeBrdf lobe(
      {.peak_brdf_sr = 80, .sigma_horizontal_deg = 1, .sigma_vertical_deg = 1, .floor_brdf_sr = 0});
  const double r = 0.2664;
  const LobeContours point = lobeContours(lobe, 20, {}, {.sun_half_angle_deg = 0});
  const LobeContours disc = lobeContours(lobe, 20, {}, {.sun_half_angle_deg = r});
  const double x = r * r / 2;
  EXPECT_NEAR(disc.peak_cd_m2 / point.peak_cd_m2, (1 - std::exp(-x)) / x, 3e-4);
}

TEST(LobeContours, NoContourAboveThePeak) {
  const GaussianLobeBrdf lobe(
      {.peak_brdf_sr = 1, .sigma_horizontal_deg = 1, .sigma_vertical_deg = 1, .floor_brdf_sr = 0});
  const double levels[] = {1e9};
  const LobeContours c = lobeContours(lobe, 10, levels);
  EXPECT_FALSE(c.contours[0].vertical_deg);
  EXPECT_FALSE(c.contours[0].horizontal_deg);
}

}  // namespace
}  // namespace glarecam::surface
