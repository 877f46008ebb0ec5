#include "pipeline/render/datasheet.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <span>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "core/atomic_file.h"
#include "core/version.h"
#include "pipeline/facet_model.h"
#include "pipeline/glare_profile.h"
#include "pipeline/limit_curve.h"

namespace glarecam::pipeline {
namespace {

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- Page geometry, in PostScript points (1/72 in) ----

constexpr double kPageWidthPt = 842;  // A4 landscape
constexpr double kPageHeightPt = 595;
constexpr double kPngPixelsPerPt = 2;  // the raster preview at 144 dpi
constexpr double kMarginPt = 28;
constexpr double kHeaderHeightPt = 40;
constexpr double kGapPt = 10;         // between blocks
constexpr double kSectionGapPt = 15;  // between the two tables
constexpr double kColumnGapPt = 22;   // between the plots and the tables
constexpr double kPlotColumnWidthPt = 400;
constexpr double kBlockTitleHeightPt = 18;  // a plot's or table's title, above it
constexpr double kYAxisGutterPt = 44;       // left of a data area: tick labels, rotated title
constexpr double kXAxisGutterPt = 28;       // below a data area: tick labels, title
constexpr double kRightPaddingPt = 6;       // right of a data area
constexpr double kTickLengthPt = 3.5;
constexpr double kMinorTickLengthPt = 2;
constexpr double kTickLabelGapPt = 2;  // between a tick and its label

// ---- Type ----

constexpr const char* kFontFamily = "DejaVu Sans";
struct Font {
  double size_pt = 0;
  bool bold = false;
};
constexpr Font kTitleFont{.size_pt = 16, .bold = true};
constexpr Font kSubtitleFont{.size_pt = 7.5};
constexpr Font kSectionFont{.size_pt = 9.5, .bold = true};
constexpr Font kTickFont{.size_pt = 7.5};
constexpr Font kAxisTitleFont{.size_pt = 8};
constexpr Font kLegendFont{.size_pt = 7};
constexpr Font kTableFont{.size_pt = 8.5};
constexpr Font kNoteFont{.size_pt = 6.8};
constexpr double kLineSpacing = 1.3;             // baseline to baseline, in font sizes
constexpr double kBaselineBelowMiddleEm = 0.35;  // centres digits and lower case on a point
constexpr double kTableLineSpacing = 1.2;        // table rows are striped: they can sit closer

// ---- Colour and lines ----

struct Rgb {
  double r = 0, g = 0, b = 0;
};
constexpr Rgb kInk{0.10, 0.10, 0.12};
constexpr Rgb kMutedInk{0.38, 0.38, 0.42};
constexpr Rgb kWhite{1, 1, 1};
constexpr Rgb kGridColour{0.88, 0.88, 0.90};
constexpr Rgb kFrameColour{0.45, 0.45, 0.48};
constexpr Rgb kStripeColour{0.95, 0.95, 0.96};
constexpr Rgb kBlue{0.12, 0.38, 0.68};
constexpr Rgb kOrange{0.88, 0.45, 0.05};
constexpr Rgb kRed{0.80, 0.12, 0.12};
constexpr Rgb kGreen{0.13, 0.55, 0.25};
constexpr Rgb kModelGrey{0.55, 0.55, 0.58};
constexpr double kExtrapolationLightening = 0.45;  // toward white

enum class Dash { kSolid, kDashed, kLongDashed, kDotted };
struct LineStyle {
  Rgb colour;
  double width_pt = 1.2;
  Dash dash = Dash::kSolid;
};
constexpr LineStyle kLimitStyle{.colour = kRed, .width_pt = 1.3, .dash = Dash::kDashed};
constexpr LineStyle kCosineStyle{.colour = kBlue, .width_pt = 1.3};
constexpr LineStyle kBiquadraticStyle{.colour = kOrange, .width_pt = 1.3};
constexpr LineStyle kVerticalStyle{.colour = kBlue, .width_pt = 1.3};
constexpr LineStyle kHorizontalStyle{.colour = kGreen, .width_pt = 1.3};
constexpr LineStyle kModelNsStyle{.colour = kModelGrey, .width_pt = 0.8, .dash = Dash::kLongDashed};
constexpr LineStyle kModelEwStyle{.colour = kModelGrey, .width_pt = 0.8, .dash = Dash::kDashed};
constexpr LineStyle kExtrapolationKeyStyle{
    .colour = kModelGrey, .width_pt = 1.0, .dash = Dash::kDotted};
constexpr LineStyle kGridStyle{.colour = kGridColour, .width_pt = 0.5};
constexpr LineStyle kFrameStyle{.colour = kFrameColour, .width_pt = 0.7};
constexpr LineStyle kRuleStyle{.colour = kFrameColour, .width_pt = 0.6};

enum class MarkerShape { kCircle, kSquare };
struct MarkerStyle {
  Rgb colour;
  MarkerShape shape = MarkerShape::kCircle;
  double size_pt = 4.6;  // diameter or side
  bool hollow = false;   // an outline only: a value that is only a bound
};
constexpr MarkerStyle kLmaxMarker{.colour = kInk};
constexpr MarkerStyle kLmaxBoundMarker{.colour = kInk, .hollow = true};
constexpr MarkerStyle kVerticalMarker{.colour = kBlue};
constexpr MarkerStyle kHorizontalMarker{
    .colour = kGreen, .shape = MarkerShape::kSquare, .size_pt = 4.2};

// ---- Small geometry ----

struct Point {
  double x = 0, y = 0;
};
struct Box {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
  bool contains(Point p) const { return p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1; }
};
struct Range {
  double lo = 0, hi = 0;
  bool empty() const { return !(hi > lo); }
};

// ---- Text ----

enum class Align { kLeft, kCentre, kRight };
struct TextStyle {
  Font font;
  Rgb colour = kInk;
  Align align = Align::kLeft;
};

void setColour(cairo_t* cr, const Rgb& colour) {
  cairo_set_source_rgb(cr, colour.r, colour.g, colour.b);
}

void setFont(cairo_t* cr, const Font& font) {
  cairo_select_font_face(cr, kFontFamily, CAIRO_FONT_SLANT_NORMAL,
                         font.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, font.size_pt);
}

double textWidthPt(cairo_t* cr, const std::string& text, const Font& font) {
  setFont(cr, font);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text.c_str(), &extents);
  return extents.x_advance;
}

double lineHeightPt(const Font& font) { return font.size_pt * kLineSpacing; }

void drawText(cairo_t* cr, Point baseline, const std::string& text, const TextStyle& style) {
  const double width = textWidthPt(cr, text, style.font);
  const double shift = style.align == Align::kLeft     ? 0
                       : style.align == Align::kCentre ? width / 2
                                                       : width;
  setColour(cr, style.colour);
  cairo_move_to(cr, baseline.x - shift, baseline.y);
  cairo_show_text(cr, text.c_str());
}

// Text centred on `centre` (its baseline through it), reading bottom to top.
void drawVerticalText(cairo_t* cr, Point centre, const std::string& text, const TextStyle& style) {
  cairo_save(cr);
  cairo_translate(cr, centre.x, centre.y);
  cairo_rotate(cr, -std::numbers::pi / 2);
  drawText(cr, {0, 0}, text, {style.font, style.colour, Align::kCentre});
  cairo_restore(cr);
}

// Greedy word wrap to a width.
std::vector<std::string> wrapText(cairo_t* cr, const std::string& text, double width_pt,
                                  const Font& font) {
  std::vector<std::string> lines;
  std::istringstream words(text);
  std::string word, line;
  while (words >> word) {
    const std::string candidate = line.empty() ? word : line + " " + word;
    if (!line.empty() && textWidthPt(cr, candidate, font) > width_pt) {
      lines.push_back(line);
      line = word;
    } else {
      line = candidate;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

// Paragraphs wrapped to the width from the baseline y downward; returns the height used.
double drawParagraphs(cairo_t* cr, Point first_baseline, double width_pt,
                      const std::vector<std::string>& paragraphs, const TextStyle& style) {
  double y = first_baseline.y;
  for (const std::string& paragraph : paragraphs) {
    for (const std::string& line : wrapText(cr, paragraph, width_pt, style.font)) {
      drawText(cr, {first_baseline.x, y}, line, style);
      y += lineHeightPt(style.font);
    }
  }
  return y - first_baseline.y;
}

// ---- Numbers ----

constexpr const char* kEmptyCell = "\u2013";  // en dash
constexpr double kGroupThousandsFrom = 1000;

std::string formatG4(double value) { return fmt::format("{:.4g}", value); }

// 47 500 000 with thin spaces between groups of three, rounded to four significant digits (a
// measured luminance is not known better: 59 713 400 would claim eight); small values likewise.
std::string formatLuminance(double cd_m2) {
  constexpr int kSignificantDigits = 4;
  if (!std::isfinite(cd_m2)) return kEmptyCell;
  if (std::abs(cd_m2) < kGroupThousandsFrom) return formatG4(cd_m2);
  const double scale =
      std::pow(10.0, std::floor(std::log10(std::abs(cd_m2))) + 1 - kSignificantDigits);
  const std::string digits = fmt::format("{:.0f}", std::round(std::abs(cd_m2) / scale) * scale);
  std::string grouped = cd_m2 < 0 ? "-" : "";
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) grouped += "\u2009";
    grouped += digits[i];
  }
  return grouped;
}

std::string formatAxis(const std::optional<double>& axis_deg) {
  return axis_deg ? fmt::format("{:.2f}", *axis_deg) : kEmptyCell;
}

std::string superscriptInteger(int value) {
  static constexpr std::array<const char*, 10> kDigits = {"\u2070", "\u00b9", "\u00b2", "\u00b3",
                                                          "\u2074", "\u2075", "\u2076", "\u2077",
                                                          "\u2078", "\u2079"};
  std::string text = value < 0 ? "\u207b" : "";
  for (const char digit : std::to_string(std::abs(value))) text += kDigits[digit - '0'];
  return text;
}

// ---- Lines and markers ----

void applyLineStyle(cairo_t* cr, const LineStyle& style) {
  static constexpr std::array<double, 2> kDashedPt = {4.0, 2.5};
  static constexpr std::array<double, 2> kLongDashedPt = {8.0, 3.0};
  static constexpr std::array<double, 2> kDottedPt = {0.0, 2.4};  // round caps make the dots
  setColour(cr, style.colour);
  cairo_set_line_width(cr, style.width_pt);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, style.dash == Dash::kDotted ? CAIRO_LINE_CAP_ROUND : CAIRO_LINE_CAP_BUTT);
  const std::array<double, 2>* pattern = style.dash == Dash::kDashed       ? &kDashedPt
                                         : style.dash == Dash::kLongDashed ? &kLongDashedPt
                                         : style.dash == Dash::kDotted     ? &kDottedPt
                                                                           : nullptr;
  cairo_set_dash(cr, pattern ? pattern->data() : nullptr, pattern ? 2 : 0, 0);
}

void drawSegment(cairo_t* cr, Point from, Point to, const LineStyle& style) {
  applyLineStyle(cr, style);
  cairo_move_to(cr, from.x, from.y);
  cairo_line_to(cr, to.x, to.y);
  cairo_stroke(cr);
}

LineStyle extrapolated(const LineStyle& style) {
  const auto lighten = [](double c) { return c + (1 - c) * kExtrapolationLightening; };
  const Rgb light{lighten(style.colour.r), lighten(style.colour.g), lighten(style.colour.b)};
  return {.colour = light, .width_pt = style.width_pt, .dash = Dash::kDotted};
}

void drawMarker(cairo_t* cr, Point at, const MarkerStyle& style) {
  constexpr double kOutlinePt = 0.6;  // white ring: markers stay distinct from lines under them
  const double half = style.size_pt / 2;
  if (style.shape == MarkerShape::kCircle) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, at.x, at.y, half, 0, 2 * std::numbers::pi);
  } else {
    cairo_rectangle(cr, at.x - half, at.y - half, style.size_pt, style.size_pt);
  }
  cairo_set_dash(cr, nullptr, 0, 0);
  if (style.hollow) {
    setColour(cr, kWhite);
    cairo_fill_preserve(cr);
    cairo_set_line_width(cr, 2 * kOutlinePt);
    setColour(cr, style.colour);
    cairo_stroke(cr);
    return;
  }
  setColour(cr, style.colour);
  cairo_fill_preserve(cr);
  cairo_set_line_width(cr, kOutlinePt);
  setColour(cr, kWhite);
  cairo_stroke(cr);
}

