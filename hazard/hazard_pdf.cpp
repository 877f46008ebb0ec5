#include "hazard/hazard_pdf.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/version.h"
#include "hazard/criteria.h"
#include "hazard/hazard_chart.h"
#include "hazard/obstruction.h"
#include "hazard/ocular_hazard.h"
#include "hazard/ocular_hazard_plot.h"
#include "hazard/scene_plan.h"
#include "pipeline/sweep_table.h"
#include "render/canvas.h"
#include "render/colour.h"
#include "render/line_style.h"
#include "render/number_format.h"
#include "render/page_geometry.h"
#include "render/page_output.h"
#include "render/rgb_surface.h"
#include "render/text.h"
#include "render/text_table.h"

namespace glarecam::hazard {
// Named after the file: in a unity build this file shares a translation unit with the library's
// other pictures, whose helpers have names of their own.
namespace hazard_pdf {

// Drawn with the plotting toolkit (render/): its vocabulary is this file's.
using namespace render;

namespace fs = std::filesystem;

// ---- Page geometry, in PostScript points (1/72 in) ----

constexpr PageSize kPage = kA4Landscape;
constexpr double kMarginPt = 28;
constexpr double kGapPt = 10;              // below the header, between blocks
constexpr double kRuleGapPt = 3;           // between the subtitle and the rule below it
constexpr double kStampGapPt = 22;         // between the title and the version stamp
constexpr double kFooterBaselinePt = 15;   // above the page's bottom edge
constexpr double kColumnGapPt = 24;        // between columns of text
constexpr double kPlanWidthPt = 470;       // the plan view's frame on the first page
constexpr double kFactKeyPt = 74;          // a fact's name, left of its value
constexpr double kParagraphGapPt = 4;      // after a paragraph
constexpr double kSectionGapPt = 8;        // before a section's heading
constexpr double kMaxResultsTextPt = 560;  // the results' sentences: lines a reader can follow
constexpr double kOcularColumnPt = 400;    // the receptor's second page: the ocular column
constexpr double kHeadingGapPt = 2;        // below a section's heading

// ---- Type ----

constexpr Font kTitleFont{.size = 16, .bold = true};
constexpr Font kSubtitleFont{.size = 7.5};
constexpr Font kSectionFont{.size = 9.5, .bold = true};
constexpr Font kTextFont{.size = 7.5};
constexpr Font kFactKeyFont{.size = 7.5, .bold = true};
constexpr Font kTableFont{.size = 8};
constexpr Font kFooterFont{.size = 6.5};
constexpr Rgb kMutedInk{0.38, 0.38, 0.42};
constexpr Rgb kAlertInk{0.75, 0.10, 0.10};  // SIMULATED, exceeded

constexpr std::size_t kWorstDayCount = 5;

// ---- Numbers and words ----

// As the summary table on stdout prints them, so that a reader finds the same numbers.
std::string minutesPerYearText(double minutes) { return fmt::format("{:.0f}", minutes); }
std::string hoursPerYearText(double hours) { return fmt::format("{:.1f}", hours); }
std::string maxMinutesText(double minutes) { return formatPlain(minutes); }
// Whole minutes where the steps make them whole, a decimal where they do not (10-s steps).
std::string minutesText(double minutes) {
  constexpr double kRoundingMin = 1e-9;  // sums of whole steps' minutes: exact but for rounding
  return std::abs(minutes - std::round(minutes)) < kRoundingMin ? fmt::format("{:.0f}", minutes)
                                                                : fmt::format("{:.1f}", minutes);
}

std::string upper(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return text;
}

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : separator) + item;
  return text;
}

// ---- What the report is made of ----

const Receptor& receptorOf(const std::vector<Receptor>& receptors, std::size_t observer) {
  for (const Receptor& receptor : receptors)
    if (observer >= receptor.first && observer < receptor.first + receptor.count) return receptor;
  return receptors.front();
}

// The distinct profiles in the order the arrays first use them.
std::vector<const ProfileTable*> distinctProfiles(const HazardReport& report) {
  std::vector<const ProfileTable*> profiles;
  for (const ProfileTable* profile : report.profiles)
    if (std::find(profiles.begin(), profiles.end(), profile) == profiles.end())
      profiles.push_back(profile);
  return profiles;
}

bool anySimulated(const HazardReport& report) {
  return std::any_of(report.profiles.begin(), report.profiles.end(),
                     [](const ProfileTable* profile) { return profile->simulated(); });
}

// "window-3", or "road-b@30m, the worst of road-b's 11 points".
std::string pointTitle(const Scene& scene, const Receptor& receptor, std::size_t o) {
  if (receptor.kind == ReceptorKind::kObserver) return scene.observers[o].name;
  return fmt::format("{}, the worst of {} {}'s {} points", scene.observers[o].name,
                     receptorKindName(receptor.kind), receptor.name, receptor.count);
}

double distanceToNearestArrayM(const Scene& scene, std::size_t o) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const ArrayPolygon& array : scene.arrays)
    nearest = std::min(nearest, norm(scene.observers[o].position_m - array.centroid_m));
  return nearest;
}

std::string compass(double azimuth_deg) {
  constexpr std::array<const char*, 8> kPoints = {"N", "NE", "E", "SE", "S", "SW", "W", "NW"};
  const auto point = static_cast<std::size_t>(std::lround(azimuth_deg / 45)) % kPoints.size();
  return kPoints[point];
}

std::string hoursText(const Observer& observer) {
  constexpr double kWholeDayH = 24;
  if (observer.from_h <= 0 && observer.to_h >= kWholeDayH) return "counts at every hour";
  return fmt::format("counts from {} to {} h local standard time", formatPlain(observer.from_h),
                     formatPlain(observer.to_h));
}

std::string viewText(const Observer& observer, ReceptorKind kind) {
  if (observer.view_azimuths_deg.empty()) return "sees in every direction";
  std::vector<std::string> directions;
  for (const double azimuth : observer.view_azimuths_deg)
    directions.push_back(fmt::format("{:.0f}° ({})", azimuth, compass(azimuth)));
  return fmt::format("{} {}, counting within ±{}° of it horizontally",
                     kind == ReceptorKind::kRoute ? "travels toward" : "looks toward",
                     joined(directions, " or "), formatPlain(observer.field_of_view_deg));
}

// The local time of day (and its offset) from localTimeText's and civilTimeText's text:
// "2027-06-21T12:05+01:00" → "12:05", "+01:00".
struct ClockText {
  std::string date, time, offset;
};
ClockText splitClock(const std::string& text, bool with_seconds) {
  constexpr std::size_t kDateLength = 10, kTimeStart = 11;
  const std::size_t time_length = with_seconds ? 8 : 5;
  return {text.substr(0, kDateLength), text.substr(kTimeStart, time_length),
          text.substr(kTimeStart + time_length)};
}

// ---- Text on the page ----

