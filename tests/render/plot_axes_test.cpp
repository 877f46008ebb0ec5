#include "render/plot_axes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "test_canvas.h"

namespace glarecam::render {
namespace {

std::vector<std::string> labels(const std::vector<Tick>& ticks) {
  std::vector<std::string> out;
  for (const Tick& t : ticks) out.push_back(t.label);
  return out;
}

TEST(PlotAxes, NiceStepsAreOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_DOUBLE_EQ(niceStep(60), 10);  // six intervals of 10
  EXPECT_DOUBLE_EQ(niceStep(59), 10);
  EXPECT_DOUBLE_EQ(niceStep(7), 2);
  EXPECT_DOUBLE_EQ(niceStep(13), 5);
  EXPECT_DOUBLE_EQ(niceStep(0.3), 0.05);
  EXPECT_DOUBLE_EQ(niceStep(5e6), 1e6);
}

TEST(PlotAxes, LinearAxisRunsFromZeroToAWholeStepAboveTheData) {
  const Axis axis = linearAxisFromZero({4.86, 8.23, kNaN, -3}, 1.15, 10);
  EXPECT_EQ(axis.scale, Scale::kLinear);
  EXPECT_DOUBLE_EQ(axis.range.lo, 0);
  EXPECT_DOUBLE_EQ(axis.step, 2);  // 8.23 × 1.15 = 9.46: six intervals of about 1.6
  EXPECT_DOUBLE_EQ(axis.range.hi, 10);
  const Axis wide = linearAxisFromZero({47}, 1, 10);
  EXPECT_DOUBLE_EQ(wide.step, 10);
  EXPECT_DOUBLE_EQ(wide.range.hi, 50);
  const Axis empty = linearAxisFromZero({kNaN, 0, -1}, 1.15, 10);
  EXPECT_DOUBLE_EQ(empty.range.hi, 10);
  EXPECT_DOUBLE_EQ(empty.step, 2);
}

TEST(PlotAxes, LogAxisSpansWholeDecades) {
  const Axis axis = logAxis({5.4e5, 6e7, kNaN, 0, -5}, {1, 10});
  EXPECT_EQ(axis.scale, Scale::kLog);
  EXPECT_DOUBLE_EQ(axis.range.lo, 1e5);
  EXPECT_DOUBLE_EQ(axis.range.hi, 1e8);
  const Axis one = logAxis({3e4}, {1, 10});
  EXPECT_DOUBLE_EQ(one.range.lo, 1e4);
  EXPECT_DOUBLE_EQ(one.range.hi, 1e5);
  const Axis exact = logAxis({1e4}, {1, 10});  // at least one decade
  EXPECT_DOUBLE_EQ(exact.range.lo, 1e4);
  EXPECT_DOUBLE_EQ(exact.range.hi, 1e5);
  const Axis none = logAxis({kNaN, 0}, {1e4, 1e8});
  EXPECT_DOUBLE_EQ(none.range.lo, 1e4);
  EXPECT_DOUBLE_EQ(none.range.hi, 1e8);
}

TEST(PlotAxes, LinearTicksEveryStepUpToTheTop) {
  const std::vector<Tick> alpha = ticks({.range = {0, 90}, .step = 10});
  ASSERT_EQ(alpha.size(), 10u);
  EXPECT_DOUBLE_EQ(alpha[3].value, 30);
  EXPECT_EQ(labels(alpha),
            (std::vector<std::string>{"0", "10", "20", "30", "40", "50", "60", "70", "80", "90"}));
  // 0.3 / 0.05 is 5.999…: the top tick is there all the same, labels free of rounding noise.
  EXPECT_EQ(labels(ticks({.range = {0, 0.3}, .step = 0.05})),
            (std::vector<std::string>{"0", "0.05", "0.1", "0.15", "0.2", "0.25", "0.3"}));
  EXPECT_EQ(labels(ticks({.range = {-4, 4}, .step = 2})),
            (std::vector<std::string>{"-4", "-2", "0", "2", "4"}));
}

TEST(PlotAxes, LogTicksLabelEachDecadeWithMinorsBetween) {
  const std::vector<Tick> t = ticks({.range = {1e4, 1e6}, .scale = Scale::kLog});
  ASSERT_EQ(t.size(), 3u + 2u * 8u);
  EXPECT_DOUBLE_EQ(t[0].value, 1e4);
  EXPECT_EQ(t[0].label, "10\u2074");
  for (int m = 2; m <= 9; ++m) {
    EXPECT_DOUBLE_EQ(t[m - 1].value, m * 1e4);
    EXPECT_TRUE(t[m - 1].label.empty());
  }
  EXPECT_EQ(t[9].label, "10\u2075");
  EXPECT_EQ(t.back().label, "10\u2076");
  EXPECT_DOUBLE_EQ(t.back().value, 1e6);
  const std::vector<Tick> small = ticks({.range = {1e-3, 1e-2}, .scale = Scale::kLog});
  EXPECT_EQ(small.front().label, "10\u207b\u00b3");
  EXPECT_EQ(small.size(), 2u + 8u);
}

TEST(PlotAxes, FixedTicksReplaceTheRegularOnes) {
  const Axis days{.range = {0, 365},
                  .step = 50,
                  .fixed_ticks = {{.value = 0, .label = "Jan", .label_at = 15.5},
                                  {.value = 31, .label = "Feb", .label_at = 45}}};
  const std::vector<Tick> t = ticks(days);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(labels(t), (std::vector<std::string>{"Jan", "Feb"}));
  EXPECT_DOUBLE_EQ(*t[0].label_at, 15.5);
  EXPECT_FALSE(ticks({.range = {0, 10}, .step = 5}).front().label_at);
}

// A label between its ticks: the month's name is drawn about its middle, not under its tick.
TEST(PlotAxes, ALabelIsDrawnWhereItSaysNotAtItsTick) {
  TestCanvas canvas(400, 300);
  const Plot plot{
      .area = plotArea({0, 10, 400, 300}),
      .x = {.range = {0, 100}, .fixed_ticks = {{.value = 0, .label = "MMM", .label_at = 50}}},
      .y = {.range = {0, 1}, .step = 1}};
  drawAxes(canvas.context(), plot, {});
  const int label_top = static_cast<int>(plot.area.y1) + 4, label_bottom = label_top + 10;
  const int middle = static_cast<int>(plot.pageX(50));
  EXPECT_TRUE(canvas.anyInk(middle - 6, label_top, middle + 6, label_bottom));
  const int start = static_cast<int>(plot.pageX(0));
  EXPECT_FALSE(canvas.anyInk(start + 2, label_top, start + 12, label_bottom));
}

TEST(PlotAxes, FractionAndPlottableFollowTheScale) {
  const Axis linear{.range = {0, 10}, .step = 2};
  EXPECT_DOUBLE_EQ(linear.fraction(2.5), 0.25);
  EXPECT_DOUBLE_EQ(linear.fraction(-5), -0.5);
  EXPECT_TRUE(linear.plottable(-1));
  EXPECT_FALSE(linear.plottable(kNaN));
  EXPECT_FALSE(linear.plottable(std::numeric_limits<double>::infinity()));
  const Axis log{.range = {1e4, 1e6}, .scale = Scale::kLog};
  EXPECT_DOUBLE_EQ(log.fraction(1e5), 0.5);
  EXPECT_NEAR(log.fraction(2e4), std::log10(2) / 2, 1e-12);
  EXPECT_TRUE(log.plottable(1));
  EXPECT_FALSE(log.plottable(0));
  EXPECT_FALSE(log.plottable(-1));
}

TEST(PlotAxes, PageHasYGrowingDownward) {
  const Plot plot{.area = {100, 50, 300, 250},
                  .x = {.range = {0, 90}, .step = 10},
                  .y = {.range = {1e4, 1e6}, .scale = Scale::kLog}};
  const Point middle = plot.page(45, 1e5);
  EXPECT_DOUBLE_EQ(middle.x, 200);
  EXPECT_DOUBLE_EQ(middle.y, 150);
  EXPECT_DOUBLE_EQ(plot.pageX(0), 100);
  EXPECT_DOUBLE_EQ(plot.pageY(1e4), 250);  // bottom
  EXPECT_DOUBLE_EQ(plot.pageY(1e6), 50);   // top
}

TEST(PlotAxes, PlotAreaLeavesRoomForLabelsLeftAndBelow) {
  const Box frame{10, 20, 410, 320};
  const Box area = plotArea(frame);
  EXPECT_DOUBLE_EQ(area.y0, frame.y0);
  EXPECT_GT(area.x0, frame.x0);
  EXPECT_LT(area.x1, frame.x1);
  EXPECT_LT(area.y1, frame.y1);
  EXPECT_GT(area.x0 - frame.x0, frame.x1 - area.x1);  // tick labels and a title on the left
  EXPECT_GT(area.width(), 300);
}

TEST(PlotAxes, GridAtLabelledTicksOnlyAndLabelsOutsideTheArea) {
  TestCanvas canvas(400, 300);
  const Plot plot{.area = plotArea({0, 10.5, 400, 300}),  // the top frame line on pixel row 10
                  .x = {.range = {0, 90}, .step = 10},
                  .y = {.range = {1e4, 1e6}, .scale = Scale::kLog}};
  drawAxes(canvas.context(), plot, {.x = "x title", .y = "y title"});
  const int row_inside = static_cast<int>(plot.pageY(3e4));
  const int grid_x = static_cast<int>(plot.pageX(40));  // a 0.5 pt line centred on it
  EXPECT_LT(canvas.at(grid_x, row_inside)[0], 255);
  EXPECT_EQ(canvas.at(static_cast<int>(plot.pageX(45)), row_inside), kWhitePixel);
  const int column_inside = static_cast<int>(plot.pageX(45));
  EXPECT_LT(canvas.at(column_inside, static_cast<int>(plot.pageY(1e5)))[0], 255);
  EXPECT_EQ(canvas.at(column_inside, static_cast<int>(plot.pageY(2e5)) + 1), kWhitePixel);
  // Tick labels and titles left of and below the area, the frame around it.
  EXPECT_TRUE(canvas.anyInk(0, 0, static_cast<int>(plot.area.x0) - 4, 300));
  EXPECT_TRUE(canvas.anyInk(0, static_cast<int>(plot.area.y1) + 4, 400, 300));
  EXPECT_LT(canvas.at(column_inside, static_cast<int>(plot.area.y0))[0], 200);
}

}  // namespace
}  // namespace glarecam::render
