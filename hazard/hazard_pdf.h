// The glare-hazard report as one PDF (`glarecam hazard --report FILE.pdf`; docs/hazard-report.md
// describes it page by page), A4 landscape throughout, drawn with render/:
//   - the site and scene in plan view (east–north metres: the arrays, the obstructions'
//     footprints, the observers with the way they face, the routes and areas with each one's
//     worst point, a north arrow and a scale bar) beside the inputs (site, year, step, models,
//     criteria, the sun used and whether the minutes are possible or expected) and each module
//     profile (its identity, whether it was simulated, its reference illuminance; its route,
//     camera or BRDF, is not recorded in a profile and is said so);
//   - the results: per pictured receptor and model, minutes and hours per year, days, the largest
//     day and each criterion's verdict, the method's ellipse beside the other models ("what a
//     circular-cone tool would have said"), flowing onto further pages when long;
//   - the assumptions and the method in words, the criteria with their thresholds and sources,
//     and the run's warnings;
//   - per pictured receptor (HazardReport::picture_stems: every observer and each route's and
//     area's worst point) two pages: the day × time chart (hazard_chart.h: the very drawing of
//     its PNG) with the year's hours against the yearly limits; then the minutes per month, the
//     worst days with their first and last glare (local standard time, and civil time when the
//     report has a daylight-saving rule), the ocular hazard plot (ocular_hazard_plot.h) with the
//     minutes per ocular class, and the verdicts with their thresholds written out.
// Every page has a footer (the glarecam version, the scene, "page i of n"), and the SIMULATED
// mark across it when a profile was made from the simulated camera's stacks.
//
// Errors: kBadInput, with nothing written, for a report without its scene, options or result, or
// content its pictures refuse (a chart needs the whole year); kIo naming the file when it cannot
// be written. The file is written atomically (render/page_output.h): a failure leaves what was
// there.
#pragma once

#include <filesystem>

#include "core/error.h"
#include "hazard/hazard_report.h"

namespace glarecam::hazard {

inline constexpr const char* kHazardReportTitle = "Glare hazard report";

Status writeHazardReportPdf(const HazardReport& report, const std::filesystem::path& file);

}  // namespace glarecam::hazard
