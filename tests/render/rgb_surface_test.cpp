#include "render/rgb_surface.h"

#include <gtest/gtest.h>

#include "test_canvas.h"

namespace glarecam::render {
namespace {

TEST(RgbSurface, StartsBlackAtTheSizeAsked) {
  const RgbSurface surface = RgbSurface::create(5, 3).value();
  EXPECT_EQ(surface.width(), 5);
  EXPECT_EQ(surface.height(), 3);
  const RgbImage image = surface.copyRgb();
  EXPECT_EQ(image.width, 5);
  EXPECT_EQ(image.height, 3);
  ASSERT_EQ(image.rgb.size(), 5u * 3u * 3u);
  for (const std::uint8_t value : image.rgb) EXPECT_EQ(value, 0);
}

TEST(RgbSurface, RefusesSizesCairoCannotMake) {
  EXPECT_FALSE(RgbSurface::create(-1, 10));
  const Result<RgbSurface> huge = RgbSurface::create(40'000, 10);  // Cairo's limit: 32 767
  ASSERT_FALSE(huge);
  EXPECT_NE(huge.error().message.find("40000x10"), std::string::npos) << huge.error().message;
}

TEST(RgbSurface, CopiesRedGreenBlueInThatOrderRowByRow) {
  TestCanvas canvas(4, 2, {1.0, 0.0, 0.0});
  const RgbImage red = canvas.image();
  EXPECT_EQ(red.rgb[0], 255);
  EXPECT_EQ(red.rgb[1], 0);
  EXPECT_EQ(red.rgb[2], 0);
  paint(canvas.context(), {0.0, 0.0, 1.0});
  const RgbImage blue = canvas.image();
  const std::size_t last = blue.rgb.size() - 3;  // pixel (3, 1)
  EXPECT_EQ(blue.rgb[last + 0], 0);
  EXPECT_EQ(blue.rgb[last + 1], 0);
  EXPECT_EQ(blue.rgb[last + 2], 255);
}

// Pixels written directly show in what is copied out, and drawing afterwards goes over them.
TEST(RgbSurface, PixelsWrittenDirectlyAreKeptAndDrawnOver) {
  TestCanvas canvas(4, 2);
  {
    const RgbSurface::Pixels pixels = canvas.surface.pixels();
    pixels.row(1)[2] = 0x00102030;
  }
  EXPECT_EQ(canvas.at(2, 1), (CanvasPixel{0x10, 0x20, 0x30}));
  EXPECT_EQ(canvas.at(1, 1), kWhitePixel);
  canvas.context().setColour({0, 0, 0});
  canvas.context().rectangle({2, 0}, 2, 2);
  canvas.context().fill();
  EXPECT_EQ(canvas.at(2, 1), (CanvasPixel{0, 0, 0}));
}

}  // namespace
}  // namespace glarecam::render
