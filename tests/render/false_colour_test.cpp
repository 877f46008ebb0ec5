#include "render/false_colour.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "test_canvas.h"

namespace glarecam::render {
namespace {

CanvasPixel turboPixel(double t) {
  std::uint8_t rgb[3];
  turboColour(t, rgb);
  return {rgb[0], rgb[1], rgb[2]};
}

TEST(FalseColour, TurboEndsAreTheDocumentedColours) {
  std::uint8_t rgb[3];
  turboColour(0.0, rgb);
  EXPECT_NEAR(rgb[0], 35, 3);  // 0.13572138 * 255
  turboColour(1.0, rgb);
  EXPECT_GT(rgb[0], 100);
  EXPECT_LT(rgb[2], 30);
  EXPECT_EQ(turboPixel(-1), turboPixel(0));  // clamped
  EXPECT_EQ(turboPixel(2), turboPixel(1));
}

TEST(FalseColour, LogScalePositionsByDecadeAndClamps) {
  const LogScale scale{.log_min = 2, .log_max = 6};
  EXPECT_DOUBLE_EQ(scale.position(100), 0);
  EXPECT_DOUBLE_EQ(scale.position(1e4), 0.5);
  EXPECT_DOUBLE_EQ(scale.position(1e6), 1);
  EXPECT_DOUBLE_EQ(scale.position(1), 0);
  EXPECT_DOUBLE_EQ(scale.position(0), 0);
  EXPECT_DOUBLE_EQ(scale.position(1e9), 1);
}

// Values through the map, marked pixels in their mark's colour, a value that is not finite black,
// each pixel a zoom x zoom block.
TEST(FalseColour, PaintsValuesMarksAndBlocks) {
  FloatImage values(3, 1);
  values.at(0, 0) = 100;
  values.at(1, 0) = std::numeric_limits<float>::quiet_NaN();
  values.at(2, 0) = 1e6;
  ByteImage marks(3, 1);
  marks.at(2, 0) = 7;
  MarkColours colours{};
  colours[7] = Rgb{1, 0, 0};
  TestCanvas canvas(6, 2);
  paintFalseColour(canvas.surface, values, marks, colours, {.log_min = 2, .log_max = 6}, 2);
  for (const auto& [dx, dy] : {std::pair{0, 0}, std::pair{1, 1}}) {
    EXPECT_EQ(canvas.at(0 + dx, dy), turboPixel(0));
    EXPECT_EQ(canvas.at(2 + dx, dy), (CanvasPixel{0, 0, 0}));
    EXPECT_EQ(canvas.at(4 + dx, dy), (CanvasPixel{255, 0, 0}));
  }
}

}  // namespace
}  // namespace glarecam::render
