#include "hazard/plane_region.h"

#include <gtest/gtest.h>

#include "tests/hazard/hazard_fixtures.h"

namespace glarecam::hazard {
namespace {

// Clipper's grid is a micrometre: areas of metre-sized shapes are exact to ~1e-6 m².
constexpr double kClipAreaToleranceM2 = 1e-5;

PlaneRing square(double cx, double cy, double half) {
  return {{cx - half, cy - half},
          {cx + half, cy - half},
          {cx + half, cy + half},
          {cx - half, cy + half}};
}

TEST(PlaneRegion, SubtractingAHoleLeavesARingWithAHole) {
  const PlaneRegion whole{{square(0, 0, 5)}};
  const PlaneRegion holed = subtract(whole, {square(0, 0, 1)});
  EXPECT_NEAR(areaM2(holed), 100 - 4, kClipAreaToleranceM2);
  EXPECT_FALSE(contains(holed, {0, 0}));
  EXPECT_TRUE(contains(holed, {3, 3}));
  EXPECT_FALSE(contains(holed, {6, 0}));
}

TEST(PlaneRegion, OverlappingCutsOfEitherOrientationUnite) {
  // Two cuts, one listed clockwise, overlapping: under the non-zero rule they must not cancel.
  PlaneRing clockwise = square(1, 0, 1);
  std::reverse(clockwise.begin(), clockwise.end());
  const PlaneRegion left = subtract(PlaneRegion{{square(0, 0, 5)}}, {square(0, 0, 1), clockwise});
  EXPECT_NEAR(areaM2(left), 100 - 6, kClipAreaToleranceM2);  // the cuts' union: 2 × 3
  EXPECT_FALSE(contains(left, {0.5, 0}));
  EXPECT_NEAR(areaM2(unite({square(0, 0, 1), clockwise})), 6, kClipAreaToleranceM2);
}

TEST(PlaneRegion, IntersectionAndHalfPlanes) {
  const PlaneRegion whole{{square(0, 0, 5)}};
  // u ≥ 2: a 3 × 10 strip of the square.
  EXPECT_NEAR(areaM2(intersect(whole, halfPlane(1, 0, -2, 10))), 30, kClipAreaToleranceM2);
  // u + w ≤ 0: half the square, whatever the scale of (a, b, c).
  EXPECT_NEAR(areaM2(intersect(whole, halfPlane(-3, -3, 0, 10))), 50, kClipAreaToleranceM2);
  // A line beyond the extent: all or nothing.
  EXPECT_NEAR(areaM2(intersect(whole, halfPlane(1, 0, 100, 10))), 100, kClipAreaToleranceM2);
  EXPECT_TRUE(intersect(whole, halfPlane(1, 0, -100, 10)).empty());
  // No direction: c's sign decides.
  EXPECT_NEAR(areaM2(halfPlane(0, 0, 1, 5)), 100, kClipAreaToleranceM2);
  EXPECT_TRUE(halfPlane(0, 0, -1, 5).empty());
}

TEST(PlaneRegion, TheArraysOwnFrameRoundTrips) {
  const ArrayPolygon array = testing::squareArray("a", {3, 4, 5}, normalised({0, -1, 1}), 4);
  const PlaneRegion region = arrayRegion(array);
  EXPECT_NEAR(areaM2(region), 16, kClipAreaToleranceM2);
  for (const Vec3& vertex : array.vertices_m) {
    const Vec3 back = planeToScene(array, sceneToPlane(array, vertex));
    EXPECT_NEAR(norm(back - vertex), 0, 1e-12);
  }
  EXPECT_TRUE(containsPlanePoint(array, array.centroid_m));
  EXPECT_FALSE(containsPlanePoint(array, array.centroid_m + 3 * array.axis_u));
}

}  // namespace
}  // namespace glarecam::hazard