// ---- Plot: data coordinates (α in degrees, y in data units) to page points ----

constexpr Range kAlphaAxisDeg{0, 90};
constexpr double kAlphaTickStepDeg = 10;
constexpr int kCurveSamples = 240;
constexpr double kCurveInkWeight = 1;
constexpr double kMarkerInkWeight = 12;  // hiding a measured point is worse than a curve

enum class Scale { kLinear, kLog };

struct Ink {
  Point at;
  double weight = 1;
};

struct Plot {
  Box area;  // the data area on the page
  Range y;
  Scale scale = Scale::kLinear;
  double y_step = 0;       // linear axes: between labelled ticks
  std::vector<Ink> ink{};  // what has been drawn, for placing the legend

  bool plottable(double value) const {
    return std::isfinite(value) && (scale == Scale::kLinear || value > 0);
  }
  double pageX(double alpha_deg) const {
    return area.x0 +
           (alpha_deg - kAlphaAxisDeg.lo) / (kAlphaAxisDeg.hi - kAlphaAxisDeg.lo) * area.width();
  }
  double pageY(double value) const {
    const double t = scale == Scale::kLog ? (std::log10(value) - std::log10(y.lo)) /
                                                (std::log10(y.hi) - std::log10(y.lo))
                                          : (value - y.lo) / (y.hi - y.lo);
    return area.y1 - t * area.height();
  }
  Point page(double alpha_deg, double value) const { return {pageX(alpha_deg), pageY(value)}; }
};

