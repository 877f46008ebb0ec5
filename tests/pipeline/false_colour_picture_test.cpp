#include "pipeline/false_colour_picture.h"

#include <gtest/gtest.h>

#include "render/test_canvas.h"
#include "support/sim_support.h"

namespace glarecam::pipeline {
namespace {

using render::RgbImage;

calibration::MergedImage gradient(int width, int height) {
  calibration::MergedImage merged = testing::measuredImage(width, height, 0.01f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x)
      merged.luminance_cd_m2.at(x, y) = std::pow(10.0f, 2.0f + 4.0f * x / (width - 1));
  }
  return merged;
}

TEST(FalseColourPicture, MapsLowToDarkBlueHighToDarkRedAndAddsAColourBar) {
  calibration::MergedImage merged = gradient(200, 120);
  merged.bound.at(5, 5) = static_cast<std::uint8_t>(calibration::PixelBound::kLowerBound);
  auto image = renderFalseColour(merged, {});
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_GT(image->width, 200);  // the colour bar panel sits to the right
  EXPECT_GE(image->height, 120);
  const std::uint8_t* low = rgbPixel(*image, 30, 60);  // 15 % up the scale: Turbo's blue
  const std::uint8_t* high = rgbPixel(*image, 199, 60);
  EXPECT_GT(low[2], low[0]);
  EXPECT_GT(high[0], high[2]);  // and ends dark red
  const std::uint8_t* saturated = rgbPixel(*image, 5, 5);
  EXPECT_EQ(saturated[0], 255);
  EXPECT_EQ(saturated[1], 255);
  EXPECT_EQ(saturated[2], 255);
}

// A suspect stack's picture carries a band across the top of the image (kLimitColour, a colour
// the Turbo map never makes) with its text in white; without a banner the top is the image.
TEST(FalseColourPicture, ABannerCrossesTheTopOfTheImage) {
  const calibration::MergedImage merged = gradient(200, 120);
  auto plain = renderFalseColour(merged, {});
  FalseColourOptions options;
  options.banner = "SUSPECT: frames disagree with the merge";
  auto bannered = renderFalseColour(merged, options);
  ASSERT_TRUE(plain && bannered);
  const auto magenta = [](const std::uint8_t* p) {
    return p[0] == 255 && p[1] == 0 && p[2] == 255;
  };
  EXPECT_TRUE(magenta(rgbPixel(*bannered, 1, 1)));
  EXPECT_TRUE(magenta(rgbPixel(*bannered, 198, 1)));
  EXPECT_FALSE(magenta(rgbPixel(*plain, 1, 1)));
  EXPECT_EQ(rgbPixel(*bannered, 100, 100)[0],
            rgbPixel(*plain, 100, 100)[0]);  // below the band: unchanged
  int white = 0;                             // the text
  for (int x = 0; x < 200; ++x)
    for (int y = 0; y < 12; ++y) white += rgbPixel(*bannered, x, y)[1] > 200;
  EXPECT_GT(white, 20);
}

// The caption's lines (stack, Lmax, limit, verdict) go under the title in the panel, which grows
// to keep the colour bar whole; without one the panel's caption rows stay background.
TEST(FalseColourPicture, TheCaptionIsWrittenUnderTheTitle) {
  const calibration::MergedImage merged = gradient(200, 120);
  FalseColourOptions options;
  options.title = "\u03b1 60\u00b0";
  auto plain = renderFalseColour(merged, options);
  options.caption = {"sim-standard-a60.00-s1", "Lmax 2 194 000 cd/m\u00b2",
                     "limit 40 000 cd/m\u00b2", "glare: yes"};
  auto captioned = renderFalseColour(merged, options);
  ASSERT_TRUE(plain && captioned);
  EXPECT_GT(captioned->height, plain->height);
  // The colour bar's first row: the first saturated (Turbo) pixel down its middle column.
  const auto barTop = [](const RgbImage& image) {
    const int x = 200 + 11 + 4;  // image width + one em (11 px font) + a few px into the bar
    for (int y = 0; y < image.height; ++y) {
      const std::uint8_t* p = rgbPixel(image, x, y);
      if (std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) > 60) return y;
    }
    return -1;
  };
  const int plain_top = barTop(*plain), captioned_top = barTop(*captioned);
  ASSERT_GT(plain_top, 0);
  EXPECT_NEAR(captioned_top - plain_top, 4 * 1.3 * 11, 2);  // four lines of 1.3 em
  int white = 0;  // the caption's text between the title and the bar
  for (int y = 16; y < captioned_top - 20; ++y)
    for (int x = 200; x < captioned->width; ++x) {
      const std::uint8_t* p = rgbPixel(*captioned, x, y);
      white += p[0] > 200 && p[1] > 200 && p[2] > 200;
    }
  EXPECT_GT(white, 100);
}

// A frame under min_image_height_px is drawn enlarged by a whole factor, each pixel a block of
// one colour; taller frames stay 1:1.
TEST(FalseColourPicture, SmallFramesAreEnlargedPixelByPixel) {
  const calibration::MergedImage merged = gradient(100, 60);
  auto plain = renderFalseColour(merged, {});
  FalseColourOptions options;
  options.min_image_height_px = 250;  // 4x: the largest whole factor that stays under it
  auto zoomed = renderFalseColour(merged, options);
  ASSERT_TRUE(plain && zoomed);
  EXPECT_GE(zoomed->height, 240);
  EXPECT_GT(zoomed->width, 400);
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{37, 21}, std::pair{99, 59}}) {
    const std::uint8_t* source = rgbPixel(*plain, x, y);
    for (int dy = 0; dy < 4; ++dy) {
      for (int dx = 0; dx < 4; ++dx) {
        const std::uint8_t* shown = rgbPixel(*zoomed, 4 * x + dx, 4 * y + dy);
        EXPECT_EQ(shown[0], source[0]) << x << "," << y;
        EXPECT_EQ(shown[1], source[1]) << x << "," << y;
        EXPECT_EQ(shown[2], source[2]) << x << "," << y;
      }
    }
  }
  options.min_image_height_px = 60;  // not under it: 1:1
  auto same = renderFalseColour(merged, options);
  ASSERT_TRUE(same);
  EXPECT_EQ(same->width, plain->width);
  EXPECT_EQ(same->rgb, plain->rgb);
}

TEST(FalseColourPicture, RefusesAnEmptyImage) {
  calibration::MergedImage empty;
  EXPECT_FALSE(renderFalseColour(empty, {}));
}

}  // namespace
}  // namespace glarecam::pipeline
