#include "hazard/ocular_hazard_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/version.h"
#include "hazard/ocular_hazard.h"
#include "render/canvas.h"
#include "render/colour.h"
#include "render/line_style.h"
#include "render/markers.h"
#include "render/number_format.h"
#include "render/page_output.h"
#include "render/plot_axes.h"
#include "render/plot_legend.h"
#include "render/plot_series.h"
#include "render/text.h"
#include "render/text_table.h"

namespace glarecam::hazard {
// Named after the file: in a unity build this file shares a translation unit with the library's
// other pictures, whose helpers have names of their own.
namespace ocular_hazard_plot {

// Drawn with the plotting toolkit (render/): its vocabulary is this file's.
using namespace render;

// ---- Page geometry, in PostScript points (1/72 in) ----

constexpr PageSize kPage = kA4Landscape;
constexpr double kMarginPt = 28;
constexpr double kGapPt = 10;       // below the header
constexpr double kRuleGapPt = 3;    // between the subtitle and the rule below it
constexpr double kStampGapPt = 22;  // between the title and the version stamp
constexpr double kFooterGapPt = 6;  // between the plot and the footnote

// ---- Type ----

constexpr Font kTitleFont{.size = 16, .bold = true};
constexpr Font kSubtitleFont{.size = 7.5};
constexpr Font kFootnoteFont{.size = 6.5};
constexpr Font kNoGlareFont{.size = 9};
constexpr Rgb kMutedInk{0.38, 0.38, 0.42};

// ---- Colour ----

constexpr Rgb fillOf(const std::array<std::uint8_t, 3>& bytes) {
  return {bytes[0] / 255.0, bytes[1] / 255.0, bytes[2] / 255.0};
}
constexpr Rgb kGreenFill = fillOf(kOcularGreenFill);
constexpr Rgb kYellowFill = fillOf(kOcularYellowFill);
constexpr Rgb kRedFill = fillOf(kOcularRedFill);

constexpr LineStyle kAfterImageLine{.colour = {0.70, 0.50, 0.00}, .width_pt = 1.0};
constexpr LineStyle kBurnLine{.colour = {0.72, 0.10, 0.10}, .width_pt = 1.0};

// The series' markers, dark over every zone: near-black and Okabe–Ito blue, circles and squares.
constexpr Rgb kSeriesBlue{0x00 / 255.0, 0x72 / 255.0, 0xB2 / 255.0};
struct SeriesLook {
  Rgb colour;
  MarkerShape shape;
};
constexpr std::array<SeriesLook, kOcularPlotMaxSeries> kSeriesLooks = {{
    {kInk, MarkerShape::kCircle},
    {kSeriesBlue, MarkerShape::kSquare},
    {kInk, MarkerShape::kSquare},
    {kSeriesBlue, MarkerShape::kCircle},
}};
constexpr double kMarkerPt = 3.6;
constexpr double kSwatchPt = 7;  // a zone's square in the legend

// ---- Axes ----

constexpr int kMinorTicksPerDecade = 9;  // at 2…9 times the decade
constexpr int kBoundarySamples = 64;     // the boundaries are straight on log-log: plenty
constexpr double kNoteInkWeight = 12;    // the "no glare" note: ink the legend keeps off
constexpr double kOverhangTopPt = 5;     // half a tick label, or a clamped marker
constexpr double kOverhangRightPt = 6;   // half of "100" beyond plotArea's right padding

// ω's decades labelled as reviewers read them ("0.1", "1", "10", "100"), not as powers of ten.
Axis angleAxis() {
  Axis axis{.range = {kOcularPlotMinAngleMrad, kOcularPlotMaxAngleMrad}, .scale = Scale::kLog};
  const int lo = static_cast<int>(std::lround(std::log10(kOcularPlotMinAngleMrad)));
  const int hi = static_cast<int>(std::lround(std::log10(kOcularPlotMaxAngleMrad)));
  for (int decade = lo; decade <= hi; ++decade) {
    const double base = std::pow(10.0, decade);
    axis.fixed_ticks.push_back({base, formatPlain(base)});
    if (decade == hi) break;
    for (int m = 2; m <= kMinorTicksPerDecade; ++m) axis.fixed_ticks.push_back({m * base, ""});
  }
  return axis;
}

Axis irradianceAxis() {
  return {.range = {kOcularPlotMinIrradianceWCm2, kOcularPlotMaxIrradianceWCm2},
          .scale = Scale::kLog};
}

// ω across the axis at evenly spaced logarithms.
std::vector<double> logSpacedAngles() {
  std::vector<double> angles;
  const double lo = std::log10(kOcularPlotMinAngleMrad), hi = std::log10(kOcularPlotMaxAngleMrad);
  for (int i = 0; i <= kBoundarySamples; ++i)
    angles.push_back(std::pow(10.0, lo + (hi - lo) * i / kBoundarySamples));
  return angles;
}

// ---- Zones ----

using Boundary = std::function<double(double)>;  // ω (mrad) to E_r (W/cm²)

// Everything above `boundary` in the data area, in `colour`. The polygon runs along the boundary
// and back along a line just above the area; where the boundary leaves the area at the top, what
// lies between them is outside the clip.
void fillAbove(Canvas& canvas, const Plot& plot, const Boundary& boundary, const Rgb& colour) {
  const Canvas::Saved saved = canvas.save();
  canvas.rectangle(plot.area);
  canvas.clip();
  bool first = true;
  for (const double angle : logSpacedAngles()) {
    const Point p = plot.page(angle, boundary(angle));
    first ? canvas.moveTo(p) : canvas.lineTo(p);
    first = false;
  }
  canvas.lineTo({plot.area.x1, plot.area.y0 - 1});
  canvas.lineTo({plot.area.x0, plot.area.y0 - 1});
  canvas.setColour(colour);
  canvas.fill();
}

// Green everywhere, yellow above the after-image boundary, red above the burn boundary: the
// classification's order (ocular_hazard.h), so that where the after-image boundary lies above
// the burn boundary (ω below about 1.24 mrad) there is no yellow.
void fillZones(Canvas& canvas, const Plot& plot) {
  {
    const Canvas::Saved saved = canvas.save();
    canvas.rectangle(plot.area);
    canvas.setColour(kGreenFill);
    canvas.fill();
  }
  fillAbove(canvas, plot, afterImageThresholdWCm2, kYellowFill);
  fillAbove(canvas, plot, retinalBurnThresholdWCm2, kRedFill);
}

void drawBoundary(Canvas& canvas, Plot& plot, const Boundary& boundary, const LineStyle& style) {
  std::vector<DataPoint> points;
  for (const double angle : logSpacedAngles()) points.push_back({angle, boundary(angle)});
  drawLine(canvas, plot, points, style);
}

// ---- Points ----

struct Tally {
  int green = 0, yellow = 0, red = 0;
  int events() const { return green + yellow + red; }
};

// The series' points where they are drawn: inside the axes, or at the nearest edge.
struct PlacedPoints {
  std::vector<DataPoint> inside, beyond;
  Tally tally;
};

PlacedPoints place(const OcularPlotSeries& series) {
  PlacedPoints placed;
  for (const OcularPlotPoint& p : series.points) {
    const double x =
        std::clamp(p.subtended_angle_mrad, kOcularPlotMinAngleMrad, kOcularPlotMaxAngleMrad);
    const double y = std::clamp(p.retinal_irradiance_w_cm2, kOcularPlotMinIrradianceWCm2,
                                kOcularPlotMaxIrradianceWCm2);
    const bool inside = x == p.subtended_angle_mrad && y == p.retinal_irradiance_w_cm2;
    (inside ? placed.inside : placed.beyond).push_back({x, y});
    // validate() has refused what classify would refuse.
    switch (classify(p.retinal_irradiance_w_cm2, p.subtended_angle_mrad)
                .value_or(OcularClass::kLowAfterImage)) {
      case OcularClass::kLowAfterImage:
        ++placed.tally.green;
        break;
      case OcularClass::kAfterImage:
        ++placed.tally.yellow;
        break;
      case OcularClass::kRetinalBurn:
        ++placed.tally.red;
        break;
    }
  }
  return placed;
}

MarkerStyle seriesMarker(std::size_t i, bool hollow) {
  return {.colour = kSeriesLooks[i].colour,
          .shape = kSeriesLooks[i].shape,
          .size_pt = kMarkerPt,
          .hollow = hollow};
}

// "array-1: 212 events (180 green, 32 yellow, 0 red)", or "array-1: no glare".
std::string seriesLabel(const OcularPlotSeries& series, const Tally& tally) {
  const std::string name = series.label.empty() ? std::string("glare") : series.label;
  if (tally.events() == 0) return name + ": no glare";
  return fmt::format("{}: {} event{} ({} green, {} yellow, {} red)", name, tally.events(),
                     tally.events() == 1 ? "" : "s", tally.green, tally.yellow, tally.red);
}

// ---- Legend ----

MarkerStyle zoneSwatch(const Rgb& colour) {
  return {.colour = colour, .shape = MarkerShape::kSquare, .size_pt = kSwatchPt};
}

// "3.59·10⁻⁵": a coefficient as written in the paper.
std::string scientific(double value) {
  const int exponent = static_cast<int>(std::floor(std::log10(value)));
  const double mantissa = value / std::pow(10.0, exponent);
  return fmt::format("{}\u00B7{}", formatSignificant(mantissa, 3), formatPowerOfTen(exponent));
}

std::vector<LegendEntry> zoneLegend() {
  const auto zone = [](OcularClass c, const Rgb& colour) {
    return LegendEntry{fmt::format("{}: {}", ocularClassName(c), ocularClassWords(c)), std::nullopt,
                       zoneSwatch(colour)};
  };
  return {
      zone(OcularClass::kRetinalBurn, kRedFill),
      zone(OcularClass::kAfterImage, kYellowFill),
      zone(OcularClass::kLowAfterImage, kGreenFill),
      {fmt::format("retinal burn: E\u1D63 = {}/\u03C9",
                   formatPlain(kRetinalBurnCoefficientWCm2Rad)),
       kBurnLine, std::nullopt},
      {fmt::format("after-image: E\u1D63 = {} \u03C9^\u2212{}",
                   scientific(kAfterImageCoefficientWCm2), formatPlain(-kAfterImageExponent)),
       kAfterImageLine, std::nullopt},
  };
}

// ---- The plot ----

void drawPlotIn(Canvas& canvas, const Box& frame, const OcularPlotContent& c) {
  // Room inside the box for what overhangs the data area (plotArea leaves none): the top tick
  // label and a point clamped to the top edge above it, the last tick label ("100") right of it.
  const Box inner{frame.x0, frame.y0 + kOverhangTopPt, frame.x1 - kOverhangRightPt, frame.y1};
  Plot plot{.area = plotArea(inner), .x = angleAxis(), .y = irradianceAxis()};
  fillZones(canvas, plot);
  drawAxes(canvas, plot,
           {.x = "subtended source angle \u03C9 (mrad)", .y = "retinal irradiance (W/cm\u00B2)"});
  drawBoundary(canvas, plot, afterImageThresholdWCm2, kAfterImageLine);
  drawBoundary(canvas, plot, retinalBurnThresholdWCm2, kBurnLine);

  std::vector<PlacedPoints> placed;
  for (const OcularPlotSeries& s : c.series) placed.push_back(place(s));
  // The last series first: the first stays on top where they overlap.
  for (std::size_t i = placed.size(); i-- > 0;) {
    drawMarkers(canvas, plot, placed[i].inside, seriesMarker(i, false));
    drawMarkers(canvas, plot, placed[i].beyond, seriesMarker(i, true));
  }

  int events = 0;
  std::size_t beyond = 0;
  for (const PlacedPoints& p : placed) {
    events += p.tally.events();
    beyond += p.beyond.size();
  }
  if (events == 0) {
    const Point centre{(plot.area.x0 + plot.area.x1) / 2, (plot.area.y0 + plot.area.y1) / 2};
    const std::string note = "no glaring event";
    drawText(canvas, {centre.x, centre.y + kBaselineBelowMiddleEm * kNoGlareFont.size}, note,
             {kNoGlareFont, kMutedInk, Align::kCentre});
    const double half = textWidth(canvas, note, kNoGlareFont) / 2;
    for (const double along : {-1.0, 0.0, 1.0})
      plot.ink.push_back({{centre.x + along * half, centre.y}, kNoteInkWeight});
  }

  std::vector<LegendEntry> legend = zoneLegend();
  for (std::size_t i = 0; i < c.series.size(); ++i)
    legend.push_back(
        {seriesLabel(c.series[i], placed[i].tally), std::nullopt, seriesMarker(i, false)});
  if (beyond > 0)
    legend.push_back({fmt::format("beyond the axes, drawn hollow at the edge: {}", beyond),
                      std::nullopt, seriesMarker(0, true)});
  drawLegend(canvas, plot, legend);
}

// ---- The page ----

std::vector<std::string> subtitleLines(Canvas& canvas, const OcularPlotContent& c, double width) {
  return c.subtitle.empty() ? std::vector<std::string>{}
                            : wrapText(canvas, c.subtitle, width, kSubtitleFont);
}

// Title, version stamp, subtitle and a rule across `page`'s top; returns the header's bottom.
double drawHeader(Canvas& canvas, const OcularPlotContent& c, const Box& page) {
  const std::string stamp = fmt::format("glarecam {}", kVersion);
  const double title_baseline = page.y0 + kTitleFont.size;
  drawText(canvas, {page.x1, title_baseline}, stamp, {kSubtitleFont, kMutedInk, Align::kRight});
  const std::string title = c.title.empty() ? std::string("Ocular hazard") : c.title;
  const double room = page.width() - textWidth(canvas, stamp, kSubtitleFont) - kStampGapPt;
  const double scale = std::min(1.0, room / textWidth(canvas, title, kTitleFont));
  drawText(canvas, {page.x0, title_baseline}, title, {{kTitleFont.size * scale, true}});
  double baseline = page.y0 + lineHeight(kTitleFont) + kSubtitleFont.size;
  const std::vector<std::string> lines = subtitleLines(canvas, c, page.width());
  for (const std::string& line : lines) {
    drawText(canvas, {page.x0, baseline}, line, {kSubtitleFont, kMutedInk});
    baseline += lineHeight(kSubtitleFont);
  }
  const double bottom = page.y0 + lineHeight(kTitleFont) +
                        static_cast<double>(lines.size()) * lineHeight(kSubtitleFont) + kRuleGapPt;
  drawSegment(canvas, {page.x0, bottom}, {page.x1, bottom}, kRuleStyle);
  return bottom;
}

std::string footnote() {
  return "Zones and boundaries: C. K. Ho, C. M. Ghanbari, R. B. Diver, J. Sol. Energy Eng. 133 "
         "(2011) 031021, for a glance (the blink response, about 0.15 s). Retinal irradiance "
         "from the luminance seen, E\u1D63 = \u03C0 d\u209A\u00B2 \u03C4 L / (4 f\u00B2 K), "
         "with the eye of the subtitle (SGHAT's defaults: d\u209A = 2 mm, f = 17 mm, "
         "\u03C4 = 0.5; K = 93 lm/W). See docs/ocular-hazard.md.";
}

void drawPage(Canvas& canvas, const OcularPlotContent& c) {
  paint(canvas, kWhite);
  const Box page{kMarginPt, kMarginPt, kPage.width_pt - kMarginPt, kPage.height_pt - kMarginPt};
  const double header_bottom = drawHeader(canvas, c, page);
  const std::vector<std::string> notes = wrapText(canvas, footnote(), page.width(), kFootnoteFont);
  const double notes_pt = static_cast<double>(notes.size()) * lineHeight(kFootnoteFont);
  const Box frame{page.x0, header_bottom + kGapPt, page.x1, page.y1 - notes_pt - kFooterGapPt};
  drawPlotIn(canvas, frame, c);
  double baseline = page.y1 - notes_pt + kFootnoteFont.size;
  for (const std::string& line : notes) {
    drawText(canvas, {page.x0, baseline}, line, {kFootnoteFont, kMutedInk});
    baseline += lineHeight(kFootnoteFont);
  }
  if (!c.mark.empty()) drawPageMark(canvas, kPage, c.mark, c.mark_note, /*over=*/true);
}

// ---- Validation ----

bool positiveFinite(double value) { return std::isfinite(value) && value > 0; }

Status validate(const OcularPlotContent& c) {
  const auto refuse = [&c](const std::string& problem) {
    return badInput(fmt::format("ocular hazard plot \"{}\": {}", c.title, problem));
  };
  if (c.series.size() > static_cast<std::size_t>(kOcularPlotMaxSeries))
    return refuse(fmt::format("{} series: at most {}", c.series.size(), kOcularPlotMaxSeries));
  for (std::size_t i = 0; i < c.series.size(); ++i) {
    const OcularPlotSeries& s = c.series[i];
    if (s.label.empty() && c.series.size() > 1)
      return refuse(fmt::format("series {} of {} has no label", i + 1, c.series.size()));
    for (std::size_t j = 0; j < s.points.size(); ++j) {
      const OcularPlotPoint& p = s.points[j];
      if (!positiveFinite(p.subtended_angle_mrad) || !positiveFinite(p.retinal_irradiance_w_cm2))
        return refuse(fmt::format(
            "point {} of series \"{}\": \u03C9 {} mrad, E\u1D63 {} W/cm\u00B2 (both must be "
            "positive and finite)",
            j + 1, s.label, p.subtended_angle_mrad, p.retinal_irradiance_w_cm2));
    }
  }
  return {};
}

}  // namespace ocular_hazard_plot

Status drawOcularHazardPlot(render::Canvas& canvas, const render::Box& frame,
                            const OcularPlotContent& content) {
  GLARECAM_CHECK(ocular_hazard_plot::validate(content));
  ocular_hazard_plot::drawPlotIn(canvas, frame, content);
  return canvas.status();
}

Status writeOcularHazardPlot(const OcularPlotContent& content,
                             const std::filesystem::path& png_path,
                             const std::filesystem::path& svg_path) {
  GLARECAM_CHECK(ocular_hazard_plot::validate(content));
  const render::PageDrawing draw = [&content](render::Canvas& canvas) {
    ocular_hazard_plot::drawPage(canvas, content);
  };
  GLARECAM_CHECK(render::writePngPage(png_path, ocular_hazard_plot::kPage, draw));
  return render::writeSvgPage(svg_path, ocular_hazard_plot::kPage, draw);
}

}  // namespace glarecam::hazard