// α in degrees to a value in the plot's units; NaN where the function is undefined.
using Function = std::function<double(double)>;

std::vector<double> sample(const Function& f, Range alpha_deg) {
  std::vector<double> values;
  if (alpha_deg.empty()) return values;
  for (int i = 0; i <= kCurveSamples; ++i)
    values.push_back(f(alpha_deg.lo + (alpha_deg.hi - alpha_deg.lo) * i / kCurveSamples));
  return values;
}

// Whole decades around every positive finite value.
Range logRange(const std::vector<double>& values) {
  constexpr Range kDefaultCdM2{1e4, 1e8};
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (const double v : values) {
    if (!std::isfinite(v) || v <= 0) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (!(hi > 0)) return kDefaultCdM2;
  const double lo_decade = std::floor(std::log10(lo));
  const double hi_decade = std::max(std::ceil(std::log10(hi)), lo_decade + 1);
  return {std::pow(10.0, lo_decade), std::pow(10.0, hi_decade)};
}

// 1, 2 or 5 times a power of ten, giving about six intervals over the span.
double niceStep(double span) {
  constexpr double kTargetIntervals = 6;
  const double raw = span / kTargetIntervals;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double multiple : {1.0, 2.0, 5.0}) {
    if (multiple * decade >= raw) return multiple * decade;
  }
  return 10 * decade;
}

// From 0 to a whole step above the largest finite value, with headroom for the legend.
Plot linearPlot(const Box& area, const std::vector<double>& values) {
  constexpr double kHeadroom = 1.15;
  constexpr double kDefaultTopDeg = 10;
  double top = 0;
  for (const double v : values)
    if (std::isfinite(v)) top = std::max(top, v);
  top = top > 0 ? top * kHeadroom : kDefaultTopDeg;
  const double step = niceStep(top);
  return {.area = area, .y = {0, std::ceil(top / step) * step}, .y_step = step};
}

Plot logPlot(const Box& area, const std::vector<double>& values) {
  return {.area = area, .y = logRange(values), .scale = Scale::kLog};
}

struct Tick {
  double value = 0;
  std::string label;  // empty: a minor tick
};

std::vector<Tick> yTicks(const Plot& plot) {
  constexpr int kMinorsPerDecade = 9;
  constexpr double kStepTolerance = 1e-6;  // of a step: the top tick despite rounding
  std::vector<Tick> ticks;
  if (plot.scale == Scale::kLinear) {
    const int steps = static_cast<int>((plot.y.hi - plot.y.lo) / plot.y_step + kStepTolerance);
    for (int i = 0; i <= steps; ++i) {
      const double v = plot.y.lo + i * plot.y_step;
      ticks.push_back({v, fmt::format("{:g}", v)});
    }
    return ticks;
  }
  const int lo = static_cast<int>(std::lround(std::log10(plot.y.lo)));
  const int hi = static_cast<int>(std::lround(std::log10(plot.y.hi)));
  for (int decade = lo; decade <= hi; ++decade) {
    const double base = std::pow(10.0, decade);
    ticks.push_back({base, "10" + superscriptInteger(decade)});
    if (decade == hi) break;
    for (int m = 2; m <= kMinorsPerDecade; ++m) ticks.push_back({m * base, ""});
  }
  return ticks;
}

std::vector<Tick> xTicks() {
  std::vector<Tick> ticks;
  for (double a = kAlphaAxisDeg.lo; a <= kAlphaAxisDeg.hi; a += kAlphaTickStepDeg)
    ticks.push_back({a, fmt::format("{:g}", a)});
  return ticks;
}

void drawYTicks(cairo_t* cr, const Plot& plot) {
  const Box& a = plot.area;
  for (const Tick& tick : yTicks(plot)) {
    const double y = plot.pageY(tick.value);
    const bool major = !tick.label.empty();
    drawSegment(cr, {a.x0 - (major ? kTickLengthPt : kMinorTickLengthPt), y}, {a.x0, y},
                kFrameStyle);
    if (!major) continue;
    drawSegment(cr, {a.x0, y}, {a.x1, y}, kGridStyle);
    drawText(
        cr,
        {a.x0 - kTickLengthPt - kTickLabelGapPt, y + kBaselineBelowMiddleEm * kTickFont.size_pt},
        tick.label, {kTickFont, kInk, Align::kRight});
  }
}

void drawXTicks(cairo_t* cr, const Plot& plot) {
  const Box& a = plot.area;
  for (const Tick& tick : xTicks()) {
    const double x = plot.pageX(tick.value);
    drawSegment(cr, {x, a.y0}, {x, a.y1}, kGridStyle);
    drawSegment(cr, {x, a.y1}, {x, a.y1 + kTickLengthPt}, kFrameStyle);
    drawText(cr, {x, a.y1 + kTickLengthPt + kTickLabelGapPt + kTickFont.size_pt}, tick.label,
             {kTickFont, kInk, Align::kCentre});
  }
}

// Grid, ticks with their labels, frame, and both axis titles.
void drawAxes(cairo_t* cr, const Plot& plot, const std::string& y_title) {
  drawYTicks(cr, plot);
  drawXTicks(cr, plot);
  const Box& a = plot.area;
  applyLineStyle(cr, kFrameStyle);
  cairo_rectangle(cr, a.x0, a.y0, a.width(), a.height());
  cairo_stroke(cr);
  const TextStyle title_style{kAxisTitleFont, kInk, Align::kCentre};
  drawText(cr, {(a.x0 + a.x1) / 2, a.y1 + kXAxisGutterPt - kTickLabelGapPt},
           "angle of incidence \u03b1 (\u00b0)", title_style);
  drawVerticalText(cr, {a.x0 - kYAxisGutterPt + kAxisTitleFont.size_pt, (a.y0 + a.y1) / 2}, y_title,
                   title_style);
}

// f sampled over alpha_deg, split where it is undefined, clipped to the data area.
void drawCurve(cairo_t* cr, Plot& plot, const Function& f, Range alpha_deg,
               const LineStyle& style) {
  const std::vector<double> values = sample(f, alpha_deg);
  cairo_save(cr);
  cairo_rectangle(cr, plot.area.x0, plot.area.y0, plot.area.width(), plot.area.height());
  cairo_clip(cr);
  applyLineStyle(cr, style);
  bool drawing = false;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!plot.plottable(values[i])) {
      drawing = false;
      continue;
    }
    const double alpha = alpha_deg.lo + (alpha_deg.hi - alpha_deg.lo) * i / kCurveSamples;
    const Point p = plot.page(alpha, values[i]);
    drawing ? cairo_line_to(cr, p.x, p.y) : cairo_move_to(cr, p.x, p.y);
    drawing = true;
    plot.ink.push_back({p, kCurveInkWeight});
  }
  cairo_stroke(cr);
  cairo_restore(cr);
}

