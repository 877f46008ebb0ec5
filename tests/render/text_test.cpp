#include "render/text.h"

#include <gtest/gtest.h>

#include "test_canvas.h"

namespace glarecam::render {
namespace {

constexpr Font kTextFont{.size = 20};

// The leftmost and rightmost columns with ink; {-1, -1} when there is none.
std::pair<int, int> inkColumns(const TestCanvas& canvas) {
  const RgbImage image = canvas.image();
  int first = -1, last = -1;
  for (int x = 0; x < image.width; ++x) {
    for (int y = 0; y < image.height; ++y) {
      if (image.rgb[(static_cast<std::size_t>(y) * image.width + x) * 3] < 200) {
        if (first < 0) first = x;
        last = x;
        break;
      }
    }
  }
  return {first, last};
}

TEST(Text, WidthGrowsWithTheTextTheSizeAndTheWeight) {
  TestCanvas canvas(10, 10);
  EXPECT_EQ(textWidth(canvas.context(), "", kTextFont), 0);
  const double iiii = textWidth(canvas.context(), "iiii", kTextFont);
  const double wwww = textWidth(canvas.context(), "WWWW", kTextFont);
  EXPECT_GT(iiii, 0);
  EXPECT_GT(wwww, 2 * iiii);
  const double small = textWidth(canvas.context(), "Glare 10\u2074", {.size = 10});
  const double large = textWidth(canvas.context(), "Glare 10\u2074", {.size = 40});
  EXPECT_NEAR(large / small, 4, 0.4);
  EXPECT_GT(textWidth(canvas.context(), "Glare", {.size = 20, .bold = true}),
            textWidth(canvas.context(), "Glare", kTextFont));
}

TEST(Text, LineHeightIsAFixedMultipleOfTheSize) {
  EXPECT_DOUBLE_EQ(lineHeight({.size = 10}), 13);
  EXPECT_DOUBLE_EQ(lineHeight({.size = 7}), 7 * kLineSpacingEm);
}

TEST(Text, AlignmentPutsTheBaselinePointAtTheStartMiddleOrEnd) {
  for (const Align align : {Align::kLeft, Align::kCentre, Align::kRight}) {
    TestCanvas canvas(200, 40);
    drawText(canvas.context(), {100, 30}, "HHHH", {kTextFont, kInk, align});
    const auto [first, last] = inkColumns(canvas);
    ASSERT_GE(first, 0);
    const double middle = (first + last + 1) / 2.0;
    if (align == Align::kLeft) {
      EXPECT_GE(first, 100);
    } else if (align == Align::kRight) {
      EXPECT_LE(last, 100);
    } else {
      EXPECT_NEAR(middle, 100, 2);
    }
  }
}

TEST(Text, DrawnInItsColourOnTheBaseline) {
  TestCanvas canvas(100, 40);
  drawText(canvas.context(), {10, 30}, "H", {kTextFont, {1, 0, 0}});
  EXPECT_FALSE(canvas.anyInk(0, 31, 100, 40));  // H has no descender
  EXPECT_TRUE(canvas.anyInk(0, 26, 100, 30));
  bool red = false;  // some pixel of a stem is all covered
  for (int x = 10; x < 30; ++x)
    red = red || (canvas.at(x, 25)[0] == 255 && canvas.at(x, 25)[1] < 100);
  EXPECT_TRUE(red);
}

TEST(Text, VerticalTextReadsUpwardCentredOnItsPoint) {
  TestCanvas canvas(60, 200);
  drawVerticalText(canvas.context(), {30, 100}, "HHHHHH", {kTextFont});
  const auto [first, last] = inkColumns(canvas);
  ASSERT_GE(first, 0);
  EXPECT_LE(last, 30);  // the baseline is at x = 30, the letters left of it
  EXPECT_LT(last - first, 20);
  EXPECT_TRUE(canvas.anyInk(0, 60, 60, 100));
  EXPECT_TRUE(canvas.anyInk(0, 100, 60, 140));
  EXPECT_FALSE(canvas.anyInk(0, 0, 60, 40));
}

// Pixels of a canvas in each of two kinds: the pale red of a page mark on white, (255, 199, 199)
// within rounding, and dark red (a translucent mark over black).
std::pair<int, int> markPixels(const TestCanvas& canvas) {
  const RgbImage image = canvas.image();
  int pale = 0, dark = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = rgbPixel(image, x, y);
      pale += p[0] == 255 && p[1] >= 196 && p[1] <= 201 && p[2] == p[1];
      dark += p[0] >= 50 && p[0] <= 62 && p[1] == 0 && p[2] == 0;
    }
  }
  return {pale, dark};
}

TEST(Text, APageMarkIsPaleRedDrawnUnderOrOver) {
  constexpr PageSize kPage{300, 200};
  TestCanvas under(300, 200), over(300, 200), over_black(300, 200, {0, 0, 0});
  drawPageMark(under.context(), kPage, "SIMULATED", "not a measurement", /*over=*/false);
  drawPageMark(over.context(), kPage, "SIMULATED", "not a measurement", /*over=*/true);
  drawPageMark(over_black.context(), kPage, "SIMULATED", "not a measurement", /*over=*/true);
  // On white, one look: the letters' pixels (anti-aliased edges aside) pale red either way.
  const int pale = markPixels(under).first;
  EXPECT_GT(pale, 2000);
  EXPECT_NEAR(markPixels(over).first, pale, pale / 50);
  // Drawn over, it lets what is under it show: over black, 22 % red.
  EXPECT_EQ(markPixels(over_black).first, 0);
  EXPECT_NEAR(markPixels(over_black).second, pale, pale / 50);
  // Across the page, bottom left to top right, centred.
  EXPECT_TRUE(under.anyInk(130, 80, 170, 120, 220));
  EXPECT_FALSE(under.anyInk(0, 0, 60, 40, 220));
}

TEST(Text, WrapBreaksAtSpacesToTheWidth) {
  TestCanvas canvas(10, 10);
  const double two_words = textWidth(canvas.context(), "one two", kTextFont);
  EXPECT_EQ(wrapText(canvas.context(), "one two three", two_words, kTextFont),
            (std::vector<std::string>{"one two", "three"}));
  EXPECT_EQ(wrapText(canvas.context(), "one  two\nthree", 1e6, kTextFont),
            (std::vector<std::string>{"one two three"}));
  EXPECT_EQ(wrapText(canvas.context(), "a unbreakable b", 1, kTextFont),
            (std::vector<std::string>{"a", "unbreakable", "b"}));
  EXPECT_TRUE(wrapText(canvas.context(), "   ", 100, kTextFont).empty());
}

TEST(Text, ParagraphsTakeALineHeightPerWrappedLine) {
  TestCanvas canvas(200, 200);
  const double two_words = textWidth(canvas.context(), "one two", kTextFont);
  const double height =
      drawParagraphs(canvas.context(), {5, 20}, two_words, {"one two three", "four"}, {kTextFont});
  EXPECT_DOUBLE_EQ(height, 3 * lineHeight(kTextFont));
  EXPECT_TRUE(canvas.anyInk(0, 20 + 2 * 26 - 15, 200, 20 + 2 * 26));  // the third line
  EXPECT_FALSE(canvas.anyInk(0, 20 + 3 * 26, 200, 200));
}

}  // namespace
}  // namespace glarecam::render