// wrapText, and a word wider than the line (a file's path) broken after its slashes.
std::vector<std::string> wrapLong(Canvas& canvas, const std::string& text, double width,
                                  const Font& font) {
  std::vector<std::string> lines;
  for (const std::string& line : wrapText(canvas, text, width, font)) {
    if (textWidth(canvas, line, font) <= width) {
      lines.push_back(line);
      continue;
    }
    std::string rest = line, piece;
    while (!rest.empty()) {
      const std::size_t slash = rest.find('/');
      const std::string part = slash == std::string::npos ? rest : rest.substr(0, slash + 1);
      rest = slash == std::string::npos ? std::string() : rest.substr(slash + 1);
      if (!piece.empty() && textWidth(canvas, piece + part, font) > width) {
        lines.push_back(piece);
        piece.clear();
      }
      piece += part;
    }
    if (!piece.empty()) lines.push_back(piece);
  }
  return lines;
}

struct Fact {
  std::string key, value;
  Rgb colour = kInk;
};

// The facts' names in bold on the left, their values wrapped right of them; the height used.
double drawFacts(Canvas& canvas, const Box& box, const std::vector<Fact>& facts) {
  double y = box.y0 + kTextFont.size;
  const double value_width = box.width() - kFactKeyPt;
  for (const Fact& fact : facts) {
    drawText(canvas, {box.x0, y}, fact.key, {kFactKeyFont, kInk});
    const std::vector<std::string> lines = wrapLong(canvas, fact.value, value_width, kTextFont);
    for (const std::string& line : lines) {
      drawText(canvas, {box.x0 + kFactKeyPt, y}, line, {kTextFont, fact.colour});
      y += lineHeight(kTextFont);
    }
    if (lines.empty()) y += lineHeight(kTextFont);
  }
  return y - kTextFont.size - box.y0;
}

double drawSection(Canvas& canvas, const Box& box, const std::string& title) {
  drawText(canvas, {box.x0, box.y0 + kSectionFont.size}, title, {kSectionFont});
  return lineHeight(kSectionFont) + kHeadingGapPt;
}

// ---- The page's frame: header, footer, mark ----

struct PageText {
  std::string title, subtitle;
};

std::vector<std::string> subtitleLines(Canvas& canvas, const PageText& text, double width) {
  return text.subtitle.empty() ? std::vector<std::string>{}
                               : wrapText(canvas, text.subtitle, width, kSubtitleFont);
}

Box pageBox() {
  return {kMarginPt, kMarginPt, kPage.width_pt - kMarginPt, kPage.height_pt - kMarginPt};
}

// The body below the header.
Box bodyBox(Canvas& canvas, const PageText& text) {
  const Box page = pageBox();
  const double header_bottom =
      page.y0 + lineHeight(kTitleFont) +
      static_cast<double>(subtitleLines(canvas, text, page.width()).size()) *
          lineHeight(kSubtitleFont) +
      kRuleGapPt;
  return {page.x0, header_bottom + kGapPt, page.x1, page.y1};
}

void drawHeader(Canvas& canvas, const PageText& text) {
  const Box page = pageBox();
  const std::string stamp = fmt::format("glarecam {}", kVersion);
  const double title_baseline = page.y0 + kTitleFont.size;
  drawText(canvas, {page.x1, title_baseline}, stamp, {kSubtitleFont, kMutedInk, Align::kRight});
  const double room = page.width() - textWidth(canvas, stamp, kSubtitleFont) - kStampGapPt;
  const double scale = std::min(1.0, room / textWidth(canvas, text.title, kTitleFont));
  drawText(canvas, {page.x0, title_baseline}, text.title, {{kTitleFont.size * scale, true}});
  double baseline = page.y0 + lineHeight(kTitleFont) + kSubtitleFont.size;
  const std::vector<std::string> lines = subtitleLines(canvas, text, page.width());
  for (const std::string& line : lines) {
    drawText(canvas, {page.x0, baseline}, line, {kSubtitleFont, kMutedInk});
    baseline += lineHeight(kSubtitleFont);
  }
  const double rule_y = page.y0 + lineHeight(kTitleFont) +
                        static_cast<double>(lines.size()) * lineHeight(kSubtitleFont) + kRuleGapPt;
  drawSegment(canvas, {page.x0, rule_y}, {page.x1, rule_y}, kRuleStyle);
}

struct Shell {
  std::string footer;  // left of the page number
  bool simulated = false;
};

void drawFooter(Canvas& canvas, const Shell& shell, std::size_t number, std::size_t total) {
  const Box page = pageBox();
  const double baseline = kPage.height_pt - kFooterBaselinePt;
  drawText(canvas, {page.x0, baseline}, shell.footer, {kFooterFont, kMutedInk});
  drawText(canvas, {page.x1, baseline}, fmt::format("page {} of {}", number, total),
           {kFooterFont, kMutedInk, Align::kRight});
}

// One page of the report: its text on top, its body drawn into the box below.
struct ReportPage {
  PageText text;
  std::function<void(Canvas&, const Box&)> body;
};

void drawReportPage(Canvas& canvas, const Shell& shell, const ReportPage& page, std::size_t number,
                    std::size_t total) {
  paint(canvas, kWhite);
  drawHeader(canvas, page.text);
  const Box body = bodyBox(canvas, page.text);
  {
    const Canvas::Saved saved = canvas.save();
    page.body(canvas, body);
  }
  drawFooter(canvas, shell, number, total);
  // Over everything: the charts' cell panels are opaque rasters that would hide a mark under them.
  if (shell.simulated)
    drawPageMark(canvas, kPage, "SIMULATED", pipeline::kSimulatedNote, /*over=*/true);
}

// ---- Flowing blocks over columns and pages ----

// A block of the flowing pages: drawn into a box as wide as its column and `height_pt` tall.
struct Block {
  double height_pt = 0;
  double gap_after_pt = 0;
  bool keep_with_next = false;  // a heading stays with what follows it
  std::function<void(Canvas&, const Box&)> draw;
};

struct PlacedBlock {
  std::size_t block = 0;
  Box box;
};

// The blocks in order down each column of `columns` in turn, a new page when the last column is
// full. A block taller than a whole column gets one of its own (and overflows it).
std::vector<std::vector<PlacedBlock>> flow(const std::vector<Block>& blocks,
                                           const std::vector<Box>& columns) {
  std::vector<std::vector<PlacedBlock>> pages(1);
  std::size_t column = 0;
  double y = columns[0].y0;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    double need = blocks[i].height_pt;
    if (blocks[i].keep_with_next && i + 1 < blocks.size())
      need += blocks[i].gap_after_pt + blocks[i + 1].height_pt;
    if (y + need > columns[column].y1 && y > columns[column].y0) {
      if (++column == columns.size()) {
        pages.emplace_back();
        column = 0;
      }
      y = columns[column].y0;
    }
    const Box& c = columns[column];
    pages.back().push_back({i, {c.x0, y, c.x1, y + blocks[i].height_pt}});
    y += blocks[i].height_pt + blocks[i].gap_after_pt;
  }
  if (pages.back().empty()) pages.pop_back();
  return pages;
}

