// The glare profile: the SGHAT-equivalent beam spread of an ellipse, and one row per degree from
// a sweep's fits.
#include "pipeline/glare_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/angles.h"
#include "pipeline/sweep_fits_test_support.h"
#include "support/test_support.h"

namespace glarecam::pipeline {
namespace {

using testing::fitsOf;

constexpr double kMradPerDeg = 1000.0 * radians(1.0);

TEST(CircularBeamSpread, ACircleIsItsOwnEquivalentCone) {
  // A circular ellipse of full angle 5°: the equal-solid-angle cone is the same cone, so beta is
  // 5° exactly (1e-9 relative: the trapezoid rule is exact for a constant radius).
  const CircularBeamSpread beam = circularBeamSpread(5.0, 5.0);
  EXPECT_NEAR(beam.beta_mrad, 5.0 * kMradPerDeg, 1e-9 * beam.beta_mrad);
  EXPECT_NEAR(beam.slope_error_mrad, beam.beta_mrad / 2 - kSunHalfAngleMrad, 1e-12);
  EXPECT_NEAR(beam.solid_angle_sr, 2 * std::numbers::pi * (1 - std::cos(2.5 * kMradPerDeg / 1e3)),
              1e-12);
}

TEST(CircularBeamSpread, AnEllipseMapsToTheGeometricMeanForSmallAngles) {
  // Small cones: Ω ≈ π a b, so the circular equivalent's full angle ≈ √(V H); at 8° × 2° the
  // curvature of the sphere changes that by < 1e-3 relative.
  const CircularBeamSpread beam = circularBeamSpread(8.0, 2.0);
  EXPECT_NEAR(beam.beta_mrad, 4.0 * kMradPerDeg, 1e-3 * beam.beta_mrad);
}

TEST(CircularBeamSpread, NarrowerThanTheSunGivesANegativeSlopeError) {
  EXPECT_LT(circularBeamSpread(0.3, 0.3).slope_error_mrad, 0);  // 0.3° < the sun's 0.53°
}

// A sweep with Lmax = lmax_at_0 e^(α / 20) and axes 3 + α/40, 4 - α/40 from `axes_from_deg` on.
SweepTable exponentialSweep(double lmax_at_0_cd_m2, double axes_from_deg) {
  SweepTable table;
  for (double alpha : {5.0, 20.0, 40.0, 55.0, 70.0, 80.0}) {
    SweepRow row;
    row.alpha_deg = alpha;
    row.lmax_cd_m2 = lmax_at_0_cd_m2 * std::exp(alpha / 20);
    if (alpha >= axes_from_deg) {
      row.vertical_deg = 3 + alpha / 40;
      row.horizontal_deg = 4 - alpha / 40;
    }
    table.rows.push_back(row);
  }
  return table;
}

TEST(GlareProfile, OneRowPerDegreeFromTheFitsWithLimitAndGlare) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  const SweepFits fits = fitsOf(*table);
  const auto rows = glareProfile(fits, {});
  ASSERT_EQ(rows.size(), 81u);
  EXPECT_TRUE(rows[0].extrapolated);  // the table starts at 5°
  EXPECT_FALSE(rows[5].extrapolated);
  EXPECT_EQ(rows[60].limit_cd_m2, 40000);
  EXPECT_DOUBLE_EQ(rows[60].lmax_cd_m2, fits.biquadratic.curve(60));  // the better fit
  EXPECT_TRUE(rows[60].glares);
  ASSERT_TRUE(rows[60].vertical_deg && rows[60].beam);
  EXPECT_DOUBLE_EQ(*rows[60].vertical_deg, fits.vertical.logistic->curve(60));
  const CircularBeamSpread expected =
      circularBeamSpread(*rows[60].vertical_deg, *rows[60].horizontal_deg);
  EXPECT_DOUBLE_EQ(rows[60].beam->beta_mrad, expected.beta_mrad);

