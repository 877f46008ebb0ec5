#include "render/plot_series.h"

#include <gtest/gtest.h>

#include <limits>

#include "test_canvas.h"

namespace glarecam::render {
namespace {

constexpr LineStyle kBlackLine{.colour = {0, 0, 0}, .width_pt = 3};

// 0–100 on both axes over a 100 × 100 area at (50, 50) of a 200 × 200 canvas: one unit a pixel.
Plot linearPlot() {
  return {.area = {50, 50, 150, 150},
          .x = {.range = {0, 100}, .step = 10},
          .y = {.range = {0, 100}, .step = 10}};
}

TEST(PlotSeries, SampleSpansTheRangeEvenly) {
  const std::vector<double> v = sample([](double x) { return 2 * x; }, {10, 20});
  ASSERT_EQ(v.size(), static_cast<std::size_t>(kCurveSamples + 1));
  EXPECT_DOUBLE_EQ(v.front(), 20);
  EXPECT_DOUBLE_EQ(v[kCurveSamples / 2], 30);
  EXPECT_DOUBLE_EQ(v.back(), 40);
  EXPECT_TRUE(sample([](double x) { return x; }, {5, 5}).empty());
  EXPECT_TRUE(sample([](double x) { return x; }, {5, 1}).empty());
}

TEST(PlotSeries, CurveFollowsTheFunctionOnThePage) {
  TestCanvas canvas(200, 200);
  Plot plot = linearPlot();
  drawCurve(
      canvas.context(), plot, [](double) { return 30.0; }, {0, 100}, kBlackLine);
  EXPECT_EQ(canvas.at(100, static_cast<int>(plot.pageY(30))), (CanvasPixel{0, 0, 0}));
  EXPECT_EQ(canvas.at(100, static_cast<int>(plot.pageY(40))), kWhitePixel);
  EXPECT_EQ(plot.ink.size(), static_cast<std::size_t>(kCurveSamples + 1));
}

TEST(PlotSeries, CurveBreaksWhereTheFunctionIsUndefined) {
  TestCanvas canvas(200, 200);
  Plot plot = linearPlot();
  const auto gap = [](double x) { return x > 40 && x < 60 ? kNaN : 50.0; };
  drawCurve(canvas.context(), plot, gap, {0, 100}, kBlackLine);
  const int y = static_cast<int>(plot.pageY(50));
  EXPECT_EQ(canvas.at(static_cast<int>(plot.pageX(20)), y), (CanvasPixel{0, 0, 0}));
  EXPECT_EQ(canvas.at(static_cast<int>(plot.pageX(50)), y), kWhitePixel);
  EXPECT_EQ(canvas.at(static_cast<int>(plot.pageX(80)), y), (CanvasPixel{0, 0, 0}));
  EXPECT_LT(plot.ink.size(), static_cast<std::size_t>(kCurveSamples + 1));
}

TEST(PlotSeries, CurveIsClippedToTheDataArea) {
  TestCanvas canvas(200, 200);
  Plot plot = linearPlot();
  drawCurve(
      canvas.context(), plot, [](double x) { return 2 * x; }, {0, 100}, kBlackLine);
  EXPECT_EQ(canvas.at(static_cast<int>(plot.pageX(25)), static_cast<int>(plot.pageY(50))),
            (CanvasPixel{0, 0, 0}));
  // y = 2x leaves the area at x = 50; off the area nothing is drawn.
  EXPECT_FALSE(canvas.anyInk(0, 0, 200, 49));
  EXPECT_FALSE(canvas.anyInk(151, 0, 200, 200));
}

TEST(PlotSeries, NonPositiveValuesAreSkippedOnALogAxis) {
  TestCanvas canvas(200, 200);
  Plot plot = linearPlot();
  plot.y = {.range = {1, 100}, .scale = Scale::kLog};
  drawCurve(
      canvas.context(), plot, [](double x) { return x - 50; }, {0, 100}, kBlackLine);
  EXPECT_EQ(plot.ink.size(), static_cast<std::size_t>(kCurveSamples / 2));  // x > 50 only
  for (const Ink& ink : plot.ink) EXPECT_GT(ink.at.x, plot.pageX(50));
}

TEST(PlotSeries, MarkersAtPlottablePointsWeighMoreThanCurves) {
  TestCanvas canvas(200, 200);
  Plot plot = linearPlot();
  drawCurve(
      canvas.context(), plot, [](double) { return 90.0; }, {0, 100}, kBlackLine);
  const std::size_t curve_ink = plot.ink.size();
  drawMarkers(canvas.context(), plot, {{20, 20}, {80, kNaN}, {60, 40}},
              {.colour = {1, 0, 0}, .size_pt = 10});
  ASSERT_EQ(plot.ink.size(), curve_ink + 2);
  EXPECT_GT(plot.ink.back().weight, plot.ink.front().weight);
  EXPECT_DOUBLE_EQ(plot.ink.back().at.x, plot.pageX(60));
  EXPECT_DOUBLE_EQ(plot.ink.back().at.y, plot.pageY(40));
  EXPECT_EQ(canvas.at(static_cast<int>(plot.pageX(20)), static_cast<int>(plot.pageY(20))),
            (CanvasPixel{255, 0, 0}));
}

// A series keeps every point (a one-day peak is not sampled away) and breaks where one is NaN.
TEST(PlotSeries, LineJoinsEveryPointAndBreaksAtUnplottableOnes) {
  TestCanvas canvas(200, 200);
  Plot plot = linearPlot();
  std::vector<DataPoint> points;
  for (int x = 0; x <= 100; ++x) points.push_back({x + 0.0, x == 37 ? 80.0 : 10.0});
  points[70].y = kNaN;
  drawLine(canvas.context(), plot, points, kBlackLine);
  EXPECT_EQ(plot.ink.size(), points.size() - 1);
  EXPECT_EQ(canvas.at(static_cast<int>(plot.pageX(37)), static_cast<int>(plot.pageY(79))),
            (CanvasPixel{0, 0, 0}));
  EXPECT_EQ(canvas.at(static_cast<int>(plot.pageX(20)), static_cast<int>(plot.pageY(10))),
            (CanvasPixel{0, 0, 0}));
  EXPECT_EQ(canvas.at(static_cast<int>(plot.pageX(70)), static_cast<int>(plot.pageY(10))),
            kWhitePixel);
}

}  // namespace
}  // namespace glarecam::render
