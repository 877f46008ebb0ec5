#include "pipeline/datasheet.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/version.h"
#include "pipeline/facet_model.h"
#include "pipeline/glare_profile.h"
#include "pipeline/limit_curve.h"
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
#include "render/text.h"
#include "render/text_table.h"

namespace glarecam::pipeline {
namespace {

// Drawn with the plotting toolkit (render/): its vocabulary is this file's.
using namespace render;

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- Page geometry, in PostScript points (1/72 in) ----

constexpr double kPageWidthPt = kA4Landscape.width_pt;
constexpr double kPageHeightPt = kA4Landscape.height_pt;
constexpr double kMarginPt = 28;
constexpr double kTitleBlockHeightPt =
    31;                                 // the title's line, down to the subtitle's first baseline
constexpr double kHeaderRuleGapPt = 9;  // the last subtitle line's baseline to the rule
constexpr double kGapPt = 10;           // between blocks
constexpr double kSectionGapPt = 15;    // between the two tables
constexpr double kColumnGapPt = 22;     // between the plots and the tables
constexpr double kPlotColumnWidthPt = 400;
constexpr double kBlockTitleHeightPt = 18;  // a plot's or table's title, above it

// ---- Type ----

constexpr Font kTitleFont{.size = 16, .bold = true};
// The subtitle wraps to as many lines as it needs at this size, never shrinks: the camera and
// calibration text of a real sheet made one line of it about 2 pt high.
constexpr Font kSubtitleFont{.size = 7.5};
constexpr Font kSectionFont{.size = 9.5, .bold = true};
constexpr Font kTableFont{.size = 8.5};
constexpr Font kNoteFont{.size = 6.8};

// ---- Colour and lines ----

constexpr Rgb kMutedInk{0.38, 0.38, 0.42};
constexpr Rgb kBlue{0.12, 0.38, 0.68};
constexpr Rgb kOrange{0.88, 0.45, 0.05};
constexpr Rgb kRed{0.80, 0.12, 0.12};
constexpr Rgb kGreen{0.13, 0.55, 0.25};
constexpr Rgb kModelGrey{0.55, 0.55, 0.58};
constexpr double kExtrapolationLightening = 0.45;  // toward white

constexpr LineStyle kLimitStyle{.colour = kRed, .width_pt = 1.3, .dash = Dash::kDashed};
constexpr LineStyle kCosineStyle{.colour = kBlue, .width_pt = 1.3};
constexpr LineStyle kBiquadraticStyle{.colour = kOrange, .width_pt = 1.3};
constexpr LineStyle kVerticalStyle{.colour = kBlue, .width_pt = 1.3};
constexpr LineStyle kHorizontalStyle{.colour = kGreen, .width_pt = 1.3};
constexpr LineStyle kModelNsStyle{.colour = kModelGrey, .width_pt = 0.8, .dash = Dash::kLongDashed};
constexpr LineStyle kModelEwStyle{.colour = kModelGrey, .width_pt = 0.8, .dash = Dash::kDashed};
constexpr LineStyle kExtrapolationKeyStyle{
    .colour = kModelGrey, .width_pt = 1.0, .dash = Dash::kDotted};

constexpr MarkerStyle kLmaxMarker{.colour = kInk};
constexpr MarkerStyle kLmaxBoundMarker{.colour = kInk, .hollow = true};  // Lmax only a bound
constexpr MarkerStyle kSuspectMarker{.colour = kRed, .hollow = true};    // frames disagree
constexpr MarkerStyle kVerticalMarker{.colour = kBlue};
constexpr MarkerStyle kHorizontalMarker{
    .colour = kGreen, .shape = MarkerShape::kSquare, .size_pt = 4.2};

// ---- Numbers ----

// Significant digits of a luminance (a measurement is not known better: 59 713 400 would claim
// eight) and of a fit parameter.
constexpr int kLuminanceDigits = 4;
constexpr int kParameterDigits = 4;
constexpr int kAxisDecimals = 2;  // limit-ellipse axes, degrees

std::string formatLuminance(double cd_m2) { return formatGrouped(cd_m2, kLuminanceDigits); }

// ---- Lines ----

// A fit's line where it is extrapolated: lighter, dotted.
LineStyle extrapolated(const LineStyle& style) {
  return {.colour = lightened(style.colour, kExtrapolationLightening),
          .width_pt = style.width_pt,
          .dash = Dash::kDotted};
}

// ---- Plots: α in degrees across, the plotted quantity up ----

constexpr Range kAlphaRangeDeg{0, 90};
constexpr Axis kAlphaAxis{.range = kAlphaRangeDeg, .step = 10};
constexpr const char* kAlphaTitle = "angle of incidence \u03b1 (\u00b0)";
constexpr Range kEmptyLmaxRangeCdM2{1e4, 1e8};  // the Lmax axis of a sweep without luminances
constexpr double kAxesHeadroom = 1.15;          // above the largest axis: room for the legend
constexpr double kEmptyAxesTopDeg = 10;         // the axes plot of a sweep without ellipses

// A fitted function: solid over the measured range, lighter and dotted where extrapolated
// within `shown` (default 0–80°).
void drawFit(Canvas& canvas, Plot& plot, const PlotFunction& f, Range measured_deg,
             const LineStyle& style, std::optional<Range> shown = std::nullopt) {
  const Range all =
      shown.value_or(Range{kAlphaRangeDeg.lo, std::max(kMaxLimitAlphaDeg, measured_deg.hi)});
  drawCurve(canvas, plot, f, {all.lo, std::min(all.hi, measured_deg.lo)}, extrapolated(style));
  drawCurve(canvas, plot, f, {std::max(all.lo, measured_deg.hi), all.hi}, extrapolated(style));
  drawCurve(canvas, plot, f, {std::max(all.lo, measured_deg.lo), std::min(all.hi, measured_deg.hi)},
            style);
}

// Where the module glares by the fits, as one range (first onset to last end); none: nowhere.
std::optional<Range> glaringRange(const DatasheetContent& content) {
  const std::vector<AlphaRange> ranges = glareRanges(*content.fits, content.limit);
  if (ranges.empty()) return std::nullopt;
  return Range{ranges.front().from_deg, ranges.back().to_deg};
}

// ---- The two plots ----

std::string r2Label(const std::string& what, const FitQuality& quality) {
  return fmt::format("{}, R\u00b2 = {:.4f}", what, quality.r2);
}

// The data area of a plot inside its block, below the block's title.
Box dataArea(const Box& block) {
  return plotArea({block.x0, block.y0 + kBlockTitleHeightPt, block.x1, block.y1});
}

void drawBlockTitle(Canvas& canvas, const Box& block, const std::string& title) {
  drawText(canvas, {block.x0, block.y0 + kSectionFont.size}, title, {kSectionFont});
}

// The α range a fit was measured over: all luminance rows, or an axis's rows with an ellipse.
Range measuredRange(const SweepFits& fits) { return {fits.alpha_min_deg, fits.alpha_max_deg}; }
Range measuredRange(const AxisFit& axis) { return {axis.alpha_min_deg, axis.alpha_max_deg}; }

// Whether a fit measured over `measured` is drawn extrapolated somewhere in 0–80°.
bool extrapolates(Range measured) {
  return measured.lo > kAlphaRangeDeg.lo || measured.hi < kMaxLimitAlphaDeg;
}

// Measured points, the limit curve, and the fits over the measured range (not their
// extrapolations, which may run off to any value).
std::vector<double> lmaxPlotValues(const SweepTable& table, const SweepFits& fits,
                                   const PlotFunction& limit,
                                   const std::vector<PlotFunction>& fitted) {
  std::vector<double> values = sample(limit, {kAlphaRangeDeg.lo, kMaxLimitAlphaDeg});
  for (const SweepRow& row : table.rows) values.push_back(row.lmax_cd_m2);
  for (const PlotFunction& f : fitted) {
    const std::vector<double> v = sample(f, measuredRange(fits));
    values.insert(values.end(), v.begin(), v.end());
  }
  return values;
}

void drawLmaxPlot(Canvas& canvas, const DatasheetContent& content, const Box& block) {
  const SweepFits& fits = *content.fits;
  const PlotFunction limit = [&](double a) { return content.limit.at(a).value_or(kNaN); };
  const PlotFunction cosine = [&](double a) { return fits.cosine.curve(a); };
  const PlotFunction biquadratic = [&](double a) { return fits.biquadratic.curve(a); };
  Plot plot{.area = dataArea(block),
            .x = kAlphaAxis,
            .y = logAxis(lmaxPlotValues(*content.table, fits, limit, {cosine, biquadratic}),
                         kEmptyLmaxRangeCdM2)};
  drawBlockTitle(canvas, block, "Maximum luminance");
  drawAxes(canvas, plot, {.x = kAlphaTitle, .y = "Lmax (cd/m\u00b2)"});
  drawCurve(canvas, plot, limit, {kAlphaRangeDeg.lo, kMaxLimitAlphaDeg}, kLimitStyle);
  drawFit(canvas, plot, cosine, measuredRange(fits), kCosineStyle);
  drawFit(canvas, plot, biquadratic, measuredRange(fits), kBiquadraticStyle);
  std::vector<DataPoint> measured, bounds, suspects;
  for (const SweepRow& row : content.table->rows)
    (row.isSuspect()          ? suspects
     : row.lmax_bound.empty() ? measured
                              : bounds)
        .push_back({row.alpha_deg, row.lmax_cd_m2});
  drawMarkers(canvas, plot, measured, kLmaxMarker);
  drawMarkers(canvas, plot, bounds, kLmaxBoundMarker);
  drawMarkers(canvas, plot, suspects, kSuspectMarker);
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
  if (!suspects.empty())
    legend.push_back(
        {"suspect: frames disagree (hollow; listed below)", std::nullopt, kSuspectMarker});
  if (extrapolates(measuredRange(fits)))
    legend.push_back({"fit extrapolated", kExtrapolationKeyStyle, {}});
  drawLegend(canvas, plot, legend);
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
PlotFunction facetModelCurve(double beta_deg, double FacetSpread::*half_spread) {
  return [beta_deg, half_spread](double alpha_deg) {
    const FacetSpread spread = facetSpread(alpha_deg, beta_deg);
    return spread.valid ? 2 * spread.*half_spread : kNaN;
  };
}

std::vector<PlotFunction> modelCurves(const std::optional<double>& beta_deg) {
  if (!beta_deg) return {};
  return {facetModelCurve(*beta_deg, &FacetSpread::gamma_ns_deg),
          facetModelCurve(*beta_deg, &FacetSpread::gamma_ew_deg)};
}

// The model's curves (under everything else) and their legend entries.
std::vector<LegendEntry> drawModel(Canvas& canvas, Plot& plot,
                                   const std::optional<double>& beta_deg) {
  const std::vector<PlotFunction> curves = modelCurves(beta_deg);
  if (curves.empty()) return {};
  const std::array<LineStyle, 2> styles = {kModelNsStyle, kModelEwStyle};
  const std::array<const char*, 2> facets = {"N\u2013S", "E\u2013W"};
  std::vector<LegendEntry> legend;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    drawCurve(canvas, plot, curves[i], kAlphaRangeDeg, styles[i]);
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
  for (const PlotFunction& f : modelCurves(content.model_beta_deg)) {
    const std::vector<double> v = sample(f, kAlphaRangeDeg);
    values.insert(values.end(), v.begin(), v.end());
  }
  return values;
}

LegendEntry axisLegendEntry(const AxisSeries& s) {
  if (!s.fit->logistic) return {s.name + " (not fitted)", std::nullopt, s.marker};
  return {r2Label(s.name + ", logistic fit", s.fit->logistic->quality), s.line, s.marker};
}

void drawAxisSeries(Canvas& canvas, Plot& plot, const DatasheetContent& content,
                    const AxisSeries& s) {
  // An axis exists only where the module glares: its fit is drawn there only (it can
  // extrapolate to anything elsewhere), as in glare-profile.json.
  const std::optional<Range> glaring = glaringRange(content);
  // Where an extrapolated fit runs off physical values it is not drawn (as not exported).
  const PlotFunction physical = [curve = s.fit->logistic ? s.fit->logistic->curve
                                                         : PlotFunction()](double alpha_deg) {
    const double axis_deg = curve(alpha_deg);
    return isPhysicalAxisDeg(axis_deg) ? axis_deg : kNaN;
  };
  if (s.fit->logistic && glaring)
    drawFit(canvas, plot, physical, measuredRange(*s.fit), s.line, glaring);
  std::vector<DataPoint> measured, suspects;
  for (const SweepRow& row : content.table->rows)
    if (const std::optional<double>& v = row.*s.column)
      (row.isSuspect() ? suspects : measured).push_back({row.alpha_deg, *v});
  drawMarkers(canvas, plot, measured, s.marker);
  MarkerStyle hollow = s.marker;
  hollow.hollow = true;
  drawMarkers(canvas, plot, suspects, hollow);
}

void drawAxesPlot(Canvas& canvas, const DatasheetContent& content, const Box& block) {
  const SweepFits& fits = *content.fits;
  const std::vector<AxisSeries> series = {
      {"vertical", &fits.vertical, &SweepRow::vertical_deg, kVerticalStyle, kVerticalMarker},
      {"horizontal", &fits.horizontal, &SweepRow::horizontal_deg, kHorizontalStyle,
       kHorizontalMarker}};
  Plot plot{
      .area = dataArea(block),
      .x = kAlphaAxis,
      .y = linearAxisFromZero(axesPlotValues(content, series), kAxesHeadroom, kEmptyAxesTopDeg)};
  drawBlockTitle(canvas, block, "Limit-ellipse axes (full angles)");
  drawAxes(canvas, plot, {.x = kAlphaTitle, .y = "axis (\u00b0)"});
  const std::vector<LegendEntry> model_legend = drawModel(canvas, plot, content.model_beta_deg);
  std::vector<LegendEntry> legend;
  for (const AxisSeries& s : series) {
    drawAxisSeries(canvas, plot, content, s);
    legend.push_back(axisLegendEntry(s));
  }
  legend.insert(legend.end(), model_legend.begin(), model_legend.end());
  const auto axis_extrapolates = [](const AxisFit& axis) {
    return axis.logistic && extrapolates(measuredRange(axis));
  };
  if (axis_extrapolates(fits.vertical) || axis_extrapolates(fits.horizontal))
    legend.push_back({"fit extrapolated", kExtrapolationKeyStyle, std::nullopt});
  drawLegend(canvas, plot, legend);
}

// ---- Tables ----

// The row's verdict, else the method's: glare when the maximum is at or above the limit.
std::string glareCell(const SweepRow& row) {
  std::optional<bool> glare = row.glare;
  if (!glare && row.limit_cd_m2) glare = row.lmax_cd_m2 >= *row.limit_cd_m2;
  return glare ? (*glare ? "yes" : "no") : kNoValue;
}

// Lmax, with ≥ or ≤ where it is only a bound (saturated top, all dark).
std::string lmaxCell(const SweepRow& row) {
  const char* prefix = row.lmax_bound == "lower"   ? "\u2265 "
                       : row.lmax_bound == "upper" ? "\u2264 "
                                                   : "";
  return prefix + formatLuminance(row.lmax_cd_m2);
}

}  // namespace

// α without a recorded uncertainty (given by hand, another tool's table): to 0.1°, an
// inclinometer's usual accuracy; the paper's table gives whole degrees, which this keeps exact.
constexpr int kAlphaDefaultDecimals = 1;

TextTable datasheetSweepTable(const SweepTable& sweep) {
  TextTable table{.rows = {{"\u03b1 (\u00b0)", "limit (cd/m\u00b2)", "Lmax (cd/m\u00b2)",
                            "vertical (\u00b0)", "horizontal (\u00b0)", "glare"}}};
  // The source illuminance each row was referred from, when any was: the sweep's own suns.
  const bool referred = std::ranges::any_of(sweep.rows, &SweepRow::isReferred);
  if (referred) table.rows.front().push_back("E (klx)");
  for (const SweepRow& row : sweep.rows) {
    table.rows.push_back(
        {formatToUncertainty(row.alpha_deg, row.alpha_uncertainty_deg, kAlphaDefaultDecimals),
         row.limit_cd_m2 ? formatLuminance(*row.limit_cd_m2) : kNoValue, lmaxCell(row),
         formatFixed(row.vertical_deg, kAxisDecimals),
         formatFixed(row.horizontal_deg, kAxisDecimals), glareCell(row)});
    if (referred)
      table.rows.back().push_back(row.source_illuminance_lx
                                      ? fmt::format("{:.1f}", *row.source_illuminance_lx / 1000)
                                      : kNoValue);
  }
  return table;
}

// What the sheet's luminances refer to, for its subtitle: "Luminances referred to E = 100 klx
// direct normal (the stacks' sources 61.2–98.4 klx, sensor)." or that they are not.
std::string referenceSentence(const SweepTable& table) {
  const std::optional<double> reference = tableReferenceIlluminance(table);
  if (reference && tableRoutes(table) == std::vector<std::string>{"brdf"})
    return fmt::format(
        " Luminances computed from the BRDF under E = {:g} klx direct normal (L = BRDF \u00b7 E "
        "\u00b7 cos "
        "\u03b1 over the sun's disc).",
        *reference / 1000);
  if (reference)
    return fmt::format(" Luminances at E = {:g} klx direct normal, referred from sources of {}.",
                       *reference / 1000, sourceIlluminanceRange(table));
  if (tableReferences(table).size() > 1)
    return fmt::format(" Luminances MIXED: {}.", mixedReferences(table));
  return fmt::format(" Luminances {}: {}.", kUnreferredWord, kUnreferredNote);
}

namespace {

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
  if (!column.quality || i >= column.quality->parameters.size()) return kNoValue;
  std::string cell = formatSignificant(column.quality->parameters[i], kParameterDigits);
  // An ill-conditioned fit's standard errors are huge and say only what its flag says.
  const auto& errors = column.quality->standard_errors;
  if (i < errors.size() && errors[i] && !column.quality->ill_conditioned)
    cell += fmt::format(" \u00b1 {:.2g}", *errors[i]);
  return cell;
}

std::vector<std::string> qualityRow(const std::vector<FitColumn>& columns, const std::string& name,
                                    const std::function<std::string(const FitQuality&)>& cell) {
  std::vector<std::string> row = {name};
  for (const FitColumn& c : columns) row.push_back(c.quality ? cell(*c.quality) : kNoValue);
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
  table.rows.push_back(qualityRow(
      columns, "RMSE", [](auto& q) { return formatSignificant(q.rmse, kParameterDigits); }));
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

// "by the fits it glares for α 49.7–80.0°", or that it does not.
std::string glareRangesText(const DatasheetContent& content) {
  const std::vector<AlphaRange> ranges = glareRanges(*content.fits, content.limit);
  if (ranges.empty())
    return fmt::format("by the fits it does not glare at any \u03b1 from 0 to {:g}\u00b0",
                       kMaxLimitAlphaDeg);
  std::string text;
  bool extrapolated = false;
  const SweepFits& fits = *content.fits;
  for (const AlphaRange& r : ranges) {
    text +=
        fmt::format("{}{:.1f}\u2013{:.1f}\u00b0", text.empty() ? "" : ", ", r.from_deg, r.to_deg);
    extrapolated = extrapolated || r.from_deg < fits.alpha_min_deg || r.to_deg > fits.alpha_max_deg;
  }
  // The fits are measured over their rows' α only: beyond, the range is extrapolated.
  if (extrapolated)
    text += fmt::format(" (measured over \u03b1 {:.1f}\u2013{:.1f}\u00b0, extrapolated beyond)",
                        fits.alpha_min_deg, fits.alpha_max_deg);
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
  // What the rows were measured with, when the table says: " Camera sim SIM-0001; calibration
  // 55e5f09d95ab9da6 of 2026-06-21, K 1500 ± 18.9 cd/m² per DN/µs."
  std::vector<std::string> measured;
  const std::vector<std::string> routes = tableRoutes(*content.table);
  const bool brdf = routes == std::vector<std::string>{"brdf"};  // the goniophotometer's rows
  std::vector<std::string> cameras = tableCameras(*content.table);
  std::erase_if(cameras, [](const std::string& c) { return c.starts_with("brdf"); });
  if (!cameras.empty()) measured.push_back(fmt::format("Camera {}", fmt::join(cameras, ", ")));
  if (const auto calibrations = tableCalibrationSummaries(*content.table); !calibrations.empty())
    measured.push_back(fmt::format("calibration {}", fmt::join(calibrations, "; ")));
  const std::string measured_with =
      measured.empty() ? std::string() : fmt::format(" {}.", fmt::join(measured, "; "));
  // α as the table shows it: to its own uncertainty (not "4.99985").
  // The route first: a sheet of goniophotometer files says so, one of both routes too.
  const std::string what =
      brdf ? fmt::format("BRDF route: {} goniophotometer measurement{}", n, n == 1 ? "" : "s")
      : routes.size() > 1 ? fmt::format("Routes MIXED (camera and BRDF): {} rows", n)
                          : fmt::format("Sweep of {} stack{}", n, n == 1 ? "" : "s");
  return fmt::format(
      "{}, \u03b1 {}\u00b0 to {}\u00b0 (angle of incidence from the module "
      "normal).{} Glare when Lmax reaches {}: {}. Axes: full angles of the limit ellipse.{}",
      what, formatToUncertainty(lo->alpha_deg, lo->alpha_uncertainty_deg, kAlphaDefaultDecimals),
      formatToUncertainty(hi->alpha_deg, hi->alpha_uncertainty_deg, kAlphaDefaultDecimals),
      referenceSentence(*content.table), limit, glareRangesText(content), measured_with);
}

void drawHeader(Canvas& canvas, const DatasheetContent& content, const Box& box,
                const std::vector<std::string>& subtitle_lines) {
  const std::string version = fmt::format("glarecam {}", kVersion);
  const std::string stamp =
      content.date.empty() ? version : fmt::format("{}   \u00b7   {}", content.date, version);
  const TextStyle stamp_style{kSubtitleFont, kMutedInk, Align::kRight};
  const double title_baseline = box.y0 + kTitleFont.size;
  drawText(canvas, {box.x1, title_baseline}, stamp, stamp_style);
  const std::string title = content.module.empty() ? std::string("Glare data sheet")
                                                   : "Glare data sheet \u2014 " + content.module;
  const double room = box.width() - textWidth(canvas, stamp, kSubtitleFont) - kColumnGapPt;
  const double scale = std::min(1.0, room / textWidth(canvas, title, kTitleFont));
  drawText(canvas, {box.x0, title_baseline}, title, {{kTitleFont.size * scale, true}});
  double baseline = box.y0 + kTitleBlockHeightPt;
  for (const std::string& line : subtitle_lines) {
    drawText(canvas, {box.x0, baseline}, line, {kSubtitleFont, kMutedInk});
    baseline += lineHeight(kSubtitleFont);
  }
  drawSegment(canvas, {box.x0, box.y1}, {box.x1, box.y1}, kRuleStyle);
}

struct Layout {
  Box header, lmax_plot, axes_plot, right_column, warnings;
  std::vector<std::string> subtitle_lines;  // wrapped to the header's width
};

constexpr std::size_t kMaxWarningLines = 6;

std::vector<std::string> warningLines(Canvas& canvas, const std::vector<std::string>& warnings,
                                      double width_pt) {
  std::vector<std::string> lines;
  std::size_t shown = 0;
  for (const std::string& warning : warnings) {
    const std::vector<std::string> wrapped =
        wrapText(canvas, "\u2022 " + warning, width_pt, kNoteFont);
    if (lines.size() + wrapped.size() > kMaxWarningLines) break;
    lines.insert(lines.end(), wrapped.begin(), wrapped.end());
    ++shown;
  }
  if (shown < warnings.size())
    lines.push_back(fmt::format("\u2026 and {} more", warnings.size() - shown));
  return lines;
}

double warningsHeightPt(Canvas& canvas, const std::vector<std::string>& warnings, double width_pt) {
  if (warnings.empty()) return 0;
  return lineHeight(kSectionFont) +
         warningLines(canvas, warnings, width_pt).size() * lineHeight(kNoteFont);
}

Layout pageLayout(Canvas& canvas, const DatasheetContent& content) {
  const Box page{kMarginPt, kMarginPt, kPageWidthPt - kMarginPt, kPageHeightPt - kMarginPt};
  const double plot_right = page.x0 + kPlotColumnWidthPt;
  const double warnings_pt = warningsHeightPt(canvas, content.fits->warnings, kPlotColumnWidthPt);
  std::vector<std::string> subtitle_lines =
      wrapText(canvas, subtitle(content), page.width(), kSubtitleFont);
  const double header_pt = kTitleBlockHeightPt +
                           (subtitle_lines.size() - 1) * lineHeight(kSubtitleFont) +
                           kHeaderRuleGapPt;
  const double body_top = page.y0 + header_pt + kGapPt;
  const double plots_bottom = page.y1 - (warnings_pt > 0 ? warnings_pt + kGapPt : 0);
  const double plot_split = (body_top + plots_bottom) / 2;
  return {.header = {page.x0, page.y0, page.x1, page.y0 + header_pt},
          .lmax_plot = {page.x0, body_top, plot_right, plot_split - kGapPt / 2},
          .axes_plot = {page.x0, plot_split + kGapPt / 2, plot_right, plots_bottom},
          .right_column = {plot_right + kColumnGapPt, body_top, page.x1, page.y1},
          .warnings = {page.x0, page.y1 - warnings_pt, plot_right, page.y1},
          .subtitle_lines = std::move(subtitle_lines)};
}

double notesHeightPt(Canvas& canvas, double width_pt) {
  double lines = 0;
  for (const std::string& note : fitNotes())
    lines += wrapText(canvas, note, width_pt, kNoteFont).size();
  return lines * lineHeight(kNoteFont);
}

// The sweep table on top, the fit parameters right below it: the sweep table shrinks (long
// sweeps) so that both fit.
void drawTables(Canvas& canvas, const DatasheetContent& content, const Box& column) {
  const TextTable fits = fitTable(*content.fits);
  const double fits_pt = kBlockTitleHeightPt + tableHeightPt(fits, kTableFont) + kGapPt / 2 +
                         notesHeightPt(canvas, column.width());
  drawBlockTitle(canvas, column, "Sweep");
  const Box sweep_box{column.x0, column.y0 + kBlockTitleHeightPt, column.x1,
                      column.y1 - fits_pt - kSectionGapPt};
  const double sweep_pt =
      drawTable(canvas, datasheetSweepTable(*content.table), sweep_box, kTableFont);
  const Box fits_block{column.x0, sweep_box.y0 + sweep_pt + kSectionGapPt, column.x1, column.y1};
  drawBlockTitle(canvas, fits_block, "Fit parameters");
  const Box fits_box{fits_block.x0, fits_block.y0 + kBlockTitleHeightPt, fits_block.x1,
                     fits_block.y1};
  const double table_pt = drawTable(canvas, fits, fits_box, kTableFont);
  drawParagraphs(canvas, {column.x0, fits_box.y0 + table_pt + kGapPt / 2 + kNoteFont.size},
                 column.width(), fitNotes(), {kNoteFont, kMutedInk});
}

void drawWarnings(Canvas& canvas, const std::vector<std::string>& warnings, const Box& box) {
  if (warnings.empty()) return;
  drawText(canvas, {box.x0, box.y0 + kSectionFont.size}, "Warnings", {kSectionFont});
  double y = box.y0 + lineHeight(kSectionFont) + kNoteFont.size;
  for (const std::string& line : warningLines(canvas, warnings, box.width())) {
    drawText(canvas, {box.x0, y}, line, {kNoteFont, kMutedInk});
    y += lineHeight(kNoteFont);
  }
}

}  // namespace

std::optional<PageMark> datasheetPageMark(const SweepTable& sweep) {
  if (isSimulated(sweep)) return PageMark{"SIMULATED", kSimulatedNote};
  if (!tableReferenceIlluminance(sweep)) return PageMark{"UNREFERRED", kUnreferredNote};
  return std::nullopt;
}

namespace {

void drawDatasheet(Canvas& canvas, const DatasheetContent& content) {
  paint(canvas, kWhite);
  // Across the page's face, pale red under everything drawn after it: a sheet of the simulated
  // camera's stacks can never pass for a measurement, whatever is cut from it. (Opaque pale red
  // drawn first rather than translucent red drawn last: the same look, and no group surface.)
  // An unreferred sheet is marked the same way: its luminances belong to the day's sky.
  if (const std::optional<PageMark> mark = datasheetPageMark(*content.table))
    drawPageMark(canvas, kA4Landscape, mark->word, mark->note, /*over=*/false);
  const Layout layout = pageLayout(canvas, content);
  drawHeader(canvas, content, layout.header, layout.subtitle_lines);
  drawLmaxPlot(canvas, content, layout.lmax_plot);
  drawAxesPlot(canvas, content, layout.axes_plot);
  drawTables(canvas, content, layout.right_column);
  drawWarnings(canvas, content.fits->warnings, layout.warnings);
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
  const PageDrawing draw = [&content](Canvas& canvas) { drawDatasheet(canvas, content); };
  const PdfMetadata metadata{.title = "Glare data sheet " + content.module,
                             .creator = std::string("glarecam ") + kVersion};
  GLARECAM_CHECK(writePdfPage(directory / kDatasheetPdf, kA4Landscape, draw, metadata));
  GLARECAM_CHECK(writeSvgPage(directory / kDatasheetSvg, kA4Landscape, draw));
  return writePngPage(directory / kDatasheetPng, kA4Landscape, draw);
}

}  // namespace glarecam::pipeline
