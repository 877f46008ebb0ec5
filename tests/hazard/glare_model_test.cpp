#include "hazard/glare_model.h"

#include <gtest/gtest.h>

#include <numbers>

#include "tests/hazard/hazard_fixtures.h"

namespace glarecam::hazard {
namespace {

TEST(HazardGlareModel, ParsesTheModelsOfTheCommandLine) {
  const auto models = parseModels("ellipse,circle,cone:0.5", "--models");
  ASSERT_TRUE(models) << models.error().message;
  ASSERT_EQ(models->size(), 3u);
  EXPECT_EQ((*models)[0].kind, ModelKind::kEllipse);
  EXPECT_EQ((*models)[1].kind, ModelKind::kCircle);
  EXPECT_EQ((*models)[2].kind, ModelKind::kCone);
  EXPECT_EQ((*models)[2].cone_deg, 0.5);
  EXPECT_EQ((*models)[2].name(), "cone:0.5");
}

TEST(HazardGlareModel, RefusesUnknownRepeatedAndBadCones) {
  for (const char* bad : {"elipse", "ellipse,ellipse", "cone:", "cone:0", "cone:-1", "cone:200",
                          "cone:1x", "cone:nan", "", "ellipse,"}) {
    const auto models = parseModels(bad, "--models");
    ASSERT_FALSE(models) << bad;
    EXPECT_EQ(models.error().code, ErrorCode::kBadInput);
    EXPECT_TRUE(models.error().message.starts_with("--models: ")) << models.error().message;
  }
  EXPECT_NE(parseModels("elipse", "--models").error().message.find("did you mean ellipse"),
            std::string::npos);
}

TEST(HazardGlareModel, EachModelsRegionFromTheProfile) {
  const ProfileTable profile = testing::constantProfile(8, 4);
  const SpreadAt spread = profile.at(30);
  const auto ellipse = regionAxes({ModelKind::kEllipse}, spread);
  ASSERT_TRUE(ellipse);
  EXPECT_EQ(ellipse->vertical_deg, 8);
  EXPECT_EQ(ellipse->horizontal_deg, 4);
  const auto circle = regionAxes({ModelKind::kCircle}, spread);
  ASSERT_TRUE(circle);
  EXPECT_EQ(circle->vertical_deg, circle->horizontal_deg);
  // The equal-solid-angle circle of an 8° × 4° ellipse is close to √(8·4) = 5.66°.
  EXPECT_NEAR(circle->vertical_deg, std::sqrt(32.0), 0.01);
  const auto cone = regionAxes({ModelKind::kCone, 2.5}, spread);
  EXPECT_EQ(cone->vertical_deg, 2.5);
  EXPECT_EQ(maxFullAxisDeg({ModelKind::kCone, 2.5}, profile), 2.5);
  EXPECT_EQ(maxFullAxisDeg({ModelKind::kEllipse}, profile), 8);
}

}  // namespace
}  // namespace glarecam::hazard

namespace glarecam::hazard {
namespace {

TEST(HazardGlareModel, SigmaIsSghatsConeForASlopeError) {
  // β = 2 (4.65 mrad + σ): σ = 2 mrad gives 13.3 mrad = 0.762°.
  const Result<std::vector<GlareModel>> models = parseModels("ellipse,sigma:2", "--models");
  ASSERT_TRUE(models) << models.error().message;
  ASSERT_EQ(models->size(), 2u);
  const GlareModel& sigma = (*models)[1];
  EXPECT_EQ(sigma.kind, ModelKind::kCone);
  EXPECT_NEAR(sigma.cone_deg, 13.3e-3 * 180 / std::numbers::pi, 1e-12);
  EXPECT_EQ(sigma.name(), "sigma:2");
  EXPECT_NEAR(sghatBeamDeg(0), 9.3e-3 * 180 / std::numbers::pi, 1e-12);  // the sun alone
  for (const char* bad : {"sigma:-1", "sigma:", "sigma:x", "sigma:2000"}) {
    const Result<std::vector<GlareModel>> refused = parseModels(bad, "--models");
    ASSERT_FALSE(refused) << bad;
    EXPECT_NE(refused.error().message.find("sigma:MRAD"), std::string::npos) << bad;
  }
  EXPECT_FALSE(parseModels("sigma:2,sigma:2", "--models"));
}

}  // namespace
}  // namespace glarecam::hazard