void addHeading(std::vector<Block>& blocks, const std::string& title, bool first) {
  const double top = first ? 0 : kSectionGapPt;
  blocks.push_back(
      {.height_pt = top + lineHeight(kSectionFont),
       .gap_after_pt = kHeadingGapPt,
       .keep_with_next = true,
       .draw = [title, top](Canvas& canvas, const Box& box) {
         drawText(canvas, {box.x0, box.y0 + top + kSectionFont.size}, title, {kSectionFont});
       }});
}

// A paragraph, one block a line so that it may continue in the next column; at most
// `max_width` wide.
void addParagraph(std::vector<Block>& blocks, Canvas& measure, const std::string& text,
                  double width, const TextStyle& style = {kTextFont}) {
  const std::vector<std::string> lines = wrapLong(measure, text, width, style.font);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    blocks.push_back({.height_pt = lineHeight(style.font),
                      .gap_after_pt = i + 1 == lines.size() ? kParagraphGapPt : 0,
                      .keep_with_next = false,
                      .draw = [line = lines[i], style](Canvas& canvas, const Box& box) {
                        drawText(canvas, {box.x0, box.y0 + style.font.size}, line, style);
                      }});
  }
}

// A table in chunks that each fit a column, each with the headings.
void addTable(std::vector<Block>& blocks, const TextTable& table, double column_height) {
  const double row_pt = tableHeightPt(TextTable{.rows = {{""}}}, kTableFont);
  // A row to spare for rounding.
  const auto fitting = static_cast<std::ptrdiff_t>(column_height / row_pt) -
                       static_cast<std::ptrdiff_t>(table.header_rows) - 1;
  const auto per_chunk = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, fitting));
  for (std::size_t first = table.header_rows; first < table.rows.size(); first += per_chunk) {
    TextTable chunk = table;
    chunk.rows.assign(table.rows.begin(), table.rows.begin() + table.header_rows);
    const std::size_t end = std::min(table.rows.size(), first + per_chunk);
    chunk.rows.insert(chunk.rows.end(), table.rows.begin() + first, table.rows.begin() + end);
    blocks.push_back(
        {.height_pt = tableHeightPt(chunk, kTableFont),
         .gap_after_pt = kParagraphGapPt,
         .keep_with_next = false,
         .draw = [chunk](Canvas& canvas, const Box& box) {
           // As tall as it needs (the chunk fits its column): only the width may shrink it.
           drawTable(canvas, chunk, {box.x0, box.y0, box.x1, kPage.height_pt}, kTableFont);
         }});
  }
}

// The flowing pages of `blocks` under `text` (its title with "(continued)" after the first).
void addFlowPages(std::vector<ReportPage>& pages, Canvas& measure, const PageText& text,
                  std::shared_ptr<const std::vector<Block>> blocks, int columns) {
  const Box body = bodyBox(measure, text);
  std::vector<Box> boxes;
  const double width = (body.width() - (columns - 1) * kColumnGapPt) / columns;
  for (int c = 0; c < columns; ++c) {
    const double x0 = body.x0 + c * (width + kColumnGapPt);
    boxes.push_back({x0, body.y0, x0 + width, body.y1});
  }
  const auto placed = flow(*blocks, boxes);
  for (std::size_t p = 0; p < placed.size(); ++p) {
    PageText page_text = text;
    if (p > 0) page_text.title += " (continued)";
    pages.push_back({page_text, [blocks, page = placed[p]](Canvas& canvas, const Box&) {
                       for (const PlacedBlock& b : page) {
                         const Canvas::Saved saved = canvas.save();
                         (*blocks)[b.block].draw(canvas, b.box);
                       }
                     }});
  }
}

// ---- Page 1: the inputs and the profiles ----

std::string siteText(const HazardSite& site) {
  const sun::SiteLocation& l = site.location;
  return fmt::format("{:.4f}° {}, {:.4f}° {}, {} m above sea level", std::abs(l.latitude_deg),
                     l.latitude_deg < 0 ? "S" : "N", std::abs(l.longitude_deg),
                     l.longitude_deg < 0 ? "W" : "E", formatPlain(l.altitude_m));
}

std::string civilRuleText(DaylightSaving rule) {
  switch (rule) {
    case DaylightSaving::kEu:
      return "EU summer time (last Sunday of March to last Sunday of October, 01:00 UTC)";
    case DaylightSaving::kUs:
      return "US daylight saving time (second Sunday of March to first Sunday of November)";
    case DaylightSaving::kNone:
      break;
  }
  return "none";
}

std::string minutesMeaning(const HazardOptions& options) {
  return options.sun.kind == SunKind::kWeather
             ? "expected: with the weather file's direct sun, not the clear sky"
             : "possible: the sun is taken to shine at every step it is up";
}

std::string criterionLimits(const Criterion& criterion) {
  return fmt::format("{} min/day, {} h/year", formatPlain(criterion.max_minutes_per_day),
                     formatPlain(criterion.max_hours_per_year));
}

// "2 observers, 1 route: 13 points".
std::string receptorCounts(std::size_t observers, std::size_t routes, std::size_t areas,
                           std::size_t points) {
  std::vector<std::string> kinds;
  const auto count = [&kinds](std::size_t n, const char* kind) {
    if (n > 0) kinds.push_back(fmt::format("{} {}{}", n, kind, n == 1 ? "" : "s"));
  };
  count(observers, "observer");
  count(routes, "route");
  count(areas, "area");
  return fmt::format("{}: {} point{}", joined(kinds, ", "), points, points == 1 ? "" : "s");
}

// "receptors within 100 m of an array (Germany's LAI looks within 100 m)".
std::string distanceText(const HazardOptions& options) {
  if (!std::isfinite(options.max_distance_m)) return "every receptor and array, at any distance";
  return fmt::format("receptors within {} m of an array (Germany's LAI looks within {} m)",
                     formatPlain(options.max_distance_m), formatPlain(kDefaultMaxDistanceM));
}