// A fitted function: solid over the measured range, lighter and dotted where extrapolated.
// Solid over the measured range, dotted where extrapolated within `shown` (default 0–80°).
void drawFit(cairo_t* cr, Plot& plot, const Function& f, Range measured_deg, const LineStyle& style,
             std::optional<Range> shown = std::nullopt) {
  const Range all =
      shown.value_or(Range{kAlphaAxisDeg.lo, std::max(kMaxLimitAlphaDeg, measured_deg.hi)});
  drawCurve(cr, plot, f, {all.lo, std::min(all.hi, measured_deg.lo)}, extrapolated(style));
  drawCurve(cr, plot, f, {std::max(all.lo, measured_deg.hi), all.hi}, extrapolated(style));
  drawCurve(cr, plot, f, {std::max(all.lo, measured_deg.lo), std::min(all.hi, measured_deg.hi)},
            style);
}

// Where the module glares by the fits, as one range (first onset to last end); none: nowhere.
std::optional<Range> glaringRange(const DatasheetContent& content) {
  const std::vector<AlphaRange> ranges = glareRanges(*content.fits, content.limit);
  if (ranges.empty()) return std::nullopt;
  return Range{ranges.front().from_deg, ranges.back().to_deg};
}

struct DataPoint {
  double alpha_deg = 0, value = 0;
};

void drawMarkers(cairo_t* cr, Plot& plot, const std::vector<DataPoint>& points,
                 const MarkerStyle& style) {
  for (const DataPoint& point : points) {
    if (!plot.plottable(point.value)) continue;
    const Point p = plot.page(point.alpha_deg, point.value);
    drawMarker(cr, p, style);
    plot.ink.push_back({p, kMarkerInkWeight});
  }
}

// ---- Legend ----

constexpr double kLegendSamplePt = 20;  // length of a line sample
constexpr double kLegendPaddingPt = 4;
constexpr double kLegendInsetPt = 5;  // from the data area's frame
constexpr double kLegendRowGapPt = 1;

struct LegendEntry {
  std::string label;
  std::optional<LineStyle> line;
  std::optional<MarkerStyle> marker;
};

// An entry with its sample starting at `left`, the sample centred on `middle_y`.
void drawLegendEntry(cairo_t* cr, double left, double middle_y, const LegendEntry& entry) {
  if (entry.line)
    drawSegment(cr, {left, middle_y}, {left + kLegendSamplePt, middle_y}, *entry.line);
  if (entry.marker) drawMarker(cr, {left + kLegendSamplePt / 2, middle_y}, *entry.marker);
  drawText(cr,
           {left + kLegendSamplePt + kLegendPaddingPt,
            middle_y + kBaselineBelowMiddleEm * kLegendFont.size_pt},
           entry.label, {kLegendFont});
}

double inkInside(const Plot& plot, const Box& box) {
  double total = 0;
  for (const Ink& ink : plot.ink)
    if (box.contains(ink.at)) total += ink.weight;
  return total;
}

// The corner of the data area that hides the least of what is drawn (ties: first listed).
Box legendBox(const Plot& plot, double width, double height) {
  const Box& a = plot.area;
  const double left = a.x0 + kLegendInsetPt, right = a.x1 - kLegendInsetPt - width;
  const double top = a.y0 + kLegendInsetPt, bottom = a.y1 - kLegendInsetPt - height;
  const std::array<Box, 4> corners = {Box{left, top, left + width, top + height},
                                      Box{right, top, right + width, top + height},
                                      Box{right, bottom, right + width, bottom + height},
                                      Box{left, bottom, left + width, bottom + height}};
  return *std::min_element(corners.begin(), corners.end(), [&](const Box& p, const Box& q) {
    return inkInside(plot, p) < inkInside(plot, q);
  });
}

void drawLegend(cairo_t* cr, const Plot& plot, const std::vector<LegendEntry>& entries) {
  constexpr double kBackgroundAlpha = 0.88;
  const double row_pt = lineHeightPt(kLegendFont) + kLegendRowGapPt;
  double text_width = 0;
  for (const LegendEntry& e : entries)
    text_width = std::max(text_width, textWidthPt(cr, e.label, kLegendFont));
  const Box box = legendBox(plot, 3 * kLegendPaddingPt + kLegendSamplePt + text_width,
                            2 * kLegendPaddingPt + row_pt * entries.size());
  cairo_rectangle(cr, box.x0, box.y0, box.width(), box.height());
  cairo_set_source_rgba(cr, kWhite.r, kWhite.g, kWhite.b, kBackgroundAlpha);
  cairo_fill_preserve(cr);
  applyLineStyle(cr, kGridStyle);
  cairo_stroke(cr);
  double middle_y = box.y0 + kLegendPaddingPt + row_pt / 2;
  for (const LegendEntry& entry : entries) {
    drawLegendEntry(cr, box.x0 + kLegendPaddingPt, middle_y, entry);
    middle_y += row_pt;
  }
}

// ---- The two plots ----

std::string r2Label(const std::string& what, const FitQuality& quality) {
  return fmt::format("{}, R\u00b2 = {:.4f}", what, quality.r2);
}

// The data area of a plot inside its block, below the block's title.
Box dataArea(const Box& block) {
  return {block.x0 + kYAxisGutterPt, block.y0 + kBlockTitleHeightPt, block.x1 - kRightPaddingPt,
          block.y1 - kXAxisGutterPt};
}

void drawBlockTitle(cairo_t* cr, const Box& block, const std::string& title) {
  drawText(cr, {block.x0, block.y0 + kSectionFont.size_pt}, title, {kSectionFont});
}

// The α range a fit was measured over: all luminance rows, or an axis's rows with an ellipse.
Range measuredRange(const SweepFits& fits) { return {fits.alpha_min_deg, fits.alpha_max_deg}; }
Range measuredRange(const AxisFit& axis) { return {axis.alpha_min_deg, axis.alpha_max_deg}; }

// Whether a fit measured over `measured` is drawn extrapolated somewhere in 0–80°.
bool extrapolates(Range measured) {
  return measured.lo > kAlphaAxisDeg.lo || measured.hi < kMaxLimitAlphaDeg;
}

// Measured points, the limit curve, and the fits over the measured range (not their
// extrapolations, which may run off to any value).
std::vector<double> lmaxPlotValues(const SweepTable& table, const SweepFits& fits,
                                   const Function& limit, const std::vector<Function>& fitted) {
  std::vector<double> values = sample(limit, {kAlphaAxisDeg.lo, kMaxLimitAlphaDeg});
  for (const SweepRow& row : table.rows) values.push_back(row.lmax_cd_m2);
  for (const Function& f : fitted) {
    const std::vector<double> v = sample(f, measuredRange(fits));
    values.insert(values.end(), v.begin(), v.end());
  }
  return values;
}

