// The glare-hazard chart of one observer over one year (docs/hazard.md): when and for how long
// the arrays glare at it, by one glare model or two side by side (the method's "ellipse" against
// a comparison such as "circle"), so that a report shows where the models differ.
//
// Upper panel, like the sun charts of glare reports: day of the year across (month ticks from
// the year's own month lengths), local standard time of day up, later times higher; each time
// step of each day coloured by what it shows (HazardCell) in colour-blind-safe colours (Okabe–
// Ito: first model only blue, second only orange, both vermillion), the sun below the horizon
// light grey, outside the observer's counting hours a pale tint. The hours shown are those of
// the cells with the sun up (every cell but kSunDown), rounded out to whole hours; 0–24 when the
// sun never rises. A step outside the hours with the sun down is kSunDown. The cells are drawn
// as a raster at the PNG's resolution, steps aggregated into pixel rows with glare winning
// (both > first > second > none > outside hours > sun down), so that even a single glaring
// 10-s step colours at least one pixel.
// Lower panel: each model's minutes per day against the day, and the criteria's daily limit as
// a dashed line. Beside both panels, when the content gives yearly limits, the year's column:
// each model's hours in the year as a bar (its colour in the lower panel), and each criterion's
// yearly limit (LAI 30 h, CH 50 h) as a dashed line across the bars, labelled, so that the
// yearly limits read beside the daily one. Title and subtitle on top of an A4 landscape page; a
// mark (SIMULATED) across it when the content has one.
//
// Two ways out: drawn into a box of a canvas (a report page embeds it: the panels and the year's
// column fill the box, no title, no mark: the embedding page draws its own), or as a page of its
// own written as PNG and SVG (page_output.h), each atomically. The same drawing serves both.
// Errors: kBadInput, with nothing drawn or written, for content that does not describe a year
// (below), kIo when a file cannot be written.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "render/page_geometry.h"

namespace glarecam::render {
class Canvas;
}

namespace glarecam::hazard {

// What one time step of one day shows.
enum class HazardCell : std::uint8_t {
  kNone = 0,          // sun up, in the observer's hours, no glare
  kFirstOnly = 1,     // glare by the first model only (e.g. "ellipse")
  kSecondOnly = 2,    // glare by the second model only (e.g. "circle")
  kBoth = 3,          // glare by both
  kSunDown = 4,       // sun at or below the horizon
  kOutsideHours = 5,  // outside the observer's counting hours (not counted)
};

struct HazardChartSeries {
  std::string label;                    // model name, e.g. "ellipse", "circle", "cone:0.5"
  std::vector<double> minutes_per_day;  // one per day of the year
};

// A criterion's yearly limit, drawn in the year's column.
struct HazardChartLimit {
  std::string label;  // e.g. "LAI", "CH"
  double hours_per_year = 0;
};

struct HazardChartContent {
  std::string title;     // e.g. "Glare at window-3, 2027"
  std::string subtitle;  // e.g. scene and profile file names, site, "local standard time UTC+1"
  int year = 0;
  int days = 0;           // 365 or 366: columns
  int steps_per_day = 0;  // rows per day (1440 at 60-s steps, 8640 at 10-s)
  // Day-major: cells[day * steps_per_day + step], step 0 starts at local midnight.
  std::vector<HazardCell> cells{};
  std::vector<HazardChartSeries> models{};  // 1 or 2; models[0] is "first", models[1] "second"
  double threshold_minutes_per_day = 30;    // the criteria's daily limit, drawn as a dashed line
  // The criteria's yearly limits; none: no year's column (the panels take its width).
  std::vector<HazardChartLimit> yearly_limits{};
  // When not empty, across the page's face over everything, translucent (render::drawPageMark):
  // "SIMULATED" and its note for a chart from a profile of simulated stacks.
  std::string mark{}, mark_note{};
};

// Writes the chart as PNG and SVG, each atomically. kBadInput, with nothing written, when
// cells.size() != days * steps_per_day, days is not the year's 365 or 366, steps_per_day is not
// in 1…86400, models is empty or has more than 2, a series has the wrong length or a value that
// is negative or not finite, the threshold or a yearly limit is not positive (or a limit has no
// label), or a cell is not a HazardCell or shows the second model's glare on a chart of one
// model.
Status writeHazardChart(const HazardChartContent& content, const std::filesystem::path& png_path,
                        const std::filesystem::path& svg_path);

// The chart without its title filling `frame` (points, the canvas's user units); refuses what
// writeHazardChart refuses, with nothing drawn.
Status drawHazardChart(render::Canvas& canvas, const render::Box& frame,
                       const HazardChartContent& content);

}  // namespace glarecam::hazard
