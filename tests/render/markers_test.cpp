#include "render/markers.h"

#include <gtest/gtest.h>

#include "test_canvas.h"

namespace glarecam::render {
namespace {

constexpr Rgb kRed{1, 0, 0};

TEST(Markers, FilledCircleIsRoundAndInItsColour) {
  TestCanvas canvas(40, 40);
  drawMarker(canvas.context(), {20, 20}, {.colour = kRed, .size_pt = 20});
  EXPECT_EQ(canvas.at(20, 20), kRedPixel);
  EXPECT_EQ(canvas.at(12, 19), kRedPixel);    // inside, off centre
  EXPECT_EQ(canvas.at(11, 11), kWhitePixel);  // the bounding square's corner: outside
  EXPECT_EQ(canvas.at(20, 33), kWhitePixel);
}

TEST(Markers, SquareFillsItsCorners) {
  TestCanvas canvas(40, 40);
  drawMarker(canvas.context(), {20, 20},
             {.colour = kRed, .shape = MarkerShape::kSquare, .size_pt = 20});
  EXPECT_EQ(canvas.at(11, 11), kRedPixel);
  EXPECT_EQ(canvas.at(28, 28), kRedPixel);
  EXPECT_EQ(canvas.at(8, 20), kWhitePixel);
}

TEST(Markers, FilledMarkerHasAWhiteRing) {
  TestCanvas canvas(40, 40, {0, 0, 0});
  drawMarker(canvas.context(), {20, 20},
             {.colour = kRed, .shape = MarkerShape::kSquare, .size_pt = 20});
  // The square's edge at x = 10 carries the 0.6 pt white ring: that column turns light.
  const CanvasPixel edge = canvas.at(9, 20);
  EXPECT_GT(edge[1], 40);
  EXPECT_EQ(canvas.at(15, 20), kRedPixel);
}

TEST(Markers, HollowMarkerIsWhiteInsideWithAColouredOutline) {
  TestCanvas canvas(40, 40, {0, 0, 0});
  drawMarker(canvas.context(), {20, 20}, {.colour = kRed, .size_pt = 20, .hollow = true});
  EXPECT_EQ(canvas.at(20, 20), kWhitePixel);
  int reddest = 0;
  for (int x = 27; x <= 31; ++x)
    reddest = std::max(reddest, canvas.at(x, 20)[0] - canvas.at(x, 20)[1]);
  EXPECT_GT(reddest, 100);  // the 1.2 pt outline crosses x = 30
}

}  // namespace
}  // namespace glarecam::render