std::vector<Fact> inputFacts(const HazardReport& report) {
  const Scene& scene = *report.scene;
  const HazardOptions& options = *report.options;
  const HazardResult& result = *report.result;
  std::vector<std::string> models;
  for (std::size_t m = 0; m < options.models.size(); ++m)
    models.push_back(options.models[m].name() + (m == 0 ? " (the method's)" : ""));
  std::vector<std::string> criteria;
  for (const Criterion& criterion : options.criteria)
    criteria.push_back(fmt::format("{}: {}", upper(criterion.id), criterionLimits(criterion)));
  std::size_t observers = 0, routes = 0, areas = 0;
  for (const Receptor& receptor : sceneReceptors(scene))
    ++(receptor.kind == ReceptorKind::kObserver ? observers
       : receptor.kind == ReceptorKind::kRoute  ? routes
                                                : areas);
  std::vector<std::string> obstructions;
  for (const Obstruction& obstruction : scene.obstructions)
    obstructions.push_back(obstruction.name);
  const EyeParameters& eye = options.eye;
  const std::string days = result.first_day == 0 && result.days >= 365
                               ? fmt::format("{}, all {} days", result.year, result.days)
                               : fmt::format("{}, days {} to {}", result.year, result.first_day + 1,
                                             result.first_day + result.days);
  return {
      {"scene", scene.path.string()},
      {"site", siteText(scene.site)},
      {"times",
       "local standard time " + utcOffsetText(scene.site.utc_offset_h) + " (days and counting)" +
           (report.daylight_saving == DaylightSaving::kNone
                ? ", no daylight saving"
                : "; clock times also in civil time: " + civilRuleText(report.daylight_saving))},
      {"year", days},
      {"time step", fmt::format("{} s, each sampled at its middle", result.step_s)},
      {"receptors", receptorCounts(observers, routes, areas, scene.observers.size())},
      {"distance", distanceText(options)},
      {"obstructions", obstructions.empty() ? "none" : joined(obstructions, ", ")},
      {"models", joined(models, ", ")},
      {"criteria", joined(criteria, "; ")},
      {"sun", options.sun.name() + ": " + options.sun.description()},
      {"minutes", minutesMeaning(options)},
      {"eye", fmt::format("pupil {:.1f} mm, focal length {:.0f} mm, transmission {:.2f}, "
                          "{:.0f} lm/W",
                          eye.pupil_diameter_m * 1e3, eye.focal_length_m * 1e3,
                          eye.ocular_transmission, eye.luminous_efficacy_lm_w)},
  };
}

std::string identityText(const nlohmann::json& identity) {
  std::vector<std::string> parts;
  if (identity.contains("date") && identity["date"].is_string())
    parts.push_back("date " + identity["date"].get<std::string>());
  if (identity.contains("source") && identity["source"].is_string())
    parts.push_back("source " + identity["source"].get<std::string>());
  std::vector<std::string> calibrations;
  if (identity.contains("calibrations") && identity["calibrations"].is_array())
    for (const nlohmann::json& c : identity["calibrations"])
      calibrations.push_back(c.is_string() ? c.get<std::string>() : c.dump());
  parts.push_back(calibrations.empty() ? "no calibration recorded"
                                       : "calibrations " + joined(calibrations, ", "));
  return joined(parts, "; ");
}

// How the profile's rows were measured: "camera", "BRDF (laboratory)", both, or not recorded
// (a profile of an earlier glarecam, or made from a table).
std::string routeText(const ProfileTable& profile) {
  const nlohmann::json& routes = profile.identity().value("routes", nlohmann::json::array());
  if (routes.empty())
    return "not recorded (the profile does not say whether it came from the camera or a BRDF)";
  std::string text;
  for (const nlohmann::json& route : routes) {
    const std::string name = route.get<std::string>();
    text += (text.empty() ? "" : " and ") +
            (name == "brdf" ? std::string("BRDF (a laboratory goniophotometer)")
                            : std::string("camera (luminance images)"));
  }
  return text;
}

std::vector<Fact> profileFacts(const HazardReport& report, const ProfileTable& profile) {
  std::vector<std::string> arrays;
  for (std::size_t a = 0; a < report.profiles.size(); ++a)
    if (report.profiles[a] == &profile) arrays.push_back(report.scene->arrays[a].name);
  std::vector<std::string> ranges;
  for (const pipeline::AlphaRange& range : profile.glareRanges())
    ranges.push_back(fmt::format("{}–{}°", formatPlain(range.from_deg), formatPlain(range.to_deg)));
  const std::optional<double> reference = profile.ladderReferenceLx();
  std::vector<Fact> facts{
      {"module", profile.module()},
      {"for arrays", joined(arrays, ", ")},
      {"identity", identityText(profile.identity())},
      {"file", profile.path().empty() ? std::string("(given in memory)") : profile.path().string()},
      profile.simulated()
          ? Fact{"simulated", std::string("SIMULATED: ") + pipeline::kSimulatedNote, kAlertInk}
          : Fact{"simulated", "no: made from measured stacks"},
      {"reference", reference ? fmt::format("{} lx (referred, with a contour ladder)",
                                            formatGrouped(*reference, 4))
                              : "none: not referred, or no contour ladder"},
      {"route", routeText(profile)},
      {"glares at", ranges.empty() ? "no α" : "α " + joined(ranges, ", ") + " (counted to 80°)"},
  };
  return facts;
}

void drawFirstPageColumn(Canvas& canvas, const HazardReport& report, const Box& column) {
  const Canvas::Saved saved = canvas.save();
  canvas.rectangle({column.x0, column.y0, column.x1, column.y1 + 1});
  canvas.clip();
  double y = column.y0;
  y += drawSection(canvas, {column.x0, y, column.x1, column.y1}, "Inputs");
  y += drawFacts(canvas, {column.x0, y, column.x1, column.y1}, inputFacts(report)) + kSectionGapPt;
  const std::vector<const ProfileTable*> profiles = distinctProfiles(report);
  y += drawSection(canvas, {column.x0, y, column.x1, column.y1},
                   profiles.size() == 1 ? "Module profile" : "Module profiles");
  for (const ProfileTable* profile : profiles)
    y += drawFacts(canvas, {column.x0, y, column.x1, column.y1}, profileFacts(report, *profile)) +
         kParagraphGapPt;
  y += kSectionGapPt - kParagraphGapPt;
  y += drawSection(canvas, {column.x0, y, column.x1, column.y1}, "Arrays");
  std::vector<Fact> arrays;
  for (std::size_t a = 0; a < report.scene->arrays.size(); ++a)
    arrays.push_back(
        {report.scene->arrays[a].name,
         arrayFacingText(report.scene->arrays[a]) + "; module " + report.profiles[a]->module()});
  drawFacts(canvas, {column.x0, y, column.x1, column.y1}, arrays);
}

ReportPage firstPage(const HazardReport& report) {
  const Scene& scene = *report.scene;
  PageText text{
      .title = fmt::format("{}: {}, {}", kHazardReportTitle, scene.path.filename().string(),
                           report.result->year),
      .subtitle = fmt::format(
          "{} · local standard time {} · {} · sun: {} · the site and the scene in plan view, "
          "east–north metres around the site",
          siteText(scene.site), utcOffsetText(scene.site.utc_offset_h),
          report.options->models.front().name() +
              (report.options->models.size() > 1 ? " beside the usual tools' cones" : ""),
          report.options->sun.name())};
  return {
      text, [&report](Canvas& canvas, const Box& body) {
        const Box plan{body.x0, body.y0, std::min(body.x1, body.x0 + kPlanWidthPt), body.y1};
        const std::vector<Receptor> receptors = sceneReceptors(*report.scene);
        std::vector<std::size_t> worst;
        for (std::size_t o = 0; o < report.picture_stems.size(); ++o) {
          const Receptor& receptor = receptorOf(receptors, o);
          if (receptor.kind != ReceptorKind::kObserver && !report.picture_stems[o].empty())
            worst.push_back(o);
        }
        (void)drawScenePlan(canvas, plan, *report.scene, worst);
        drawFirstPageColumn(canvas, report, {plan.x1 + kColumnGapPt, body.y0, body.x1, body.y1});
      }};
}