void drawLmaxPlot(cairo_t* cr, const DatasheetContent& content, const Box& block) {
  const SweepFits& fits = *content.fits;
  const Function limit = [&](double a) { return content.limit.at(a).value_or(kNaN); };
  const Function cosine = [&](double a) { return fits.cosine.curve(a); };
  const Function biquadratic = [&](double a) { return fits.biquadratic.curve(a); };
  Plot plot =
      logPlot(dataArea(block), lmaxPlotValues(*content.table, fits, limit, {cosine, biquadratic}));
  drawBlockTitle(cr, block, "Maximum luminance");
  drawAxes(cr, plot, "Lmax (cd/m\u00b2)");
  drawCurve(cr, plot, limit, {kAlphaAxisDeg.lo, kMaxLimitAlphaDeg}, kLimitStyle);
  drawFit(cr, plot, cosine, measuredRange(fits), kCosineStyle);
  drawFit(cr, plot, biquadratic, measuredRange(fits), kBiquadraticStyle);
  std::vector<DataPoint> measured, bounds;
  for (const SweepRow& row : content.table->rows)
    (row.lmax_bound.empty() ? measured : bounds).push_back({row.alpha_deg, row.lmax_cd_m2});
  drawMarkers(cr, plot, measured, kLmaxMarker);
  drawMarkers(cr, plot, bounds, kLmaxBoundMarker);
  std::vector<LegendEntry> legend = {
      {"measured Lmax", std::nullopt, kLmaxMarker},
      {content.limit.constant_cd_m2 ? fmt::format("glare limit (constant {})",
                                                  formatLuminance(*content.limit.constant_cd_m2))
                                    : std::string("glare limit (\u03b1 curve)"),
       kLimitStyle, std::nullopt},
      {r2Label("cosine fit", fits.cosine.quality), kCosineStyle, std::nullopt},
      {r2Label("biquadratic fit", fits.biquadratic.quality), kBiquadraticStyle, std::nullopt}};
  if (!bounds.empty())
    legend.push_back({"Lmax only a bound (not fitted)", std::nullopt, kLmaxBoundMarker});
  if (extrapolates(measuredRange(fits)))
    legend.push_back({"fit extrapolated", kExtrapolationKeyStyle, {}});
  drawLegend(cr, plot, legend);
}

// One limit-ellipse axis: its measured rows, fit and style.
struct AxisSeries {
  std::string name;
  const AxisFit* fit = nullptr;
  std::optional<double> SweepRow::*column = nullptr;
  LineStyle line;
  MarkerStyle marker;
};

// The five-facet model's full spread 2γ for one axis; NaN where the model does not hold.
Function facetModelCurve(double beta_deg, double FacetSpread::*half_spread) {
  return [beta_deg, half_spread](double alpha_deg) {
    const FacetSpread spread = facetSpread(alpha_deg, beta_deg);
    return spread.valid ? 2 * spread.*half_spread : kNaN;
  };
}

std::vector<Function> modelCurves(const std::optional<double>& beta_deg) {
  if (!beta_deg) return {};
  return {facetModelCurve(*beta_deg, &FacetSpread::gamma_ns_deg),
          facetModelCurve(*beta_deg, &FacetSpread::gamma_ew_deg)};
}

// The model's curves (under everything else) and their legend entries.
std::vector<LegendEntry> drawModel(cairo_t* cr, Plot& plot, const std::optional<double>& beta_deg) {
  const std::vector<Function> curves = modelCurves(beta_deg);
  if (curves.empty()) return {};
  const std::array<LineStyle, 2> styles = {kModelNsStyle, kModelEwStyle};
  const std::array<const char*, 2> facets = {"N\u2013S", "E\u2013W"};
  std::vector<LegendEntry> legend;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    drawCurve(cr, plot, curves[i], kAlphaAxisDeg, styles[i]);
    legend.push_back(
        {fmt::format("facet model \u03b2 = {:g}\u00b0: 2\u03b3 {}", *beta_deg, facets[i]),
         styles[i], std::nullopt});
  }
  return legend;
}

std::vector<double> axesPlotValues(const DatasheetContent& content,
                                   const std::vector<AxisSeries>& series) {
  std::vector<double> values;
  for (const AxisSeries& s : series) {
    for (const SweepRow& row : content.table->rows) values.push_back((row.*s.column).value_or(0));
    if (s.fit->logistic) {
      const std::vector<double> v = sample(s.fit->logistic->curve, measuredRange(*s.fit));
      values.insert(values.end(), v.begin(), v.end());
    }
  }
  for (const Function& f : modelCurves(content.model_beta_deg)) {
    const std::vector<double> v = sample(f, kAlphaAxisDeg);
    values.insert(values.end(), v.begin(), v.end());
  }
  return values;
}

LegendEntry axisLegendEntry(const AxisSeries& s) {
  if (!s.fit->logistic) return {s.name + " (not fitted)", std::nullopt, s.marker};
  return {r2Label(s.name + ", logistic fit", s.fit->logistic->quality), s.line, s.marker};
}

void drawAxisSeries(cairo_t* cr, Plot& plot, const DatasheetContent& content, const AxisSeries& s) {
  // An axis exists only where the module glares: its fit is drawn there only (it can
  // extrapolate to anything elsewhere), as in glare-profile.json.
  const std::optional<Range> glaring = glaringRange(content);
  if (s.fit->logistic && glaring)
    drawFit(cr, plot, s.fit->logistic->curve, measuredRange(*s.fit), s.line, glaring);
  std::vector<DataPoint> measured;
  for (const SweepRow& row : content.table->rows)
    if (const std::optional<double>& v = row.*s.column) measured.push_back({row.alpha_deg, *v});
  drawMarkers(cr, plot, measured, s.marker);
}

void drawAxesPlot(cairo_t* cr, const DatasheetContent& content, const Box& block) {
  const SweepFits& fits = *content.fits;
  const std::vector<AxisSeries> series = {
      {"vertical", &fits.vertical, &SweepRow::vertical_deg, kVerticalStyle, kVerticalMarker},
      {"horizontal", &fits.horizontal, &SweepRow::horizontal_deg, kHorizontalStyle,
       kHorizontalMarker}};
  Plot plot = linearPlot(dataArea(block), axesPlotValues(content, series));
  drawBlockTitle(cr, block, "Limit-ellipse axes (full angles)");
  drawAxes(cr, plot, "axis (\u00b0)");
  const std::vector<LegendEntry> model_legend = drawModel(cr, plot, content.model_beta_deg);
  std::vector<LegendEntry> legend;
  for (const AxisSeries& s : series) {
    drawAxisSeries(cr, plot, content, s);
    legend.push_back(axisLegendEntry(s));
  }
  legend.insert(legend.end(), model_legend.begin(), model_legend.end());
  const auto axis_extrapolates = [](const AxisFit& axis) {
    return axis.logistic && extrapolates(measuredRange(axis));
  };
  if (axis_extrapolates(fits.vertical) || axis_extrapolates(fits.horizontal))
    legend.push_back({"fit extrapolated", kExtrapolationKeyStyle, std::nullopt});
  drawLegend(cr, plot, legend);
}

// ---- Tables ----

struct TextTable {
  std::vector<std::vector<std::string>> rows;  // the first header_rows are headings
  std::size_t header_rows = 1;
  bool first_column_left = false;  // the other columns are right-aligned
};

constexpr double kCellPaddingEm = 0.6;  // each side of a cell's text

Font cellFont(const TextTable& table, std::size_t row, Font font) {
  font.bold = row < table.header_rows;
  return font;
}

