#include "brdf/brdf_measurement.h"

#include <gtest/gtest.h>

#include <cmath>

#include "brdf/simulated_goniophotometer.h"
#include "surface/brdf_model.h"

namespace glarecam::brdf {
namespace {

GoniophotometerOptions options(double fine_step_deg, double noise) {
  GoniophotometerOptions o;
  o.fine_step_deg = fine_step_deg;
  o.medium_radius_deg = 15;
  o.relative_noise = noise;
  return o;
}

TEST(CheckSampling, TheGaussianApproximationOfAGaussianLobeIsTheLobe) {
  const surface::GaussianLobeBrdf lobe({.peak_brdf_sr = 40,
                                        .sigma_horizontal_deg = 2,
                                        .sigma_vertical_deg = 1.25,
                                        .floor_brdf_sr = 0});
  const BrdfMeasurement m = simulateMeasurement(lobe, 30, options(0.2, 0), "g.dat");
  const auto check = checkSampling(m);
  ASSERT_TRUE(check) << check.error().message;
  // ln f of a Gaussian is exactly quadratic: the fit is exact up to the 8-digit rounding.
  EXPECT_NEAR(check->lobe.sigma_horizontal_deg, 2, 1e-6);
  EXPECT_NEAR(check->lobe.sigma_vertical_deg, 1.25, 1e-6);
  EXPECT_NEAR(check->lobe.peak_brdf_sr, 40, 1e-5);
  EXPECT_NEAR(check->lobe.centre.y_deg, 0, 1e-6);
  EXPECT_NEAR(check->spacing_deg, 0.2, 0.02);
  EXPECT_GT(check->samples_across_fwhm, 10);
  EXPECT_TRUE(check->warnings.empty());
  // Half the peak at √(2 ln 2) σ: the FWHM.
  EXPECT_NEAR(check->lobe.verticalAxisDeg(0.5), 2.3548200450309493 * 1.25, 1e-5);
}

TEST(CheckSampling, AGridTooCoarseForTheLobeIsRefused) {
  // FWHM 1.18° sampled every 0.5°: 2.4 samples across, fewer than 5.
  const surface::GaussianLobeBrdf narrow({.peak_brdf_sr = 400,
                                          .sigma_horizontal_deg = 0.5,
                                          .sigma_vertical_deg = 0.5,
                                          .floor_brdf_sr = 0});
  const BrdfMeasurement m = simulateMeasurement(narrow, 20, options(0.5, 0), "coarse.dat");
  const auto check = checkSampling(m);
  ASSERT_FALSE(check);
  EXPECT_EQ(check.error().code, ErrorCode::kBadInput);
  EXPECT_NE(check.error().message.find("too coarse"), std::string::npos) << check.error().message;
  EXPECT_EQ(check.error().message.rfind("coarse.dat", 0), 0u);
}

TEST(CheckSampling, DataWithoutALobeAreSaidToBeSo) {
  // A flat distribution: every sample near the peak value, none a maximum.
  BrdfMeasurement m;
  m.file = "flat.dat";
  m.incident_theta_deg = 20;
  for (double t = 0; t <= 80; t += 0.5)
    for (double p = 0; p < 360; p += 5)
      m.samples.push_back({t, p, 1.0 + 1e-3 * std::sin(t + p), 1});
  const auto check = checkSampling(m);
  ASSERT_FALSE(check);
  EXPECT_NE(check.error().message.find("no glare lobe"), std::string::npos)
      << check.error().message;
}

TEST(CheckSampling, APeakAwayFromTheSpecularDirectionIsWarnedAbout) {
  // The file's φ_i the direction away from the source: the data's peak then lies 2 θ_i from the
  // specular direction the file implies.
  const surface::GaussianLobeBrdf lobe({.peak_brdf_sr = 40,
                                        .sigma_horizontal_deg = 2,
                                        .sigma_vertical_deg = 2,
                                        .floor_brdf_sr = 0.01});
  BrdfMeasurement m = simulateMeasurement(lobe, 10, options(0.2, 0), "flipped.dat");
  m.incident_phi_deg = 180;
  const auto check = checkSampling(m);
  ASSERT_TRUE(check) << check.error().message;
  ASSERT_EQ(check->warnings.size(), 1u);
  EXPECT_NEAR(check->peak_offset_deg, 20, 0.2);
  EXPECT_NE(check->warnings[0].find("20."), std::string::npos) << check->warnings[0];
}

TEST(EstimateRelativeNoise, FindsTheNoiseOfTheData) {
  const surface::GaussianLobeBrdf lobe({.peak_brdf_sr = 40,
                                        .sigma_horizontal_deg = 2,
                                        .sigma_vertical_deg = 1.5,
                                        .floor_brdf_sr = 0.01});
  // Noiseless: only the 8-digit rounding and the lobe's departure from a line remain.
  const auto clean = estimateRelativeNoise(simulateMeasurement(lobe, 30, options(0.2, 0), "c"));
  ASSERT_TRUE(clean);
  EXPECT_LT(*clean, 1e-3);
  // 2 % noise: thousands of runs make the median's estimate good to a few per cent; the
  // rings' curvature adds a little (runs are along arcs).
  const auto noisy = estimateRelativeNoise(simulateMeasurement(lobe, 30, options(0.2, 0.02), "n"));
  ASSERT_TRUE(noisy);
  EXPECT_NEAR(*noisy, 0.02, 0.002);
}

}  // namespace
}  // namespace glarecam::brdf