// ---- The results ----

std::vector<std::size_t> picturedPoints(const HazardReport& report) {
  std::vector<std::size_t> points;
  for (std::size_t o = 0; o < report.picture_stems.size(); ++o)
    if (!report.picture_stems[o].empty()) points.push_back(o);
  return points;
}

TextTable resultsTable(const HazardReport& report) {
  const Scene& scene = *report.scene;
  const HazardOptions& options = *report.options;
  const HazardResult& result = *report.result;
  const std::vector<Receptor> receptors = sceneReceptors(scene);
  const std::vector<std::size_t> points = picturedPoints(report);
  // A column for the point only when a route's or an area's worst point is among them.
  const bool with_point = std::any_of(points.begin(), points.end(), [&](std::size_t o) {
    return receptorOf(receptors, o).kind != ReceptorKind::kObserver;
  });
  std::vector<std::string> heading{"receptor"};
  if (with_point) heading.push_back("point");
  for (const char* title : {"distance", "model", "min/year", "h/year", "days", "max min/day"})
    heading.push_back(title);
  std::vector<std::size_t> left{with_point ? 3u : 2u};
  if (with_point) left.push_back(1);
  for (const Criterion& criterion : options.criteria) {
    left.push_back(heading.size());
    heading.push_back(upper(criterion.id));
  }
  TextTable table{
      .rows = {heading}, .header_rows = 1, .first_column_left = true, .left_columns = left};
  for (const std::size_t o : points) {
    const Receptor& receptor = receptorOf(receptors, o);
    for (std::size_t m = 0; m < options.models.size(); ++m) {
      const ModelSummary& summary = result.observers[o].models[m];
      std::vector<std::string> row{
          m == 0 ? receptor.name + " (" + receptorKindName(receptor.kind) + ")" : ""};
      if (with_point)
        row.push_back(m == 0 && receptor.kind != ReceptorKind::kObserver
                          ? scene.observers[o].name + " (worst)"
                          : "");
      row.insert(row.end(),
                 {m == 0 ? fmt::format("{:.0f} m", distanceToNearestArrayM(scene, o)) : "",
                  options.models[m].name(), minutesPerYearText(summary.minutes_per_year),
                  hoursPerYearText(summary.hours_per_year), std::to_string(summary.days_with_glare),
                  maxMinutesText(summary.max_minutes_per_day)});
      for (const Verdict& verdict : summary.verdicts) row.push_back(verdict.text);
      table.rows.push_back(row);
    }
  }
  return table;
}

// "+12 %", "−7 %" (a true minus sign).
std::string percentChange(double value, double reference) {
  const double percent = std::round((value / reference - 1) * 100);
  if (percent == 0) return "\u00B10 %";
  return fmt::format("{}{:.0f} %", percent > 0 ? "+" : "\u2212", std::abs(percent));
}

// Per pictured point and comparison model: what it says beside the method's model.
std::string comparisonText(const HazardReport& report, std::size_t o, std::size_t m) {
  const HazardOptions& options = *report.options;
  const ModelSummary& method = report.result->observers[o].models[0];
  const ModelSummary& other = report.result->observers[o].models[m];
  const std::string method_name = options.models[0].name(), name = options.models[m].name();
  std::vector<std::string> differ;
  for (std::size_t c = 0; c < options.criteria.size(); ++c)
    if (method.verdicts[c].text != other.verdicts[c].text)
      differ.push_back(fmt::format("{} {} instead of {}", upper(options.criteria[c].id),
                                   other.verdicts[c].text, method.verdicts[c].text));
  const std::string& point = report.scene->observers[o].name;
  if (method.minutes_per_year == 0 && other.minutes_per_year == 0)
    return fmt::format("{}: neither the {} nor the {} glares there.", point, method_name, name);
  const std::string change = method.minutes_per_year > 0
                                 ? percentChange(other.minutes_per_year, method.minutes_per_year)
                                 : "where the " + method_name + " has none";
  return fmt::format(
      "{}: the {} says {} min/year ({} against the {}'s {}), {} days with glare against {}, at "
      "most {} min/day against {}; {}.",
      point, name, minutesPerYearText(other.minutes_per_year), change, method_name,
      minutesPerYearText(method.minutes_per_year), other.days_with_glare, method.days_with_glare,
      maxMinutesText(other.max_minutes_per_day), maxMinutesText(method.max_minutes_per_day),
      differ.empty() ? "the verdicts are the same"
                     : "the verdicts differ: " + joined(differ, ", "));
}

void addResultsPages(std::vector<ReportPage>& pages, Canvas& measure, const HazardReport& report) {
  const PageText text{
      .title = "Results: the measured ellipse beside the usual tools' cones",
      .subtitle = fmt::format(
          "per receptor and glare model · minutes {} · local standard time {} · hazard.json and "
          "events.csv hold every point and event",
          report.options->sun.kind == SunKind::kWeather ? "expected (weather)"
                                                        : "possible (the sun shining whenever up)",
          utcOffsetText(report.scene->site.utc_offset_h))};
  const Box body = bodyBox(measure, text);
  auto blocks = std::make_shared<std::vector<Block>>();
  addHeading(*blocks, "Minutes and verdicts per receptor and model", true);
  addTable(*blocks, resultsTable(report), body.height() - lineHeight(kSectionFont));
  const double width = std::min(body.width(), kMaxResultsTextPt);
  const TextStyle note{kTextFont, kMutedInk};
  addParagraph(*blocks, measure,
               "Receptors: each observer, and each route's and area's worst point (the most "
               "minutes per year by the first model, then the largest day); distance: to the "
               "nearest array's centre. min/year and h/year: glare counted in the receptor's "
               "hours; days: days with glare; max min/day: the day with the most. " +
                   report.options->models.front().name() +
                   " is the method's model, the measured elliptical spread; the others are what "
                   "tools with a circular cone would have said.",
               width, note);
  if (report.options->models.size() > 1) {
    addHeading(*blocks, "What a circular-cone tool would have said", false);
    for (const std::size_t o : picturedPoints(report))
      for (std::size_t m = 1; m < report.options->models.size(); ++m)
        addParagraph(*blocks, measure, comparisonText(report, o, m), width);
  }
  addFlowPages(pages, measure, text, blocks, 1);
}

// ---- The assumptions and the method ----

std::string modelWords(const GlareModel& model) {
  switch (model.kind) {
    case ModelKind::kEllipse:
      return "ellipse: the measured, α-dependent elliptical spread of the module's glare (the "
             "profile's full axes, vertical in the plane of incidence and horizontal across it): "
             "the method's model.";
    case ModelKind::kCircle:
      return "circle: a circular cone of the same solid angle as this module's measured "
             "ellipse at each α (the profile's equal-solid-angle beam): what an SGHAT-style tool "
             "would say with this module's own data. It is not SGHAT's default cone.";
    case ModelKind::kCone:
      if (model.slope_error_mrad)
        return fmt::format(
            "{}: the constant circular cone an SGHAT-style tool draws for a slope error σ = {} "
            "mrad, full angle β = 2 (4.65 mrad + σ) = {:.2f}° at every glaring α.",
            model.name(), formatPlain(*model.slope_error_mrad), model.cone_deg);
      return fmt::format(
          "{}: one constant circular cone of full angle {}° at every glaring α (blendtool.ch, "
          "SGHAT with one slope error).",
          model.name(), formatPlain(model.cone_deg));
  }
  return model.name();
}