std::vector<double> columnWidthsPt(cairo_t* cr, const TextTable& table, const Font& font) {
  std::vector<double> widths;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const std::vector<std::string>& row = table.rows[r];
    widths.resize(std::max(widths.size(), row.size()), 0);
    for (std::size_t c = 0; c < row.size(); ++c)
      widths[c] = std::max(widths[c], textWidthPt(cr, row[c], cellFont(table, r, font)) +
                                          2 * kCellPaddingEm * font.size_pt);
  }
  return widths;
}

double rowHeightPt(const Font& font) { return font.size_pt * kTableLineSpacing; }

double tableHeightPt(const TextTable& table, const Font& font) {
  return table.rows.size() * rowHeightPt(font);
}

void drawTableRow(cairo_t* cr, const TextTable& table, std::size_t r,
                  const std::vector<double>& widths, Point top_left, const Font& font) {
  const double baseline =
      top_left.y + rowHeightPt(font) / 2 + kBaselineBelowMiddleEm * font.size_pt;
  const double padding = kCellPaddingEm * font.size_pt;
  double x = top_left.x;
  const std::vector<std::string>& row = table.rows[r];
  for (std::size_t c = 0; c < row.size(); ++c) {
    const bool left = c == 0 && table.first_column_left;
    const Point at{left ? x + padding : x + widths[c] - padding, baseline};
    drawText(cr, at, row[c], {cellFont(table, r, font), kInk, left ? Align::kLeft : Align::kRight});
    x += widths[c];
  }
}

// The table at the top left of box, its font shrunk (never grown) to fit the box. Data rows are
// striped; a rule separates the headings. Returns the height used.
double drawTable(cairo_t* cr, const TextTable& table, const Box& box, const Font& font) {
  std::vector<double> widths = columnWidthsPt(cr, table, font);
  double natural_width = 0;
  for (const double w : widths) natural_width += w;
  constexpr double kMinScale = 0.3;  // a box far too small gets a tiny table, not a negative one
  const double scale = std::max(kMinScale, std::min({1.0, box.width() / natural_width,
                                                     box.height() / tableHeightPt(table, font)}));
  const Font fitted{font.size_pt * scale, font.bold};
  for (double& w : widths) w *= scale;
  const double row_pt = rowHeightPt(fitted), width = natural_width * scale;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const double top = box.y0 + r * row_pt;
    if (r >= table.header_rows && (r - table.header_rows) % 2 == 1) {
      setColour(cr, kStripeColour);
      cairo_rectangle(cr, box.x0, top, width, row_pt);
      cairo_fill(cr);
    }
    drawTableRow(cr, table, r, widths, {box.x0, top}, fitted);
  }
  const double rule_y = box.y0 + table.header_rows * row_pt;
  drawSegment(cr, {box.x0, rule_y}, {box.x0 + width, rule_y}, kRuleStyle);
  drawSegment(cr, {box.x0, box.y0 + tableHeightPt(table, fitted)},
              {box.x0 + width, box.y0 + tableHeightPt(table, fitted)}, kRuleStyle);
  return tableHeightPt(table, fitted);
}

// The row's verdict, else the method's: glare when the maximum is at or above the limit.
std::string glareCell(const SweepRow& row) {
  std::optional<bool> glare = row.glare;
  if (!glare && row.limit_cd_m2) glare = row.lmax_cd_m2 >= *row.limit_cd_m2;
  return glare ? (*glare ? "yes" : "no") : kEmptyCell;
}

// Lmax, with ≥ or ≤ where it is only a bound (saturated top, all dark).
std::string lmaxCell(const SweepRow& row) {
  const char* prefix = row.lmax_bound == "lower"   ? "\u2265 "
                       : row.lmax_bound == "upper" ? "\u2264 "
                                                   : "";
  return prefix + formatLuminance(row.lmax_cd_m2);
}

TextTable sweepTable(const SweepTable& sweep) {
  TextTable table{.rows = {{"\u03b1 (\u00b0)", "limit (cd/m\u00b2)", "Lmax (cd/m\u00b2)",
                            "vertical (\u00b0)", "horizontal (\u00b0)", "glare"}}};
  for (const SweepRow& row : sweep.rows) {
    table.rows.push_back({fmt::format("{:g}", row.alpha_deg),
                          row.limit_cd_m2 ? formatLuminance(*row.limit_cd_m2) : kEmptyCell,
                          lmaxCell(row), formatAxis(row.vertical_deg),
                          formatAxis(row.horizontal_deg), glareCell(row)});
  }
  return table;
}

// One fitted function's column of the parameter table.
struct FitColumn {
  std::string name, quantity;
  const FitQuality* quality = nullptr;  // none: not fitted
  std::vector<std::string> status;      // one line each, below the parameters
};

std::vector<std::string> qualityStatus(const FitQuality& quality) {
  std::vector<std::string> status;
  if (quality.ill_conditioned) status.push_back("(ill-conditioned)");
  if (quality.under_determined) status.push_back("(under-determined)");
  return status;
}

FitColumn axisColumn(const std::string& axis, const AxisFit& fit) {
  if (fit.logistic)
    return {"logistic", axis, &fit.logistic->quality, qualityStatus(fit.logistic->quality)};
  const int n = fit.rows_with_ellipse;
  return {"logistic",
          axis,
          nullptr,
          {"not fitted", fmt::format("({} row{} with an ellipse)", n, n == 1 ? "" : "s")}};
}

std::string parameterCell(const FitColumn& column, std::size_t i) {
  if (!column.quality || i >= column.quality->parameters.size()) return kEmptyCell;
  std::string cell = formatG4(column.quality->parameters[i]);
  // An ill-conditioned fit's standard errors are huge and say only what its flag says.
  const auto& errors = column.quality->standard_errors;
  if (i < errors.size() && errors[i] && !column.quality->ill_conditioned)
    cell += fmt::format(" \u00b1 {:.2g}", *errors[i]);
  return cell;
}

std::vector<std::string> qualityRow(const std::vector<FitColumn>& columns, const std::string& name,
                                    const std::function<std::string(const FitQuality&)>& cell) {
  std::vector<std::string> row = {name};
  for (const FitColumn& c : columns) row.push_back(c.quality ? cell(*c.quality) : kEmptyCell);
  return row;
}

