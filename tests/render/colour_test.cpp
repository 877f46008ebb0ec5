#include "render/colour.h"

#include <gtest/gtest.h>

#include "test_canvas.h"

namespace glarecam::render {
namespace {

TEST(Colour, LightenedMovesEachChannelTowardWhite) {
  const Rgb c = lightened({0.2, 0.4, 1.0}, 0.5);
  EXPECT_DOUBLE_EQ(c.r, 0.6);
  EXPECT_DOUBLE_EQ(c.g, 0.7);
  EXPECT_DOUBLE_EQ(c.b, 1.0);
  const Rgb same = lightened(kInk, 0);
  EXPECT_DOUBLE_EQ(same.r, kInk.r);
  const Rgb white = lightened(kInk, 1);
  EXPECT_DOUBLE_EQ(white.g, 1.0);
}

TEST(Colour, PaintFillsTheWholeSurface) {
  TestCanvas canvas(3, 3, {0.0, 1.0, 0.0});
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) EXPECT_EQ(canvas.at(x, y), (CanvasPixel{0, 255, 0})) << x << y;
  paint(canvas.context(), kWhite);
  EXPECT_EQ(canvas.at(1, 1), kWhitePixel);
}

TEST(Colour, InkIsDarkAndNeutral) {
  TestCanvas canvas(1, 1, kInk);
  const CanvasPixel ink = canvas.at(0, 0);
  EXPECT_LT(ink[0], 40);
  EXPECT_NEAR(ink[0], ink[2], 8);
}

}  // namespace
}  // namespace glarecam::render
