#include "hazard/hazard_chart.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/time.h"
#include "core/version.h"
#include "render/canvas.h"
#include "render/colour.h"
#include "render/line_style.h"
#include "render/markers.h"
#include "render/number_format.h"
#include "render/page_geometry.h"
#include "render/page_output.h"
#include "render/plot_axes.h"
#include "render/plot_legend.h"
#include "render/plot_series.h"
#include "render/rgb_surface.h"
#include "render/text.h"
#include "render/text_table.h"

namespace glarecam::hazard {
namespace {

// Drawn with the plotting toolkit (render/): its vocabulary is this file's.
using namespace render;

namespace fs = std::filesystem;

// ---- Page geometry, in PostScript points (1/72 in) ----

constexpr PageSize kPage = kA4Landscape;
constexpr double kMarginPt = 28;
constexpr double kGapPt = 10;               // below the header, between the panels
constexpr double kUpperPanelShare = 0.66;   // of the height below the header
constexpr double kRuleGapPt = 3;            // between the subtitle and the rule below it
constexpr double kStampGapPt = 22;          // between the title and the version stamp
constexpr double kThresholdLabelGapPt = 2;  // between the limit's line and its label
// Above the upper panel's data area: the top hour's tick label is centred on its edge.
constexpr double kOverhangTopPt = 5;
// The year's column beside the panels: its width, the gap before it, its bars and the room
// above them for the title and the bars' values.
constexpr double kYearColumnPt = 84;
constexpr double kYearGapPt = 12;
constexpr double kYearBarPt = 14;
constexpr double kYearBarGapPt = 5;
constexpr double kYearTitlePt = 22;
constexpr double kYearValueRoomPt = 10;
// The column's scale reaches this much above its highest limit and its highest bar.
constexpr double kYearLimitHeadroom = 1.15, kYearBarHeadroom = 1.05;

// ---- Type ----

constexpr Font kTitleFont{.size = 16, .bold = true};
constexpr Font kSubtitleFont{.size = 7.5};
constexpr Font kThresholdFont{.size = 7};
constexpr Font kYearTitleFont{.size = 7, .bold = true};
constexpr Font kYearFont{.size = 6.5};
constexpr Rgb kMutedInk{0.38, 0.38, 0.42};

// ---- Colour: Okabe–Ito's colour-blind-safe set for what glares ----

constexpr Rgb kFirstColour{0x00 / 255.0, 0x72 / 255.0, 0xB2 / 255.0};   // blue
constexpr Rgb kSecondColour{0xE6 / 255.0, 0x9F / 255.0, 0x00 / 255.0};  // orange
constexpr Rgb kBothColour{0xD5 / 255.0, 0x5E / 255.0, 0x00 / 255.0};    // vermillion
constexpr Rgb kSunDownColour{0.80, 0.81, 0.84};
constexpr Rgb kOutsideHoursColour{0.90, 0.90, 0.91};
constexpr Rgb kNoGlareColour = kWhite;

constexpr std::array<Rgb, 2> kModelColours = {kFirstColour, kSecondColour};
constexpr double kSeriesWidthPt = 1.0;
constexpr LineStyle kCriterionLineStyle{.colour = kInk, .width_pt = 0.9, .dash = Dash::kDashed};
constexpr LineStyle kYearBaselineStyle{.colour = kFrameColour, .width_pt = 0.7};
constexpr double kSwatchPt = 6.5;  // a colour's square in the legend

// ---- Cells ----

constexpr int kCellKinds = 6;
constexpr int kMaxStepsPerDay = 86400;  // 1-s steps
constexpr int kHoursPerDay = 24;

// Which of the cells aggregated into one pixel it shows: glare wins, then daylight.
constexpr std::array<int, kCellKinds> kPriority = {
    /*kNone*/ 3,        /*kFirstOnly*/ 5, /*kSecondOnly*/ 4, /*kBoth*/ 6, /*kSunDown*/ 1,
    /*kOutsideHours*/ 2};

int priority(HazardCell cell) { return kPriority[static_cast<std::size_t>(cell)]; }

bool glares(HazardCell cell) {
  return cell == HazardCell::kFirstOnly || cell == HazardCell::kSecondOnly ||
         cell == HazardCell::kBoth;
}

Rgb cellColour(HazardCell cell) {
  switch (cell) {
    case HazardCell::kFirstOnly:
      return kFirstColour;
    case HazardCell::kSecondOnly:
      return kSecondColour;
    case HazardCell::kBoth:
      return kBothColour;
    case HazardCell::kSunDown:
      return kSunDownColour;
    case HazardCell::kOutsideHours:
      return kOutsideHoursColour;
    case HazardCell::kNone:
      break;
  }
  return kNoGlareColour;
}

// Legend ink of a pixel showing `cell`: the legend goes over the night rather than the day, and
// never over glare.
double inkWeight(HazardCell cell) {
  constexpr double kGlareWeight = 12, kDaylightWeight = 1;
  return glares(cell) ? kGlareWeight : cell == HazardCell::kSunDown ? 0 : kDaylightWeight;
}

// ---- Calendar ----

// Ticks at the first day of each month, each month's name centred between its ticks.
std::vector<Tick> monthTicks(int year) {
  constexpr std::array<const char*, 12> kNames = {"Jan", "Feb", "Mar", "Apr", "May", "Jun",
                                                  "Jul", "Aug", "Sep", "Oct", "Nov", "Dec"};
  std::vector<Tick> ticks;
  int first_day = 0;
  for (std::size_t m = 0; m < kNames.size(); ++m) {
    const int length = daysInMonth(year, static_cast<int>(m) + 1);
    ticks.push_back({.value = static_cast<double>(first_day),
                     .label = kNames[m],
                     .label_at = first_day + length / 2.0});
    first_day += length;
  }
  return ticks;
}

// ---- The hours shown ----

struct HourRange {
  int from_h = 0, to_h = kHoursPerDay;
  int span() const { return to_h - from_h; }
};

// Whole hours around every cell with the sun up; the whole day when the sun never rises.
HourRange shownHours(const HazardChartContent& c) {
  int first = c.steps_per_day, last = -1;
  for (int day = 0; day < c.days; ++day) {
    const HazardCell* cells = c.cells.data() + static_cast<std::size_t>(day) * c.steps_per_day;
    for (int step = 0; step < c.steps_per_day; ++step) {
      if (cells[step] == HazardCell::kSunDown) continue;
      first = std::min(first, step);
      last = std::max(last, step);
    }
  }
  if (last < 0) return {};
  const auto hours = [&c](int step) {
    return static_cast<double>(step) * kHoursPerDay / c.steps_per_day;
  };
  const int from = static_cast<int>(std::floor(hours(first)));
  const int to = static_cast<int>(std::ceil(hours(last + 1)));
  return {from, std::max(to, from + 1)};
}

// "06:00" at every hour a multiple of the step apart (1, 2 or 3 h: six to twelve labels), and a
// minor tick at each other whole hour.
std::vector<Tick> hourTicks(const HourRange& hours) {
  const int step = hours.span() <= 6 ? 1 : hours.span() <= 16 ? 2 : 3;
  std::vector<Tick> ticks;
  for (int h = hours.from_h; h <= hours.to_h; ++h)
    ticks.push_back({.value = static_cast<double>(h),
                     .label = h % step == 0 ? fmt::format("{:02d}:00", h) : std::string()});
  return ticks;
}

// ---- The cell raster ----

// The cells of the shown hours aggregated into `rows` pixel rows a day (the top row the latest),
// one pixel column a day.
struct CellRaster {
  int columns = 0, rows = 0;
  double from_h = 0, to_h = 0;  // the hours the rows span (whole steps: may exceed those shown)
  std::vector<HazardCell> pixels{};  // row-major, top row first
  HazardCell at(int column, int row) const {
    return pixels[static_cast<std::size_t>(row) * columns + column];
  }
};

CellRaster rasterise(const HazardChartContent& c, const HourRange& hours, int max_rows) {
  const int first_step = static_cast<int>(
      std::floor(static_cast<double>(hours.from_h) * c.steps_per_day / kHoursPerDay));
  const int end_step =
      static_cast<int>(std::ceil(static_cast<double>(hours.to_h) * c.steps_per_day / kHoursPerDay));
  const int steps = end_step - first_step;
  CellRaster raster{.columns = c.days,
                    .rows = std::max(1, std::min(steps, max_rows)),
                    .from_h = static_cast<double>(first_step) * kHoursPerDay / c.steps_per_day,
                    .to_h = static_cast<double>(end_step) * kHoursPerDay / c.steps_per_day};
  raster.pixels.assign(static_cast<std::size_t>(raster.columns) * raster.rows,
                       HazardCell::kSunDown);
  for (int day = 0; day < c.days; ++day) {
    const HazardCell* cells = c.cells.data() + static_cast<std::size_t>(day) * c.steps_per_day;
    for (int b = 0; b < raster.rows; ++b) {  // b: rows from the bottom
      const std::int64_t from = first_step + static_cast<std::int64_t>(b) * steps / raster.rows;
      const std::int64_t to = first_step + static_cast<std::int64_t>(b + 1) * steps / raster.rows;
      HazardCell shown = HazardCell::kSunDown;
      for (std::int64_t step = from; step < to; ++step)
        if (priority(cells[step]) > priority(shown)) shown = cells[step];
      raster.pixels[static_cast<std::size_t>(raster.rows - 1 - b) * raster.columns + day] = shown;
    }
  }
  return raster;
}

// The raster's colours as an image of its size.
RgbImage rasterImage(const CellRaster& raster) {
  std::array<std::array<std::uint8_t, 3>, kCellKinds> colours{};
  for (int kind = 0; kind < kCellKinds; ++kind)
    colours[kind] = rgbBytes(cellColour(static_cast<HazardCell>(kind)));
  RgbImage image{.width = raster.columns, .height = raster.rows, .rgb = {}};
  image.rgb.reserve(static_cast<std::size_t>(raster.columns) * raster.rows * 3);
  for (int row = 0; row < raster.rows; ++row)
    for (int column = 0; column < raster.columns; ++column) {
      const std::array<std::uint8_t, 3>& colour =
          colours[static_cast<std::size_t>(raster.at(column, row))];
      image.rgb.insert(image.rgb.end(), colour.begin(), colour.end());
    }
  return image;
}

// ---- Layout ----

struct Layout {
  Box header;
  Box body;  // the panels and the year's column
};

struct BodyLayout {
  Box upper, lower;         // the panels' frames (data area, ticks and titles)
  std::optional<Box> year;  // the year's column, beside both panels
};

// The box shrunk to whole pixels of the PNG, so that the cell raster's rows meet them exactly.
Box snappedToPixels(const Box& box) {
  const auto down = [](double v) { return std::floor(v * kPngPixelsPerPt) / kPngPixelsPerPt; };
  const auto up = [](double v) { return std::ceil(v * kPngPixelsPerPt) / kPngPixelsPerPt; };
  return {up(box.x0), up(box.y0), down(box.x1), down(box.y1)};
}

std::vector<std::string> subtitleLines(Canvas& canvas, const HazardChartContent& c, double width) {
  return c.subtitle.empty() ? std::vector<std::string>{}
                            : wrapText(canvas, c.subtitle, width, kSubtitleFont);
}

Layout pageLayout(Canvas& canvas, const HazardChartContent& c) {
  const Box page{kMarginPt, kMarginPt, kPage.width_pt - kMarginPt, kPage.height_pt - kMarginPt};
  const double subtitle_pt = static_cast<double>(subtitleLines(canvas, c, page.width()).size()) *
                             lineHeight(kSubtitleFont);
  const double header_bottom = page.y0 + lineHeight(kTitleFont) + subtitle_pt + kRuleGapPt;
  return {.header = {page.x0, page.y0, page.x1, header_bottom},
          .body = {page.x0, header_bottom + kGapPt - kOverhangTopPt, page.x1, page.y1}};
}

// `frame` holds everything drawn: the panels start below the top tick label's overhang.
BodyLayout bodyLayout(const Box& frame, bool with_year) {
  const Box body{frame.x0, frame.y0 + kOverhangTopPt, frame.x1, frame.y1};
  const double split = body.y0 + (body.y1 - body.y0 - kGapPt) * kUpperPanelShare;
  const double right = with_year ? body.x1 - kYearColumnPt - kYearGapPt : body.x1;
  BodyLayout layout{.upper = {body.x0, body.y0, right, split},
                    .lower = {body.x0, split + kGapPt, right, body.y1},
                    .year = std::nullopt};
  if (with_year) layout.year = Box{body.x1 - kYearColumnPt, body.y0, body.x1, body.y1};
  return layout;
}

// ---- Header ----

void drawHeader(Canvas& canvas, const HazardChartContent& c, const Box& box) {
  const std::string stamp = fmt::format("glarecam {}", kVersion);
  const double title_baseline = box.y0 + kTitleFont.size;
  drawText(canvas, {box.x1, title_baseline}, stamp, {kSubtitleFont, kMutedInk, Align::kRight});
  const std::string title = c.title.empty() ? std::string("Glare hazard") : c.title;
  const double room = box.width() - textWidth(canvas, stamp, kSubtitleFont) - kStampGapPt;
  const double scale = std::min(1.0, room / textWidth(canvas, title, kTitleFont));
  drawText(canvas, {box.x0, title_baseline}, title, {{kTitleFont.size * scale, true}});
  double baseline = box.y0 + lineHeight(kTitleFont) + kSubtitleFont.size;
  for (const std::string& line : subtitleLines(canvas, c, box.width())) {
    drawText(canvas, {box.x0, baseline}, line, {kSubtitleFont, kMutedInk});
    baseline += lineHeight(kSubtitleFont);
  }
  drawSegment(canvas, {box.x0, box.y1}, {box.x1, box.y1}, kRuleStyle);
}

// ---- Upper panel: the cells ----

Axis dayAxis(const HazardChartContent& c) {
  return {.range = {0, static_cast<double>(c.days)}, .fixed_ticks = monthTicks(c.year)};
}

MarkerStyle swatch(const Rgb& colour) {
  return {.colour = colour, .shape = MarkerShape::kSquare, .size_pt = kSwatchPt};
}

std::vector<LegendEntry> cellLegend(const HazardChartContent& c, const CellRaster& raster) {
  std::array<bool, kCellKinds> shown{};
  for (const HazardCell cell : raster.pixels) shown[static_cast<std::size_t>(cell)] = true;
  const auto entry = [](const std::string& label, const Rgb& colour) {
    return LegendEntry{label, std::nullopt, swatch(colour)};
  };
  std::vector<LegendEntry> legend;
  if (c.models.size() == 1) {
    legend.push_back(entry("glare", kFirstColour));
  } else {
    legend.push_back(entry(c.models[0].label + " only", kFirstColour));
    legend.push_back(entry(c.models[1].label + " only", kSecondColour));
    legend.push_back(entry("both", kBothColour));
  }
  legend.push_back({"no glare", std::nullopt,
                    MarkerStyle{.colour = kFrameColour,
                                .shape = MarkerShape::kSquare,
                                .size_pt = kSwatchPt,
                                .hollow = true}});
  if (shown[static_cast<std::size_t>(HazardCell::kOutsideHours)])
    legend.push_back(entry("outside the observer's hours", kOutsideHoursColour));
  if (shown[static_cast<std::size_t>(HazardCell::kSunDown)])
    legend.push_back(entry("sun below the horizon", kSunDownColour));
  return legend;
}

void drawCellPanel(Canvas& canvas, const HazardChartContent& c, const Box& frame) {
  const HourRange hours = shownHours(c);
  Plot plot{.area = snappedToPixels(plotArea(frame)),
            .x = dayAxis(c),
            .y = {.range = {static_cast<double>(hours.from_h), static_cast<double>(hours.to_h)},
                  .fixed_ticks = hourTicks(hours)}};
  // One pixel row of the PNG per raster row at most, so that each row shows in the PNG.
  const int max_rows = static_cast<int>(std::lround(plot.area.height() * kPngPixelsPerPt));
  const CellRaster raster = rasterise(c, hours, max_rows);
  const RgbImage image = rasterImage(raster);

  // The axes first: the cells hide the grid, which would hide a glaring pixel row.
  drawAxes(canvas, plot, {.x = "", .y = "time of day (local standard time)"});
  const double top = plot.pageY(raster.to_h), bottom = plot.pageY(raster.from_h);
  {
    const Canvas::Saved saved = canvas.save();
    canvas.rectangle(plot.area);
    canvas.clip();
    canvas.translate(plot.area.x0, top);
    canvas.scale(plot.area.width() / raster.columns, (bottom - top) / raster.rows);
    canvas.paintImage(image);
  }

  const double column_pt = plot.area.width() / raster.columns;
  const double row_pt = (bottom - top) / raster.rows;
  for (int row = 0; row < raster.rows; ++row)
    for (int column = 0; column < raster.columns; ++column)
      if (const double weight = inkWeight(raster.at(column, row)); weight > 0)
        plot.ink.push_back(
            {{plot.area.x0 + (column + 0.5) * column_pt, top + (row + 0.5) * row_pt}, weight});

  drawFrame(canvas, plot);
  drawLegend(canvas, plot, cellLegend(c, raster));
}

// ---- Lower panel: minutes per day ----

// "ellipse: 48 days, ≤ 23 min/day, 11.2 h/year": short, so that the legend hides little.
std::string seriesLabel(const HazardChartSeries& s) {
  const auto glaring = std::count_if(s.minutes_per_day.begin(), s.minutes_per_day.end(),
                                     [](double m) { return m > 0; });
  if (glaring == 0) return s.label + ": no glare";
  double total = 0, most = 0;
  for (const double m : s.minutes_per_day) {
    total += m;
    most = std::max(most, m);
  }
  constexpr double kMinutesPerHour = 60;
  return fmt::format("{}: {} day{}, \u2264 {} min/day, {:.1f} h/year", s.label, glaring,
                     glaring == 1 ? "" : "s", formatFixed(most, most >= 10 ? 0 : 1),
                     total / kMinutesPerHour);
}

// Returns the data area (the year's column stands on its zero line).
Box drawMinutesPanel(Canvas& canvas, const HazardChartContent& c, const Box& frame) {
  double most = 0;
  for (const HazardChartSeries& s : c.models)
    for (const double m : s.minutes_per_day) most = std::max(most, m);
  constexpr double kThresholdHeadroom = 1.2, kDataHeadroom = 1.1;
  const double top =
      std::max(c.threshold_minutes_per_day * kThresholdHeadroom, most * kDataHeadroom);
  Plot plot{.area = snappedToPixels(plotArea(frame)),
            .x = dayAxis(c),
            .y = {.range = {0, top}, .step = niceStep(top)}};
  drawAxes(canvas, plot, {.x = fmt::format("day of the year {}", c.year), .y = "glare (min/day)"});

  const double limit = c.threshold_minutes_per_day;
  drawCurve(
      canvas, plot, [limit](double) { return limit; }, plot.x.range, kCriterionLineStyle);
  const std::string limit_label = fmt::format("{} min/day", formatPlain(limit));
  const Point label_end{plot.area.x1 - kThresholdLabelGapPt,
                        plot.pageY(limit) - kThresholdLabelGapPt};
  drawText(canvas, label_end, limit_label, {kThresholdFont, kInk, Align::kRight});
  // The label is ink the legend keeps off, like a marker.
  constexpr double kLabelInkWeight = 12;
  const double label_width = textWidth(canvas, limit_label, kThresholdFont);
  for (const double along : {0.0, 0.5, 1.0})
    plot.ink.push_back({{label_end.x - along * label_width, label_end.y - kThresholdFont.size / 2},
                        kLabelInkWeight});

  std::vector<LegendEntry> legend;
  // The second model first: the method's (first) line stays on top where they coincide.
  for (std::size_t i = c.models.size(); i-- > 0;) {
    const HazardChartSeries& s = c.models[i];
    std::vector<DataPoint> points;
    for (std::size_t day = 0; day < s.minutes_per_day.size(); ++day)
      points.push_back({static_cast<double>(day) + 0.5, s.minutes_per_day[day]});
    const LineStyle style{.colour = kModelColours[i], .width_pt = kSeriesWidthPt};
    drawLine(canvas, plot, points, style);
  }
  for (std::size_t i = 0; i < c.models.size(); ++i)
    legend.push_back({seriesLabel(c.models[i]),
                      LineStyle{.colour = kModelColours[i], .width_pt = kSeriesWidthPt},
                      std::nullopt});
  drawLegend(canvas, plot, legend);
  return plot.area;
}

// ---- The year's column: hours per year against the yearly limits ----

double hoursPerYear(const HazardChartSeries& s) {
  constexpr double kMinutesPerHour = 60;
  double total = 0;
  for (const double m : s.minutes_per_day) total += m;
  return total / kMinutesPerHour;
}

// "142 h" from 10 h on, "8.3 h" below: narrow enough to stand over a bar.
std::string hoursText(double hours) { return formatFixed(hours, hours >= 10 ? 0 : 1) + " h"; }

// One label per distinct limit ("LAI/CH 30 h" when both are 30 h), lowest first.
std::vector<HazardChartLimit> mergedLimits(const std::vector<HazardChartLimit>& limits) {
  std::vector<HazardChartLimit> merged;
  for (const HazardChartLimit& limit : limits) {
    const auto same = std::find_if(merged.begin(), merged.end(), [&](const HazardChartLimit& m) {
      return m.hours_per_year == limit.hours_per_year;
    });
    if (same == merged.end()) {
      merged.push_back(limit);
    } else {
      same->label += "/" + limit.label;
    }
  }
  std::sort(merged.begin(), merged.end(), [](const HazardChartLimit& a, const HazardChartLimit& b) {
    return a.hours_per_year < b.hours_per_year;
  });
  return merged;
}

// `column` from the top of the upper panel to the bottom of the lower one; the bars stand on
// `baseline_y`, the lower panel's zero line. The scale runs from 0 at the baseline to above the
// highest limit and the highest bar, with no ticks: each bar carries its value, each limit its
// label.
void drawYearColumn(Canvas& canvas, const HazardChartContent& c, const Box& column,
                    double baseline_y) {
  drawText(canvas, {column.x0, column.y0 + kYearTitleFont.size}, "glare per year",
           {kYearTitleFont, kInk, Align::kLeft});
  drawText(canvas, {column.x0, column.y0 + kYearTitleFont.size + lineHeight(kYearFont)},
           "h/year, yearly limits", {kYearFont, kMutedInk, Align::kLeft});

  const std::vector<HazardChartLimit> limits = mergedLimits(c.yearly_limits);
  std::vector<double> hours;
  double top_hours = limits.back().hours_per_year * kYearLimitHeadroom;
  for (const HazardChartSeries& s : c.models) {
    hours.push_back(hoursPerYear(s));
    top_hours = std::max(top_hours, hours.back() * kYearBarHeadroom);
  }
  const double area_top = column.y0 + kYearTitlePt + kYearValueRoomPt;
  const auto y_of = [&](double h) { return baseline_y - h / top_hours * (baseline_y - area_top); };
  const double bars_x0 = column.x0 + kYearBarGapPt;
  const double bars_x1 = bars_x0 + static_cast<double>(hours.size()) * (kYearBarPt + kYearBarGapPt);

  for (std::size_t i = 0; i < hours.size(); ++i) {
    const double x0 = bars_x0 + static_cast<double>(i) * (kYearBarPt + kYearBarGapPt);
    const double y = y_of(hours[i]);
    canvas.rectangle({x0, y}, kYearBarPt, baseline_y - y);
    canvas.setColour(kModelColours[i]);
    canvas.fill();
    drawText(canvas, {x0 + kYearBarPt / 2, y - kThresholdLabelGapPt}, hoursText(hours[i]),
             {kYearFont, kInk, Align::kCentre});
  }
  drawSegment(canvas, {column.x0, baseline_y}, {bars_x1, baseline_y}, kYearBaselineStyle);

  // The limits over the bars, their labels right of them, pushed apart upward when closer
  // than a line.
  double last_label_y = baseline_y + lineHeight(kYearFont);
  for (const HazardChartLimit& limit : limits) {
    const double y = y_of(limit.hours_per_year);
    drawSegment(canvas, {column.x0, y}, {bars_x1, y}, kCriterionLineStyle);
    const double label_y =
        std::min(y + kBaselineBelowMiddleEm * kYearFont.size, last_label_y - lineHeight(kYearFont));
    drawText(canvas, {bars_x1 + kThresholdLabelGapPt, label_y},
             fmt::format("{} {} h", limit.label, formatPlain(limit.hours_per_year)),
             {kYearFont, kInk, Align::kLeft});
    last_label_y = label_y;
  }
}

void drawBody(Canvas& canvas, const HazardChartContent& c, const Box& body) {
  const BodyLayout layout = bodyLayout(body, !c.yearly_limits.empty());
  drawCellPanel(canvas, c, layout.upper);
  const Box minutes_area = drawMinutesPanel(canvas, c, layout.lower);
  if (layout.year) drawYearColumn(canvas, c, *layout.year, minutes_area.y1);
}

// ---- The page ----

void drawChart(Canvas& canvas, const HazardChartContent& c) {
  paint(canvas, kWhite);
  const Layout layout = pageLayout(canvas, c);
  drawHeader(canvas, c, layout.header);
  drawBody(canvas, c, layout.body);
  // Over everything: the cell panel is an opaque raster that would hide a mark drawn under it.
  if (!c.mark.empty()) drawPageMark(canvas, kPage, c.mark, c.mark_note, /*over=*/true);
}

// ---- Validation ----

Status validate(const HazardChartContent& c) {
  const auto refuse = [&c](const std::string& problem) {
    return badInput(fmt::format("hazard chart \"{}\": {}", c.title, problem));
  };
  if (c.days != 365 && c.days != 366)
    return refuse(fmt::format("a year has 365 or 366 days, not {}", c.days));
  if (c.days != daysInYear(c.year))
    return refuse(fmt::format("{} has {} days, not {}", c.year, daysInYear(c.year), c.days));
  if (c.steps_per_day < 1 || c.steps_per_day > kMaxStepsPerDay)
    return refuse(fmt::format("{} steps a day: must be 1 to {}", c.steps_per_day, kMaxStepsPerDay));
  const std::size_t expected = static_cast<std::size_t>(c.days) * c.steps_per_day;
  if (c.cells.size() != expected)
    return refuse(fmt::format("{} cells, but {} days of {} steps are {}", c.cells.size(), c.days,
                              c.steps_per_day, expected));
  if (c.models.empty() || c.models.size() > 2)
    return refuse(fmt::format("1 or 2 models, not {}", c.models.size()));
  for (const HazardChartSeries& s : c.models) {
    if (s.minutes_per_day.size() != static_cast<std::size_t>(c.days))
      return refuse(fmt::format("model \"{}\" has {} days of minutes, not {}", s.label,
                                s.minutes_per_day.size(), c.days));
    for (std::size_t day = 0; day < s.minutes_per_day.size(); ++day)
      if (!(std::isfinite(s.minutes_per_day[day]) && s.minutes_per_day[day] >= 0))
        return refuse(fmt::format("model \"{}\": {} minutes on day {}", s.label,
                                  s.minutes_per_day[day], day + 1));
  }
  if (!(std::isfinite(c.threshold_minutes_per_day) && c.threshold_minutes_per_day > 0))
    return refuse(fmt::format("the daily limit must be positive, not {} minutes",
                              c.threshold_minutes_per_day));
  for (const HazardChartLimit& limit : c.yearly_limits) {
    if (limit.label.empty()) return refuse("a yearly limit without a label");
    if (!(std::isfinite(limit.hours_per_year) && limit.hours_per_year > 0))
      return refuse(fmt::format("the yearly limit \"{}\" must be positive, not {} hours",
                                limit.label, limit.hours_per_year));
  }
  for (std::size_t i = 0; i < c.cells.size(); ++i) {
    const auto value = static_cast<int>(c.cells[i]);
    const bool second = c.cells[i] == HazardCell::kSecondOnly || c.cells[i] == HazardCell::kBoth;
    if (value >= kCellKinds || (second && c.models.size() == 1))
      return refuse(fmt::format(
          "cell {} of day {} is {}{}", i % c.steps_per_day, i / c.steps_per_day + 1, value,
          value < kCellKinds ? ", a second model's glare, with one model" : ", not a cell kind"));
  }
  return {};
}

}  // namespace

Status writeHazardChart(const HazardChartContent& content, const fs::path& png_path,
                        const fs::path& svg_path) {
  GLARECAM_CHECK(validate(content));
  const PageDrawing draw = [&content](Canvas& canvas) { drawChart(canvas, content); };
  GLARECAM_CHECK(writePngPage(png_path, kPage, draw));
  return writeSvgPage(svg_path, kPage, draw);
}

Status drawHazardChart(Canvas& canvas, const Box& frame, const HazardChartContent& content) {
  GLARECAM_CHECK(validate(content));
  drawBody(canvas, content, frame);
  return canvas.status();
}

}  // namespace glarecam::hazard