TextTable fitTable(const SweepFits& fits) {
  const std::vector<FitColumn> columns = {
      {"cosine", "ln L", &fits.cosine.quality, qualityStatus(fits.cosine.quality)},
      {"biquadratic", "ln L", &fits.biquadratic.quality, qualityStatus(fits.biquadratic.quality)},
      axisColumn("vertical (\u00b0)", fits.vertical),
      axisColumn("horizontal (\u00b0)", fits.horizontal)};
  TextTable table{.rows = {{""}, {""}}, .header_rows = 2, .first_column_left = true};
  for (const FitColumn& c : columns) {
    table.rows[0].push_back(c.name);
    table.rows[1].push_back(c.quantity);
  }
  constexpr std::array<const char*, kLogisticParameters> kNames = {"a", "b", "c", "d"};
  for (std::size_t i = 0; i < kNames.size(); ++i) {
    table.rows.push_back({kNames[i]});
    for (const FitColumn& c : columns) table.rows.back().push_back(parameterCell(c, i));
  }
  table.rows.push_back(
      qualityRow(columns, "R\u00b2", [](auto& q) { return fmt::format("{:.4f}", q.r2); }));
  table.rows.push_back(qualityRow(columns, "RMSE", [](auto& q) { return formatG4(q.rmse); }));
  table.rows.push_back(qualityRow(columns, "n", [](auto& q) { return std::to_string(q.points); }));
  std::size_t status_lines = 0;
  for (const FitColumn& c : columns) status_lines = std::max(status_lines, c.status.size());
  for (std::size_t line = 0; line < status_lines; ++line) {
    table.rows.push_back({""});
    for (const FitColumn& c : columns)
      table.rows.back().push_back(line < c.status.size() ? c.status[line] : "");
  }
  return table;
}

const std::vector<std::string>& fitNotes() {
  static const std::vector<std::string> kNotes = {
      "cosine: ln L = a + b / cos(\u03b1)\u1d9c;  "
      "biquadratic: ln L = a \u03b1\u2074 + b \u03b1\u00b2 + c;  "
      "logistic: y = a / (1 + exp(\u2212(\u03b1 \u2212 b) d)) + c.",
      "L in cd/m\u00b2, \u03b1 and the axes y in degrees. R\u00b2 and RMSE on ln L for luminance, "
      "on degrees for the axes; \u00b1 one standard error; n points fitted."};
  return kNotes;
}

// ---- Page ----

struct Layout {
  Box header, lmax_plot, axes_plot, right_column, warnings;
};

constexpr std::size_t kMaxWarningLines = 6;

std::vector<std::string> warningLines(cairo_t* cr, const std::vector<std::string>& warnings,
                                      double width_pt) {
  std::vector<std::string> lines;
  std::size_t shown = 0;
  for (const std::string& warning : warnings) {
    const std::vector<std::string> wrapped = wrapText(cr, "\u2022 " + warning, width_pt, kNoteFont);
    if (lines.size() + wrapped.size() > kMaxWarningLines) break;
    lines.insert(lines.end(), wrapped.begin(), wrapped.end());
    ++shown;
  }
  if (shown < warnings.size())
    lines.push_back(fmt::format("\u2026 and {} more", warnings.size() - shown));
  return lines;
}

double warningsHeightPt(cairo_t* cr, const std::vector<std::string>& warnings, double width_pt) {
  if (warnings.empty()) return 0;
  return lineHeightPt(kSectionFont) +
         warningLines(cr, warnings, width_pt).size() * lineHeightPt(kNoteFont);
}

Layout pageLayout(cairo_t* cr, const DatasheetContent& content) {
  const Box page{kMarginPt, kMarginPt, kPageWidthPt - kMarginPt, kPageHeightPt - kMarginPt};
  const double plot_right = page.x0 + kPlotColumnWidthPt;
  const double warnings_pt = warningsHeightPt(cr, content.fits->warnings, kPlotColumnWidthPt);
  const double body_top = page.y0 + kHeaderHeightPt + kGapPt;
  const double plots_bottom = page.y1 - (warnings_pt > 0 ? warnings_pt + kGapPt : 0);
  const double plot_split = (body_top + plots_bottom) / 2;
  return {.header = {page.x0, page.y0, page.x1, page.y0 + kHeaderHeightPt},
          .lmax_plot = {page.x0, body_top, plot_right, plot_split - kGapPt / 2},
          .axes_plot = {page.x0, plot_split + kGapPt / 2, plot_right, plots_bottom},
          .right_column = {plot_right + kColumnGapPt, body_top, page.x1, page.y1},
          .warnings = {page.x0, page.y1 - warnings_pt, plot_right, page.y1}};
}

// "by the fits it glares for α 49.7–80.0°", or that it does not.
std::string glareRangesText(const DatasheetContent& content) {
  const std::vector<AlphaRange> ranges = glareRanges(*content.fits, content.limit);
  if (ranges.empty())
    return fmt::format("by the fits it does not glare at any \u03b1 from 0 to {:g}\u00b0",
                       kMaxLimitAlphaDeg);
  std::string text;
  for (const AlphaRange& r : ranges)
    text +=
        fmt::format("{}{:.1f}\u2013{:.1f}\u00b0", text.empty() ? "" : ", ", r.from_deg, r.to_deg);
  return "by the fits it glares for \u03b1 " + text;
}

std::string subtitle(const DatasheetContent& content) {
  const std::size_t n = content.table->rows.size();
  if (n == 0) return "An empty sweep.";
  const auto [lo, hi] = std::minmax_element(
      content.table->rows.begin(), content.table->rows.end(),
      [](const SweepRow& a, const SweepRow& b) { return a.alpha_deg < b.alpha_deg; });
  const std::string limit =
      content.limit.constant_cd_m2
          ? fmt::format("a constant limit of {} cd/m\u00b2",
                        formatLuminance(*content.limit.constant_cd_m2))
          : fmt::format("the limit curve of the SPF method (undefined above {:g}\u00b0)",
                        kMaxLimitAlphaDeg);
  return fmt::format(
      "Sweep of {} stack{}, \u03b1 {:g}\u00b0 to {:g}\u00b0 (angle of incidence from the module "
      "normal). Glare when Lmax reaches {}: {}. Axes: full angles of the limit ellipse.",
      n, n == 1 ? "" : "s", lo->alpha_deg, hi->alpha_deg, limit, glareRangesText(content));
}

void drawHeader(cairo_t* cr, const DatasheetContent& content, const Box& box) {
  const std::string version = fmt::format("glarecam {}", kVersion);
  const std::string stamp =
      content.date.empty() ? version : fmt::format("{}   \u00b7   {}", content.date, version);
  const TextStyle stamp_style{kSubtitleFont, kMutedInk, Align::kRight};
  const double title_baseline = box.y0 + kTitleFont.size_pt;
  drawText(cr, {box.x1, title_baseline}, stamp, stamp_style);
  const std::string title = content.module.empty() ? std::string("Glare data sheet")
                                                   : "Glare data sheet \u2014 " + content.module;
  const double room = box.width() - textWidthPt(cr, stamp, kSubtitleFont) - kColumnGapPt;
  const double scale = std::min(1.0, room / textWidthPt(cr, title, kTitleFont));
  drawText(cr, {box.x0, title_baseline}, title, {{kTitleFont.size_pt * scale, true}});
  const std::string line = subtitle(content);
  const double sub_scale = std::min(1.0, box.width() / textWidthPt(cr, line, kSubtitleFont));
  drawText(cr, {box.x0, title_baseline + 2 * kSubtitleFont.size_pt}, line,
           {{kSubtitleFont.size_pt * sub_scale}, kMutedInk});
  drawSegment(cr, {box.x0, box.y1}, {box.x1, box.y1}, kRuleStyle);
}