std::string criterionWords(const Criterion& criterion) {
  return fmt::format(
      "{}: {}. \"{}\" when glare lasts more than {} minutes on any day or more than {} hours in "
      "the year; \"{}\" otherwise (both limits inclusive).",
      upper(criterion.id), criterion.title, criterion.exceeded_verdict,
      formatPlain(criterion.max_minutes_per_day), formatPlain(criterion.max_hours_per_year),
      criterion.within_verdict);
}

void addMethodPages(std::vector<ReportPage>& pages, Canvas& measure, const HazardReport& report) {
  const HazardOptions& options = *report.options;
  const Scene& scene = *report.scene;
  const PageText text{.title = "Assumptions and method",
                      .subtitle =
                          "how the minutes are counted, what each glare model is, and "
                          "the criteria they are judged by"};
  const Box body = bodyBox(measure, text);
  const double width = (body.width() - kColumnGapPt) / 2;
  auto blocks = std::make_shared<std::vector<Block>>();
  const auto paragraph = [&](const std::string& words) {
    addParagraph(*blocks, measure, words, width);
  };
  addHeading(*blocks, "The method", true);
  paragraph(fmt::format(
      "Every step of the year ({} s long, sampled at its middle) the sun's direction is computed "
      "(NREL SPA, apparent, with refraction). For each array and receptor the reflected sun is "
      "found, and the receptor sees glare when the module's glare region around the reflected ray "
      "meets the array as seen from it. The region is given in the azimuthal-equidistant plane "
      "around the reflected ray, the plane in which glarecam measures its ellipses, so that a "
      "measured axis is exactly the angle it spans there. With several arrays a step counts once.",
      report.result->step_s));
  paragraph(
      "Minutes per day are the glaring steps of a local standard day inside the receptor's "
      "hours, times the step. An obstruction takes away the part of an array the receptor does "
      "not see and the part the sun does not light. A route counts glare only within its field "
      "of view around the direction of travel, a window only within its field of view around "
      "the way it faces.");
  paragraph(
      "Glare is counted only where the angle of incidence α lies in the profile's glare ranges "
      "and α ≤ 80°: above 80° the method defines no limit, and such steps are counted apart as "
      "\"beyond the method\". Where the profile gives no spread at a glaring α, the step is "
      "counted apart as of unknown spread, never as no glare.");
  addHeading(*blocks, "Glare models", false);
  std::vector<std::string> run;
  for (const GlareModel& model : options.models) run.push_back(model.name());
  paragraph(
      fmt::format("This run compares {} (the first is the method's model):", joined(run, ", ")));
  for (const GlareModel& model : options.models) paragraph(modelWords(model));
  std::vector<std::string> others;
  if (std::none_of(options.models.begin(), options.models.end(),
                   [](const GlareModel& m) { return m.kind == ModelKind::kCircle; }))
    others.push_back(
        "circle, a circular cone of this module's own measured solid angle (what an "
        "SGHAT-style tool would say with its data; not SGHAT's default cone)");
  if (std::none_of(options.models.begin(), options.models.end(),
                   [](const GlareModel& m) { return m.kind == ModelKind::kCone; }))
    others.push_back(
        "sigma:MRAD, the constant cone SGHAT-style tools draw for a slope error σ (full angle "
        "2 (4.65 mrad + σ)), and cone:DEG, any constant full angle");
  if (!others.empty())
    paragraph("Not run here, and available with --models: " + joined(others, "; ") + ".");
  paragraph(
      "Comparing them is the point of the report: a circular cone spreads the glare evenly "
      "around the reflected ray, while the measured ellipse is narrow in one direction and wide "
      "in the other, so that the same module glares for more or fewer minutes by the cone than "
      "it does.");
  addHeading(*blocks, "The sun", false);
  paragraph(fmt::format("{}: {}. The minutes are {}.", options.sun.name(),
                        options.sun.description(), minutesMeaning(options)));
  if (options.sun.kind != SunKind::kReference)
    paragraph(
        "Under a sun of illuminance E the glare region at α is the profile's referred contour "
        "at the limit luminance times E_ref / E: a dimmer sun's region is smaller, and there is "
        "none where that level exceeds the referred peak.");
  addHeading(*blocks, "Times", false);
  paragraph(fmt::format(
      "Days and times are local standard time {} (glare reports count in standard time; a day "
      "is a standard day).{}",
      utcOffsetText(scene.site.utc_offset_h),
      report.daylight_saving == DaylightSaving::kNone
          ? " No daylight-saving rule was given: clock times are standard times all year."
          : " Clock times are also given in local civil time under " +
                civilRuleText(report.daylight_saving) +
                ", as the receptor's occupants read their clocks; counting stays in standard "
                "time."));
  addHeading(*blocks, "Criteria", false);
  for (const Criterion& criterion : options.criteria) paragraph(criterionWords(criterion));
  paragraph(
      "LAI's rule that glare seen within 10° of the sun is not counted (the sun outshines it) "
      "never applies within the method's range: the angle between the sun and the reflection "
      "seen is 180° − 2α, at least 20° for α ≤ 80°.");
  paragraph(
      "LAI notes that receptors farther than about 100 m from an installation are, as a rule, "
      "glared at only briefly. This report applies no distance cut-off: every receptor is "
      "computed, and its distance to the nearest array is given with the results, so that the "
      "rule can be applied to them.");
  addHeading(*blocks, "Ocular hazard", false);
  paragraph(
      "Each glare event is placed, at its brightest step, on the ocular hazard plot of Ho, "
      "Ghanbari and Diver (J. Sol. Energy Eng. 133, 2011, 031021): the retinal irradiance "
      "from the luminance seen against the angle the glaring spot subtends, with the eye of "
      "the inputs (SGHAT's defaults). Minutes per class count every glaring step by its class.");
  addHeading(*blocks, "Assumptions", false);
  for (const std::string& item : {
           std::string("Each array is a planar polygon covered by one module type, every part of "
                       "it behaving as the profile measured."),
           std::string("Nothing but the scene's obstructions blocks sight or sun: no terrain, no "
                       "vegetation beyond what is modelled, no frames or gaps between modules."),
           std::string("The profile's glare region is taken as measured at its reference "
                       "illuminance and scaled with the sun's (see The sun)."),
           std::string("The receptor's eye is at the point given; its field of view as stated; "
                       "it looks wherever the glare is within it."),
       })
    addParagraph(*blocks, measure, "\u2022 " + item, width);
  const std::vector<std::string> warnings = reportWarnings(report);
  if (!warnings.empty()) {
    addHeading(*blocks, "Warnings", false);
    for (const std::string& warning : warnings)
      addParagraph(*blocks, measure, "\u2022 " + warning, width, {kTextFont, kAlertInk});
  }
  addFlowPages(pages, measure, text, blocks, 2);
}

