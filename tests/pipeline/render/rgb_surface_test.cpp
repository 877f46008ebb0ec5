#include "pipeline/render/rgb_surface.h"

#include <gtest/gtest.h>

#include "canvas.h"

namespace glarecam::pipeline {
namespace {

TEST(RgbSurface, StartsBlackAtTheSizeAsked) {
  const CairoSurface surface = createRgbSurface(5, 3).value();
  const RgbImage image = copyRgb(surface.get());
  EXPECT_EQ(image.width, 5);
  EXPECT_EQ(image.height, 3);
  ASSERT_EQ(image.rgb.size(), 5u * 3u * 3u);
  for (const std::uint8_t value : image.rgb) EXPECT_EQ(value, 0);
}

TEST(RgbSurface, RefusesSizesCairoCannotMake) {
  EXPECT_FALSE(createRgbSurface(-1, 10));
  const Result<CairoSurface> huge = createRgbSurface(40'000, 10);  // Cairo's limit: 32 767
  ASSERT_FALSE(huge);
  EXPECT_NE(huge.error().message.find("40000x10"), std::string::npos) << huge.error().message;
}

TEST(RgbSurface, CopiesRedGreenBlueInThatOrderRowByRow) {
  TestCanvas canvas(4, 2, {1.0, 0.0, 0.0});
  const RgbImage red = canvas.image();
  EXPECT_EQ(red.rgb[0], 255);
  EXPECT_EQ(red.rgb[1], 0);
  EXPECT_EQ(red.rgb[2], 0);
  paint(canvas.cr(), {0.0, 0.0, 1.0});
  const RgbImage blue = canvas.image();
  const std::size_t last = blue.rgb.size() - 3;  // pixel (3, 1)
  EXPECT_EQ(blue.rgb[last + 0], 0);
  EXPECT_EQ(blue.rgb[last + 1], 0);
  EXPECT_EQ(blue.rgb[last + 2], 255);
}

}  // namespace
}  // namespace glarecam::pipeline