  const nlohmann::json j = glareProfileJson({"standard", "2026-11-26", "t.csv"}, *table, fits, {});
  EXPECT_EQ(j["schema"], "glarecam.glare-profile/1");
  EXPECT_EQ(j["profile"].size(), 81u);
  EXPECT_EQ(j["measured"].size(), 9u);
  EXPECT_TRUE(j["fits"]["vertical"]["logistic"]["r2"].is_number());
  EXPECT_TRUE(j["profile"][60]["circular_beam"]["slope_error_mrad"].is_number());
  EXPECT_EQ(j["simulated"], false);
  EXPECT_TRUE(j["cameras"].empty());  // Table III says nothing of its camera

  // A sweep of the simulated camera makes a simulated profile, naming the camera and calibration.
  SweepTable simulated = *table;
  for (SweepRow& row : simulated.rows) {
    row.camera_backend = "sim";
    row.camera_serial = "SIM-0001";
    row.calibration_id = "0123456789abcdef";
  }
  const nlohmann::json s = glareProfileJson({"standard", "2026-11-26", "t.csv"}, simulated, fits, {});
  EXPECT_EQ(s["simulated"], true);
  EXPECT_EQ(s["cameras"], nlohmann::json::array({"sim SIM-0001"}));
  EXPECT_EQ(s["calibrations"], nlohmann::json::array({"0123456789abcdef"}));
}

// A logistic extrapolated past its rows can leave physical values (issue 18: a day sheet's
// vertical fit fell to 0° at α ≈ 42°): an axis is exported only within (0, 180°].
TEST(GlareProfile, AnAxisFitThatLeavesPhysicalValuesIsNotExported) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  SweepFits fits = fitsOf(*table);
  ASSERT_TRUE(fits.vertical.logistic);
  // y = 10 / (1 + exp(-(α - 50) 0.5)) - 2: below zero under ~47°, 8° at 80°.
  fits.vertical.logistic->curve = {.a = 10, .b = 50, .c = -2, .d = 0.5};
  const auto rows = glareProfile(fits, {});
  ASSERT_TRUE(rows[10].glares && rows[80].glares);  // Table III glares throughout
  EXPECT_FALSE(rows[10].vertical_deg);
  EXPECT_FALSE(rows[10].beam);
  ASSERT_TRUE(rows[80].vertical_deg);
  EXPECT_NEAR(*rows[80].vertical_deg, 8, 1e-5);
  EXPECT_TRUE(isPhysicalAxisDeg(180));
  EXPECT_FALSE(isPhysicalAxisDeg(0));
  EXPECT_FALSE(isPhysicalAxisDeg(180.5));
}

TEST(GlareProfile, NoAxesWhereTheModuleDoesNotGlare) {
  // Lmax crosses the 30 000 limit at 22°: ellipses from the 40° row on.
  const auto rows = glareProfile(fitsOf(exponentialSweep(10000, 40)), {});
  EXPECT_FALSE(rows[10].glares);
  EXPECT_FALSE(rows[10].vertical_deg);
  EXPECT_FALSE(rows[10].beam);
  EXPECT_TRUE(rows[80].glares);
}

TEST(GlareProfile, AConstantLimitReplacesTheCurve) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  const auto rows = glareProfile(fitsOf(*table), {.constant_cd_m2 = 5e6});
  EXPECT_EQ(rows[30].limit_cd_m2, 5e6);
  EXPECT_FALSE(rows[30].glares);  // ~570 000 cd/m² < 5e6
  EXPECT_TRUE(rows[80].glares);   // ~50e6
}

TEST(GlareProfile, AxesFittedOnANarrowerRangeAreFlaggedExtrapolated) {
  // Axes measured from 40° only: at 30° the module glares, the Lmax fit interpolates, but the
  // axis fits extrapolate.
  const auto rows = glareProfile(fitsOf(exponentialSweep(5e5, 40)), {});
  EXPECT_TRUE(rows[30].glares);
  EXPECT_TRUE(rows[30].extrapolated);
  EXPECT_FALSE(rows[50].extrapolated);
}

}  // namespace
}  // namespace glarecam::pipeline