// ---- Per receptor: the chart page ----

std::string verdictSummary(const HazardReport& report, std::size_t o) {
  const ModelSummary& method = report.result->observers[o].models[0];
  std::vector<std::string> verdicts;
  for (std::size_t c = 0; c < report.options->criteria.size(); ++c)
    verdicts.push_back(upper(report.options->criteria[c].id) + " " + method.verdicts[c].text);
  return fmt::format("{} min/year ({} h), {} by the {}",
                     minutesPerYearText(method.minutes_per_year),
                     hoursPerYearText(method.hours_per_year), joined(verdicts, ", "),
                     report.options->models[0].name());
}

PageText receptorPageText(const HazardReport& report, std::size_t o, const std::string& what) {
  const Scene& scene = *report.scene;
  const std::vector<Receptor> receptors = sceneReceptors(scene);
  const Receptor& receptor = receptorOf(receptors, o);
  const Observer& observer = scene.observers[o];
  return {.title = fmt::format("{}: {}", pointTitle(scene, receptor, o), what),
          .subtitle =
              fmt::format("{} at ({}, {}, {}) m, {:.0f} m from the nearest array · {} · "
                          "{} · {}",
                          receptorKindName(receptor.kind), formatPlain(observer.position_m.x),
                          formatPlain(observer.position_m.y), formatPlain(observer.position_m.z),
                          distanceToNearestArrayM(scene, o), hoursText(observer),
                          viewText(observer, receptor.kind), verdictSummary(report, o))};
}

// ---- Per receptor: months, worst days, ocular hazard, verdicts ----

TextTable monthsTable(const HazardReport& report, std::size_t o) {
  constexpr std::array<const char*, 12> kMonths = {"January",   "February", "March",    "April",
                                                   "May",       "June",     "July",     "August",
                                                   "September", "October",  "November", "December"};
  const HazardOptions& options = *report.options;
  const HazardResult& result = *report.result;
  TextTable table{.rows = {{"month"}}, .header_rows = 1, .first_column_left = true};
  std::vector<std::array<double, 12>> months;
  for (std::size_t m = 0; m < options.models.size(); ++m) {
    table.rows[0].push_back(options.models[m].name() + " (min)");
    months.push_back(minutesPerMonth(result.observers[o].models[m], result.year, result.first_day));
  }
  for (std::size_t month = 0; month < kMonths.size(); ++month) {
    std::vector<std::string> row{kMonths[month]};
    for (const auto& model : months) row.push_back(minutesText(model[month]));
    table.rows.push_back(row);
  }
  std::vector<std::string> total{"year"};
  for (std::size_t m = 0; m < options.models.size(); ++m)
    total.push_back(minutesText(result.observers[o].models[m].minutes_per_year));
  table.rows.push_back(total);
  return table;
}

TextTable worstDaysTable(const HazardReport& report, std::size_t o) {
  const HazardOptions& options = *report.options;
  const HazardResult& result = *report.result;
  const Scene& scene = *report.scene;
  const bool with_seconds = result.step_s % 60 != 0;
  const bool civil = report.daylight_saving != DaylightSaving::kNone;
  std::vector<std::string> heading{"day"};
  for (const GlareModel& model : options.models) heading.push_back(model.name() + " (min)");
  heading.push_back("from–to (" + utcOffsetText(scene.site.utc_offset_h) + ")");
  if (civil) heading.push_back("civil time");
  TextTable table{.rows = {heading}, .header_rows = 1, .first_column_left = true};
  const ModelSummary& method = result.observers[o].models[0];
  for (const std::size_t d : worstDays(method, kWorstDayCount)) {
    const std::int64_t day_s =
        static_cast<std::int64_t>(result.first_day + static_cast<int>(d)) * 86400;
    const auto [first, last] = method.first_last_step[d].value_or(std::pair{0, 0});
    const std::int64_t from_s = day_s + static_cast<std::int64_t>(first) * result.step_s;
    const std::int64_t to_s = day_s + static_cast<std::int64_t>(last + 1) * result.step_s;
    const ClockText from = splitClock(
        localTimeText(result.year, from_s, scene.site.utc_offset_h, with_seconds), with_seconds);
    const ClockText to = splitClock(
        localTimeText(result.year, to_s, scene.site.utc_offset_h, with_seconds), with_seconds);
    std::vector<std::string> row{from.date};
    for (std::size_t m = 0; m < options.models.size(); ++m)
      row.push_back(minutesText(result.observers[o].models[m].minutes_per_day[d]));
    row.push_back(from.time + "\u2013" + to.time);
    if (civil) {
      const ClockText civil_from =
          splitClock(civilTimeText(report, from_s, with_seconds), with_seconds);
      const ClockText civil_to =
          splitClock(civilTimeText(report, to_s, with_seconds), with_seconds);
      row.push_back(civil_from.time + "\u2013" + civil_to.time + " (" + civil_from.offset + ")");
    }
    table.rows.push_back(row);
  }
  return table;
}

TextTable ocularTable(const HazardReport& report, std::size_t o) {
  TextTable table{.rows = {{"model", "green", "yellow", "red", "unclassified"}},
                  .header_rows = 1,
                  .first_column_left = true};
  for (std::size_t m = 0; m < report.options->models.size(); ++m) {
    const ModelSummary& summary = report.result->observers[o].models[m];
    table.rows.push_back({report.options->models[m].name(), minutesText(summary.ocular_minutes[0]),
                          minutesText(summary.ocular_minutes[1]),
                          minutesText(summary.ocular_minutes[2]),
                          minutesText(summary.unclassified_minutes)});
  }
  return table;
}

// "LAI: significant by the ellipse: 125 min on its worst day > 30 min/day (exceeded); 142.3 h
// in the year > 30 h/year (exceeded)."
std::vector<std::pair<std::string, Rgb>> verdictLines(const HazardReport& report, std::size_t o) {
  const HazardOptions& options = *report.options;
  std::vector<std::pair<std::string, Rgb>> lines;
  for (std::size_t c = 0; c < options.criteria.size(); ++c) {
    const Criterion& criterion = options.criteria[c];
    for (std::size_t m = 0; m < options.models.size(); ++m) {
      const ModelSummary& summary = report.result->observers[o].models[m];
      const Verdict& verdict = summary.verdicts[c];
      lines.push_back(
          {fmt::format(
               "{}: {} by the {}: {} min on the worst day {} {} min/day ({}); {} h in "
               "the year {} {} h/year ({}).",
               upper(criterion.id), verdict.text, options.models[m].name(),
               maxMinutesText(summary.max_minutes_per_day), verdict.day_exceeded ? ">" : "\u2264",
               formatPlain(criterion.max_minutes_per_day),
               verdict.day_exceeded ? "exceeded" : "within",
               hoursPerYearText(summary.hours_per_year), verdict.year_exceeded ? ">" : "\u2264",
               formatPlain(criterion.max_hours_per_year),
               verdict.year_exceeded ? "exceeded" : "within"),
           verdict.exceeded ? kAlertInk : kInk});
    }
  }
  return lines;
}