double notesHeightPt(cairo_t* cr, double width_pt) {
  double lines = 0;
  for (const std::string& note : fitNotes())
    lines += wrapText(cr, note, width_pt, kNoteFont).size();
  return lines * lineHeightPt(kNoteFont);
}

// The sweep table on top, the fit parameters right below it: the sweep table shrinks (long
// sweeps) so that both fit.
void drawTables(cairo_t* cr, const DatasheetContent& content, const Box& column) {
  const TextTable fits = fitTable(*content.fits);
  const double fits_pt = kBlockTitleHeightPt + tableHeightPt(fits, kTableFont) + kGapPt / 2 +
                         notesHeightPt(cr, column.width());
  drawBlockTitle(cr, column, "Sweep");
  const Box sweep_box{column.x0, column.y0 + kBlockTitleHeightPt, column.x1,
                      column.y1 - fits_pt - kSectionGapPt};
  const double sweep_pt = drawTable(cr, sweepTable(*content.table), sweep_box, kTableFont);
  const Box fits_block{column.x0, sweep_box.y0 + sweep_pt + kSectionGapPt, column.x1, column.y1};
  drawBlockTitle(cr, fits_block, "Fit parameters");
  const Box fits_box{fits_block.x0, fits_block.y0 + kBlockTitleHeightPt, fits_block.x1,
                     fits_block.y1};
  const double table_pt = drawTable(cr, fits, fits_box, kTableFont);
  drawParagraphs(cr, {column.x0, fits_box.y0 + table_pt + kGapPt / 2 + kNoteFont.size_pt},
                 column.width(), fitNotes(), {kNoteFont, kMutedInk});
}

void drawWarnings(cairo_t* cr, const std::vector<std::string>& warnings, const Box& box) {
  if (warnings.empty()) return;
  drawText(cr, {box.x0, box.y0 + kSectionFont.size_pt}, "Warnings", {kSectionFont});
  double y = box.y0 + lineHeightPt(kSectionFont) + kNoteFont.size_pt;
  for (const std::string& line : warningLines(cr, warnings, box.width())) {
    drawText(cr, {box.x0, y}, line, {kNoteFont, kMutedInk});
    y += lineHeightPt(kNoteFont);
  }
}

void drawDatasheet(cairo_t* cr, const DatasheetContent& content) {
  setColour(cr, kWhite);
  cairo_paint(cr);
  const Layout layout = pageLayout(cr, content);
  drawHeader(cr, content, layout.header);
  drawLmaxPlot(cr, content, layout.lmax_plot);
  drawAxesPlot(cr, content, layout.axes_plot);
  drawTables(cr, content, layout.right_column);
  drawWarnings(cr, content.fits->warnings, layout.warnings);
}

// ---- Output ----

struct SurfaceDeleter {
  void operator()(cairo_surface_t* surface) const { cairo_surface_destroy(surface); }
};
struct ContextDeleter {
  void operator()(cairo_t* cr) const { cairo_destroy(cr); }
};
using SurfacePtr = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using ContextPtr = std::unique_ptr<cairo_t, ContextDeleter>;

// Draws the page on surface, `scale` device units per point; the drawing's first error.
cairo_status_t drawOn(cairo_surface_t* surface, const DatasheetContent& content, double scale) {
  const ContextPtr cr(cairo_create(surface));
  cairo_scale(cr.get(), scale, scale);
  drawDatasheet(cr.get(), content);
  return cairo_status(cr.get());
}

enum class VectorFormat { kPdf, kSvg };

SurfacePtr vectorSurface(VectorFormat format, const fs::path& file,
                         const DatasheetContent& content) {
  if (format == VectorFormat::kSvg) {
    SurfacePtr surface(cairo_svg_surface_create(file.c_str(), kPageWidthPt, kPageHeightPt));
    cairo_svg_surface_set_document_unit(surface.get(), CAIRO_SVG_UNIT_PT);
    return surface;
  }
  SurfacePtr surface(cairo_pdf_surface_create(file.c_str(), kPageWidthPt, kPageHeightPt));
  const std::string title = "Glare data sheet " + content.module;
  const std::string creator = std::string("glarecam ") + kVersion;
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE, title.c_str());
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, creator.c_str());
  return surface;
}

cairo_status_t renderVector(VectorFormat format, const fs::path& file,
                            const DatasheetContent& content) {
  const SurfacePtr surface = vectorSurface(format, file, content);
  const cairo_status_t drawn = drawOn(surface.get(), content, 1);
  cairo_surface_finish(surface.get());  // writes the file
  return drawn != CAIRO_STATUS_SUCCESS ? drawn : cairo_surface_status(surface.get());
}

cairo_status_t renderPng(const fs::path& file, const DatasheetContent& content) {
  const SurfacePtr surface(cairo_image_surface_create(
      CAIRO_FORMAT_RGB24, static_cast<int>(kPageWidthPt * kPngPixelsPerPt),
      static_cast<int>(kPageHeightPt * kPngPixelsPerPt)));
  const cairo_status_t drawn = drawOn(surface.get(), content, kPngPixelsPerPt);
  if (drawn != CAIRO_STATUS_SUCCESS) return drawn;
  return cairo_surface_write_to_png(surface.get(), file.c_str());
}

// Renders into a temporary sibling of target and renames it into place.
Status writeAtomically(const fs::path& target,
                       const std::function<cairo_status_t(const fs::path&)>& render) {
  fs::path temp;
  GLARECAM_ASSIGN(temp, createTemporarySibling(target));
  const cairo_status_t status = render(temp);
  if (status != CAIRO_STATUS_SUCCESS) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    return ioError(fmt::format("{}: {}", target.string(), cairo_status_to_string(status)));
  }
  return commitTemporary(temp, target);
}

constexpr double kMaxFacetBetaDeg = 45;  // facet_model.h's domain

Status validate(const DatasheetContent& content) {
  if (!content.table || !content.fits)
    return fail(ErrorCode::kInternal, "data sheet: no sweep table or no fits given");
  if (content.model_beta_deg &&
      !(*content.model_beta_deg > 0 && *content.model_beta_deg <= kMaxFacetBetaDeg))
    return badInput(
        fmt::format("data sheet: facet model \u03b2 must be in (0\u00b0, {:g}\u00b0], "
                    "got {:g}\u00b0",
                    kMaxFacetBetaDeg, *content.model_beta_deg));
  return {};
}

}  // namespace

Status writeDatasheet(const DatasheetContent& content, const fs::path& directory) {
  GLARECAM_CHECK(validate(content));
  const auto vector = [&](VectorFormat format) {
    return [&content, format](const fs::path& file) { return renderVector(format, file, content); };
  };
  GLARECAM_CHECK(writeAtomically(directory / kDatasheetPdf, vector(VectorFormat::kPdf)));
  GLARECAM_CHECK(writeAtomically(directory / kDatasheetSvg, vector(VectorFormat::kSvg)));
  return writeAtomically(directory / kDatasheetPng,
                         [&content](const fs::path& file) { return renderPng(file, content); });
}

}  // namespace glarecam::pipeline
