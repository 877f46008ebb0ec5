#include "render/canvas.h"

#include <gtest/gtest.h>

#include <type_traits>

#include "render/text.h"
#include "test_canvas.h"

namespace glarecam::render {
namespace {

static_assert(!std::is_copy_constructible_v<Canvas> && !std::is_copy_assignable_v<Canvas>);
static_assert(std::is_nothrow_move_constructible_v<Canvas> &&
              std::is_nothrow_move_assignable_v<Canvas>);
static_assert(!std::is_copy_constructible_v<Canvas::Saved> &&
              !std::is_move_constructible_v<Canvas::Saved>);

TEST(Canvas, OnASurfaceDrawsWithoutError) {
  RgbSurface surface = RgbSurface::create(8, 8).value();
  Result<Canvas> canvas = Canvas::onSurface(surface);
  ASSERT_TRUE(canvas) << canvas.error().message;
  paint(*canvas, kWhite);
  EXPECT_TRUE(canvas->status());
  EXPECT_EQ(surface.copyRgb().rgb[0], 255);
}

TEST(Canvas, StatusKeepsTheFirstError) {
  TestCanvas canvas(8, 8);
  drawText(canvas.context(), {1, 6}, "\xff not UTF-8", {{.size = 6}});
  drawText(canvas.context(), {1, 6}, "fine", {{.size = 6}});
  const Status status = canvas.context().status();
  ASSERT_FALSE(status);
  EXPECT_NE(status.error().message.find("UTF-8"), std::string::npos) << status.error().message;
}

// What is changed under a save() guard (the user space, the clip, the colour) is undone when it
// goes.
TEST(Canvas, SavedStateIsRestoredWhenTheGuardGoes) {
  TestCanvas canvas(20, 10);
  Canvas& c = canvas.context();
  c.setColour({0, 0, 0});
  {
    const Canvas::Saved saved = c.save();
    c.translate(10, 0);
    c.rectangle({0, 0}, 5, 5);
    c.clip();
    c.setColour({1, 0, 0});
    c.rectangle({0, 0}, 10, 10);
    c.fill();
  }
  EXPECT_EQ(canvas.at(12, 2), kRedPixel);  // translated and clipped
  EXPECT_EQ(canvas.at(12, 7), kWhitePixel);
  c.rectangle({0, 0}, 2, 2);  // at the origin again, in black, unclipped
  c.fill();
  EXPECT_EQ(canvas.at(1, 1), kBlackPixel);
  EXPECT_EQ(canvas.at(5, 1), kWhitePixel);
}

TEST(Canvas, ScaleShowsInTheClipAndInDeviceDistances) {
  TestCanvas canvas(40, 20);
  Canvas& c = canvas.context();
  c.scale(2, 4);
  const Point d = c.deviceToUserDistance({1, 0});
  EXPECT_DOUBLE_EQ(d.x, 0.5);
  EXPECT_DOUBLE_EQ(d.y, 0);
  c.rectangle({1, 1}, 3, 2);
  c.clip();
  const Box clip = c.clipExtents();
  EXPECT_DOUBLE_EQ(clip.x0, 1);
  EXPECT_DOUBLE_EQ(clip.y0, 1);
  EXPECT_DOUBLE_EQ(clip.x1, 4);
  EXPECT_DOUBLE_EQ(clip.y1, 3);
}

TEST(Canvas, ArcAndStrokeDrawAPathOnlyWhereItRuns) {
  TestCanvas canvas(40, 40);
  Canvas& c = canvas.context();
  c.setColour({0, 0, 0});
  c.setLineWidth(4);
  c.newSubPath();
  c.arc({20, 20}, 10, 0, 6.3);
  c.stroke();
  EXPECT_EQ(canvas.at(30, 19), kBlackPixel);  // on the circle
  EXPECT_EQ(canvas.at(20, 20), kWhitePixel);  // its centre, not filled
}

// An image painted scaled stays sharp: each pixel a block of its own colour.
TEST(Canvas, PaintedImagesKeepSharpPixels) {
  TestCanvas canvas(8, 4);
  Canvas& c = canvas.context();
  const RgbImage image{.width = 2, .height = 1, .rgb = {255, 0, 0, 0, 0, 255}};
  {
    const Canvas::Saved saved = c.save();
    c.scale(4, 4);
    c.paintImage(image);
  }
  EXPECT_EQ(canvas.at(0, 0), kRedPixel);
  EXPECT_EQ(canvas.at(3, 3), kRedPixel);
  EXPECT_EQ(canvas.at(4, 0), (CanvasPixel{0, 0, 255}));
  EXPECT_EQ(canvas.at(7, 3), (CanvasPixel{0, 0, 255}));
  EXPECT_TRUE(c.status());
}

TEST(Canvas, TextPathOutlinesTheText) {
  TestCanvas canvas(60, 30);
  Canvas& c = canvas.context();
  selectFont(c, {.size = 20, .bold = true});
  EXPECT_GT(c.textAdvance("HH"), c.textAdvance("H"));
  c.moveTo({2, 24});
  c.textPath("HH");
  c.setColour({0, 0, 0});
  c.fill();
  EXPECT_TRUE(canvas.anyInk(0, 0, 60, 30));
}

}  // namespace
}  // namespace glarecam::render