struct ReceptorContent {
  std::size_t observer = 0;
  HazardChartContent chart;
  OcularPlotContent ocular;
};

void drawDetailsPage(Canvas& canvas, const HazardReport& report, const ReceptorContent& content,
                     const Box& body) {
  const std::size_t o = content.observer;
  // Left: the ocular hazard plot and the minutes per class.
  const Box left{body.x0, body.y0, body.x0 + kOcularColumnPt, body.y1};
  const TextTable ocular = ocularTable(report, o);
  const double ocular_table_pt = tableHeightPt(ocular, kTableFont);
  double y = left.y0 + drawSection(canvas, left, "Ocular hazard of each glare event");
  const Box plot{left.x0, y, left.x1,
                 left.y1 - ocular_table_pt - 2 * lineHeight(kSectionFont) - kGapPt};
  (void)drawOcularHazardPlot(canvas, plot, content.ocular);  // checked before the file is made
  y = plot.y1 + kGapPt;
  y += drawSection(canvas, {left.x0, y, left.x1, left.y1}, "Glare minutes per ocular class");
  drawTable(canvas, ocular, {left.x0, y, left.x1, left.y1}, kTableFont);

  // Right: months, worst days, verdicts.
  const Box right{left.x1 + kColumnGapPt, body.y0, body.x1, body.y1};
  y = right.y0 + drawSection(canvas, right, "Glare minutes per month");
  y += drawTable(canvas, monthsTable(report, o), {right.x0, y, right.x1, right.y1}, kTableFont) +
       kSectionGapPt;
  y += drawSection(canvas, {right.x0, y, right.x1, right.y1},
                   fmt::format("The worst days by the {}", report.options->models[0].name()));
  const TextTable worst = worstDaysTable(report, o);
  if (worst.rows.size() > 1) {
    y += drawTable(canvas, worst, {right.x0, y, right.x1, right.y1}, kTableFont) + kSectionGapPt;
  } else {
    drawText(canvas, {right.x0, y + kTextFont.size}, "no day with glare", {kTextFont, kMutedInk});
    y += lineHeight(kTextFont) + kSectionGapPt;
  }
  y += drawSection(canvas, {right.x0, y, right.x1, right.y1}, "Verdicts, thresholds written out");
  for (const auto& [line, colour] : verdictLines(report, o))
    y += drawParagraphs(canvas, {right.x0, y + kTextFont.size}, right.width(), {line},
                        {kTextFont, colour}) +
         kParagraphGapPt / 2;
  std::vector<std::string> notes;
  for (std::size_t m = 0; m < report.options->models.size(); ++m) {
    const ModelSummary& summary = report.result->observers[o].models[m];
    if (summary.steps_beyond_method > 0 || summary.steps_unknown_spread > 0)
      notes.push_back(
          fmt::format("{}: {} steps beyond the method (α > 80°), {} of unknown spread "
                      "(not counted as glare).",
                      report.options->models[m].name(), summary.steps_beyond_method,
                      summary.steps_unknown_spread));
  }
  if (!notes.empty())
    drawParagraphs(canvas, {right.x0, y + kParagraphGapPt + kTextFont.size}, right.width(), notes,
                   {kTextFont, kMutedInk});
}

// ---- The document ----

Status validate(const HazardReport& report) {
  if (!report.scene || !report.options || !report.result)
    return badInput("hazard report: no scene, options or result given");
  const Scene& scene = *report.scene;
  if (report.profiles.size() != scene.arrays.size() ||
      std::any_of(report.profiles.begin(), report.profiles.end(),
                  [](const ProfileTable* p) { return p == nullptr; }))
    return badInput("hazard report: one profile per array needed");
  if (report.picture_stems.size() != scene.observers.size() ||
      report.result->observers.size() != scene.observers.size())
    return badInput("hazard report: the result and the pictures must cover every observer");
  if (report.options->models.empty()) return badInput("hazard report: no glare model");
  return {};
}

Status writeReport(const HazardReport& report, const fs::path& file) {
  GLARECAM_CHECK(validate(report));
  // Text is measured on a scratch canvas; each chart and plot is drawn there once first, so that
  // content it refuses fails before the file is made.
  Result<render::RgbSurface> scratch = render::RgbSurface::create(1, 1);
  if (!scratch) return std::unexpected(scratch.error());
  Result<render::Canvas> scratch_canvas = render::Canvas::onSurface(*scratch);
  if (!scratch_canvas) return std::unexpected(scratch_canvas.error());
  render::Canvas& measure = *scratch_canvas;

  std::vector<ReceptorContent> receptors;
  for (const std::size_t o : picturedPoints(report)) {
    ReceptorContent content{
        .observer = o, .chart = chartContent(report, o), .ocular = ocularContent(report, o)};
    // The pages draw their own title and mark.
    content.chart.mark.clear();
    content.ocular.mark.clear();
    const render::Box page{0, 0, kPage.width_pt, kPage.height_pt};
    GLARECAM_CHECK(drawHazardChart(measure, page, content.chart));
    GLARECAM_CHECK(drawOcularHazardPlot(measure, page, content.ocular));
    receptors.push_back(std::move(content));
  }

  std::vector<ReportPage> pages;
  pages.push_back(firstPage(report));
  addResultsPages(pages, measure, report);
  addMethodPages(pages, measure, report);
  for (const ReceptorContent& content : receptors) {
    const std::size_t o = content.observer;
    pages.push_back({receptorPageText(report, o, "glare over the year"),
                     [&content](render::Canvas& canvas, const render::Box& body) {
                       (void)drawHazardChart(canvas, body, content.chart);
                     }});
    pages.push_back({receptorPageText(report, o, "months, worst days, ocular hazard, verdicts"),
                     [&report, &content](render::Canvas& canvas, const render::Box& body) {
                       drawDetailsPage(canvas, report, content, body);
                     }});
  }

  const Shell shell{
      .footer = fmt::format("glarecam {} · {} · {} · {}", kVersion, kHazardReportTitle,
                            report.scene->path.filename().string(), report.result->year),
      .simulated = anySimulated(report)};
  std::vector<render::PageDrawing> drawings;
  for (std::size_t i = 0; i < pages.size(); ++i)
    drawings.push_back([&shell, &pages, i](render::Canvas& canvas) {
      drawReportPage(canvas, shell, pages[i], i + 1, pages.size());
    });
  const render::PdfMetadata metadata{
      .title = fmt::format("{}: {}, {}", kHazardReportTitle, report.scene->path.filename().string(),
                           report.result->year),
      .creator = fmt::format("glarecam {}", kVersion)};
  return render::writePdfPages(file, kPage, drawings, metadata);
}

}  // namespace hazard_pdf

Status writeHazardReportPdf(const HazardReport& report, const std::filesystem::path& file) {
  return hazard_pdf::writeReport(report, file);
}

}  // namespace glarecam::hazard
