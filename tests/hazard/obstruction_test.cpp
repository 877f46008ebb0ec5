#include "hazard/obstruction.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/hazard/hazard_fixtures.h"

namespace glarecam::hazard {
namespace {

// Clipper's micrometre grid: areas of metre-sized shadows exact to ~1e-5 m².
constexpr double kShadowAreaToleranceM2 = 1e-4;

const ArrayPolygon kLevel = testing::squareArray("roof", {0, 0, 0}, {0, 0, 1}, 10);

double shadedAreaM2(const std::vector<PlaneRing>& rings) {
  return areaM2(intersect(unite(rings), arrayRegion(kLevel)));
}

Obstruction box(double half, double base_m, double height_m) {
  return *makeExtrudedObstruction("box",
                                  {{-half, -half}, {half, -half}, {half, half}, {-half, half}},
                                  base_m, height_m, "scene.json", "obstructions[0]");
}

TEST(Obstruction, ASunOverheadShadesTheFootprint) {
  const std::vector<Obstruction> obstructions = {box(1, 2, 3)};
  EXPECT_NEAR(shadedAreaM2(sunShadowRings(kLevel, obstructions, {0, 0, 1})), 4,
              kShadowAreaToleranceM2);
}

TEST(Obstruction, ALowSunStretchesTheShadowAwayFromIt) {
  // Sun 45° high in the south: a point z above the roof shades the point z further north. The
  // floating box (z 2–3 over [−1, 1]²) shades y ∈ [1, 4]: 2 × 3 m², all north of its footprint.
  const std::vector<Obstruction> obstructions = {box(1, 2, 3)};
  const Vec3 sun = normalised({0, -1, 1});
  const std::vector<PlaneRing> rings = sunShadowRings(kLevel, obstructions, sun);
  EXPECT_NEAR(shadedAreaM2(rings), 6, kShadowAreaToleranceM2);
  const PlaneRegion shadow = unite(rings);
  EXPECT_TRUE(contains(shadow, {0, 2.5}));
  EXPECT_FALSE(contains(shadow, {0, 0}));
  EXPECT_FALSE(contains(shadow, {0, 4.5}));
}

TEST(Obstruction, OnlyWhatStandsInFrontOfThePlaneShades) {
  // Wholly below the roof: nothing. Half above: only the upper part's shadow (overhead sun:
  // still the footprint; sun from the south at 45°: z ∈ [0, 1] shades y ∈ [−1, 2]).
  EXPECT_TRUE(sunShadowRings(kLevel, {box(1, -3, -1)}, {0, 0, 1}).empty());
  EXPECT_NEAR(shadedAreaM2(sunShadowRings(kLevel, {box(1, -1, 1)}, {0, 0, 1})), 4,
              kShadowAreaToleranceM2);
  EXPECT_NEAR(shadedAreaM2(sunShadowRings(kLevel, {box(1, -1, 1)}, normalised({0, -1, 1}))), 2 * 3,
              kShadowAreaToleranceM2);
}

TEST(Obstruction, APointSeesAroundWhatIsBetween) {
  // An eye 10 m above the roof, a 2 × 2 m screen halfway: it hides twice its size, 4 × 4 m².
  const Obstruction screen = *makePlanarObstruction(
      "screen", {{-1, -1, 5}, {1, -1, 5}, {1, 1, 5}, {-1, 1, 5}}, "scene.json", "obstructions[0]");
  EXPECT_NEAR(shadedAreaM2(hiddenRings(kLevel, {screen}, {0, 0, 10})), 16, kShadowAreaToleranceM2);
  // Above the eye, or below the roof, it hides nothing.
  EXPECT_TRUE(hiddenRings(kLevel, {screen}, {0, 0, 4}).empty());
  // A box around the eye's level is cut a millionth below it: what it hides still lies within
  // the roof's square, as a whole (the box is wider than the roof as seen from inside it).
  EXPECT_NEAR(shadedAreaM2(hiddenRings(kLevel, {box(20, 8, 12)}, {0, 0, 10})), 100,
              kShadowAreaToleranceM2);
}

TEST(Obstruction, BadShapesAreRefusedNamingTheField) {
  const Result<Obstruction> low = makeExtrudedObstruction("wall", {{0, 0}, {1, 0}, {1, 1}}, 3, 3,
                                                          "scene.json", "obstructions[2]");
  ASSERT_FALSE(low);
  EXPECT_EQ(low.error().code, ErrorCode::kBadInput);
  EXPECT_NE(low.error().message.find("scene.json: obstructions[2]"), std::string::npos)
      << low.error().message;
  const Result<Obstruction> crossing = makeExtrudedObstruction(
      "house", {{0, 0}, {1, 1}, {1, 0}, {0, 1}}, 0, 3, "scene.json", "obstructions[1]");
  ASSERT_FALSE(crossing);
  EXPECT_NE(crossing.error().message.find("crosses itself"), std::string::npos)
      << crossing.error().message;
}

}  // namespace
}  // namespace glarecam::hazard
