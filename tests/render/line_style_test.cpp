#include "render/line_style.h"

#include <gtest/gtest.h>

#include "test_canvas.h"

namespace glarecam::render {
namespace {

constexpr Rgb kBlack{0, 0, 0};

TEST(LineStyle, SolidSegmentCoversItsWidthOnly) {
  TestCanvas canvas(100, 40);
  drawSegment(canvas.context(), {10, 20}, {90, 20}, {.colour = kBlack, .width_pt = 4});
  for (int x = 10; x < 90; x += 7) EXPECT_EQ(canvas.at(x, 19), (CanvasPixel{0, 0, 0})) << x;
  EXPECT_EQ(canvas.at(50, 17), kWhitePixel);  // the line covers y 18 to 22
  EXPECT_EQ(canvas.at(50, 22), kWhitePixel);
  EXPECT_EQ(canvas.at(5, 19), kWhitePixel);  // butt caps: nothing past the ends
  EXPECT_EQ(canvas.at(91, 19), kWhitePixel);
}

TEST(LineStyle, DashedLeavesGapsAndTheNextSolidLineDoesNot) {
  TestCanvas canvas(100, 40);
  // Dashes of 4 pt, gaps of 2.5 pt from x = 10: [10, 14] ink, [14, 16.5] gap, [16.5, 20.5] ink.
  drawSegment(canvas.context(), {10, 10}, {90, 10},
              {.colour = kBlack, .width_pt = 4, .dash = Dash::kDashed});
  EXPECT_EQ(canvas.at(11, 9), (CanvasPixel{0, 0, 0}));
  EXPECT_EQ(canvas.at(14, 9), kWhitePixel);
  EXPECT_EQ(canvas.at(15, 9), kWhitePixel);
  EXPECT_EQ(canvas.at(17, 9), (CanvasPixel{0, 0, 0}));
  drawSegment(canvas.context(), {10, 30}, {90, 30}, {.colour = kBlack, .width_pt = 4});
  EXPECT_EQ(canvas.at(14, 29), (CanvasPixel{0, 0, 0}));
  EXPECT_EQ(canvas.at(15, 29), (CanvasPixel{0, 0, 0}));
}

TEST(LineStyle, DottedDrawsRoundDotsApart) {
  TestCanvas canvas(100, 20);
  // Dots of the line's width every 2.4 pt: with a 1 pt line, ink and gaps alternate.
  drawSegment(canvas.context(), {10.5, 10.5}, {90, 10.5},
              {.colour = kBlack, .width_pt = 1, .dash = Dash::kDotted});
  int inked = 0, blank = 0;
  for (int x = 10; x < 88; ++x) {
    const int value = canvas.at(x, 10)[0];
    if (value < 200) ++inked;
    if (value == 255) ++blank;
  }
  EXPECT_GT(inked, 20);
  EXPECT_GT(blank, 10);
  EXPECT_EQ(canvas.at(50, 12), kWhitePixel);  // round dots, not a dashed bar
}

TEST(LineStyle, LongDashesAreLongerThanDashes) {
  TestCanvas canvas(100, 40);
  drawSegment(canvas.context(), {10, 10}, {90, 10},
              {.colour = kBlack, .width_pt = 4, .dash = Dash::kDashed});
  drawSegment(canvas.context(), {10, 30}, {90, 30},
              {.colour = kBlack, .width_pt = 4, .dash = Dash::kLongDashed});
  EXPECT_EQ(canvas.at(15, 9), kWhitePixel);              // a dashed line's first gap
  EXPECT_EQ(canvas.at(15, 29), (CanvasPixel{0, 0, 0}));  // still the first long dash (8 pt)
}

TEST(LineStyle, ColourAndWidthAreTheStyles) {
  TestCanvas canvas(40, 40);
  drawSegment(canvas.context(), {0, 20}, {40, 20}, {.colour = {1, 0, 0}, .width_pt = 10});
  EXPECT_EQ(canvas.at(20, 16), (CanvasPixel{255, 0, 0}));
  EXPECT_EQ(canvas.at(20, 24), (CanvasPixel{255, 0, 0}));
  EXPECT_EQ(canvas.at(20, 26), kWhitePixel);
}

}  // namespace
}  // namespace glarecam::render
