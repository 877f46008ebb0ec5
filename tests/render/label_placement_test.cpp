#include "render/label_placement.h"

#include <gtest/gtest.h>

namespace glarecam::render {
namespace {

// A horizontal line through y, from x0 to x1, a point per pixel.
Polyline horizontal(double y, double x0, double x1) {
  Polyline line;
  for (double x = x0; x <= x1; x += 1) line.push_back({x, y});
  return line;
}

constexpr Box kBox{0, 0, 400, 300};

TEST(LabelPlacement, StaysWhereItIsWhenItCoversNoLine) {
  const LabelSpec label{{100, 150}, {0, -1}, 60, 12};
  const Point p = placeLabel(label, kBox, {horizontal(50, 0, 400)});
  EXPECT_DOUBLE_EQ(p.x, 100);
  EXPECT_DOUBLE_EQ(p.y, 150);
}

TEST(LabelPlacement, MovesAwayFromALineItWouldCover) {
  // A line right through the text's middle: the label moves up (away) until the line is more
  // than a quarter em below its baseline's descent.
  const LabelSpec label{{100, 150}, {0, -1}, 60, 12};
  const std::vector<Polyline> lines{horizontal(146, 0, 400)};
  ASSERT_TRUE(labelCovers(label.at, label.width_px, label.font_px, lines));
  const Point p = placeLabel(label, kBox, lines);
  EXPECT_DOUBLE_EQ(p.x, 100);
  EXPECT_LT(p.y, 150);
  EXPECT_FALSE(labelCovers(p, label.width_px, label.font_px, lines));
  EXPECT_GE(146 - p.y, 12 * (0.2 + 0.25));  // the line clears the text's box and margin
  // The first clear place: a quarter em less would still cover it.
  EXPECT_TRUE(labelCovers({p.x, p.y + 3}, label.width_px, label.font_px, lines));
}

TEST(LabelPlacement, StaysInsideThePictureAndFallsBackWhenNoPlaceIsClear) {
  // Pushed towards the top edge: kept inside (baseline at least 1.1 em down).
  const LabelSpec high{{100, 5}, {0, -1}, 60, 12};
  const Point top = placeLabel(high, kBox, {});
  EXPECT_DOUBLE_EQ(top.y, 1.1 * 12);
  // Lines everywhere: the preferred place, inside the picture.
  std::vector<Polyline> everywhere;
  for (double y = 0; y <= 300; y += 2) everywhere.push_back(horizontal(y, 0, 400));
  const Point p = placeLabel({{390, 150}, {1, 0}, 60, 12}, kBox, everywhere);
  EXPECT_DOUBLE_EQ(p.x, 400 - 60 - 0.2 * 12);
  EXPECT_DOUBLE_EQ(p.y, 150);
}

}  // namespace
}  // namespace glarecam::render
