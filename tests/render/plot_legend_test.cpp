#include "render/plot_legend.h"

#include <gtest/gtest.h>

#include "test_canvas.h"

namespace glarecam::render {
namespace {

const std::vector<LegendEntry> kEntries = {
    {"a line", LineStyle{.colour = {0, 0, 1}}, std::nullopt},
    {"a marker", std::nullopt, MarkerStyle{.colour = {1, 0, 0}}},
    {"both", LineStyle{.colour = {0, 0, 1}}, MarkerStyle{.colour = {1, 0, 0}}}};

Plot emptyPlot() {
  return {.area = {0, 0, 300, 200},
          .x = {.range = {0, 1}, .step = 1},
          .y = {.range = {0, 1}, .step = 1}};
}

// Which quadrants of the 300 × 200 area hold dark ink: top left, top right, bottom right,
// bottom left.
std::vector<bool> inkedQuadrants(const TestCanvas& canvas) {
  return {canvas.anyInk(0, 0, 150, 100), canvas.anyInk(150, 0, 300, 100),
          canvas.anyInk(150, 100, 300, 200), canvas.anyInk(0, 100, 150, 200)};
}

TEST(PlotLegend, AnEmptyPlotGetsItsLegendTopLeft) {
  TestCanvas canvas(300, 200);
  drawLegend(canvas.context(), emptyPlot(), kEntries);
  EXPECT_EQ(inkedQuadrants(canvas), (std::vector<bool>{true, false, false, false}));
}

TEST(PlotLegend, TheLegendAvoidsTheCornersWithInk) {
  TestCanvas canvas(300, 200);
  Plot plot = emptyPlot();
  plot.ink = {{{20, 20}, 12}, {{280, 20}, 12}, {{20, 180}, 1}, {{25, 180}, 1}, {{280, 180}, 1}};
  drawLegend(canvas.context(), plot, kEntries);  // the bottom right has the least ink
  EXPECT_EQ(inkedQuadrants(canvas), (std::vector<bool>{false, false, true, false}));
}

TEST(PlotLegend, BackgroundIsNearlyOpaqueWhite) {
  TestCanvas canvas(300, 200, {0, 0, 0});
  drawLegend(canvas.context(), emptyPlot(), kEntries);
  // Inside the box's padding, left of the samples: 88 % white over black.
  const CanvasPixel inside = canvas.at(7, 7);
  EXPECT_NEAR(inside[0], 0.88 * 255, 2);
  EXPECT_EQ(canvas.at(250, 150), (CanvasPixel{0, 0, 0}));
}

TEST(PlotLegend, SamplesShowTheEntriesStyles) {
  TestCanvas canvas(300, 200);
  drawLegend(canvas.context(), emptyPlot(), kEntries);
  bool blue = false, red = false;
  const RgbImage image = canvas.image();
  for (int y = 0; y < 60; ++y) {
    for (int x = 0; x < 40; ++x) {
      const std::uint8_t* p = image.rgb.data() + (static_cast<std::size_t>(y) * 300 + x) * 3;
      blue = blue || (p[2] > 200 && p[0] < 130);
      red = red || (p[0] > 200 && p[2] < 130);
    }
  }
  EXPECT_TRUE(blue);
  EXPECT_TRUE(red);
}

}  // namespace
}  // namespace glarecam::render
