// What `glarecam hazard` writes (docs/hazard.md, "Outputs"): hazard.json (glarecam.hazard/1),
// events.csv, hazard.geojson (the map, hazard_geojson.h: the screening's schema), one picture per
// observer (PNG and SVG, hazard_chart.h), and the short table printed
// on stdout; the PDF report (hazard_pdf.h) is drawn from the same HazardReport. Times are local
// standard time, "YYYY-MM-DDTHH:MM+HH:MM".
#pragma once

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "hazard/civil_time.h"
#include "hazard/hazard_calculation.h"
#include "hazard/hazard_chart.h"
#include "hazard/ocular_hazard_plot.h"
#include "hazard/profile_table.h"
#include "hazard/scene.h"

namespace glarecam::hazard {

inline constexpr const char* kHazardSchema = "glarecam.hazard/1";
inline constexpr const char* kHazardJson = "hazard.json";
inline constexpr const char* kEventsCsv = "events.csv";

struct HazardReport {
  const Scene* scene = nullptr;
  std::vector<const ProfileTable*> profiles;  // per array
  const HazardOptions* options = nullptr;
  const HazardResult* result = nullptr;
  // Per observer point: "glare-window-3" (+ .png, .svg; "ocular-" + the same for its ocular
  // hazard plot), or empty for a point drawn by no picture (a route's or an area's points other
  // than the worst).
  std::vector<std::string> picture_stems;
  // Clock times are also given in local civil time under this rule (civil_time.h).
  DaylightSaving daylight_saving = DaylightSaving::kNone;
};

// "glare-<name>" with every character outside [A-Za-z0-9._-] as '-', unique among observers.
std::vector<std::string> pictureStems(const Scene& scene);
// The stems of the points that get pictures: every observer, and each route's and area's worst
// point (worstPoint); the others empty.
std::vector<std::string> pictureStems(const Scene& scene, const HazardResult& result);

// The scene's receptors; a scene built without them (tests) has one observer receptor per point.
std::vector<Receptor> sceneReceptors(const Scene& scene);

// The point of a receptor with the most glare by the first model (minutes per year, then the
// largest day; the first such point on a tie).
std::size_t worstPoint(const Receptor& receptor, const HazardResult& result);

// Minutes per calendar month of the run's days (12 values, months the run does not cover 0).
std::array<double, 12> minutesPerMonth(const ModelSummary& summary, int year, int first_day);

OcularPlotContent ocularContent(const HazardReport& report, std::size_t observer);

// The local time at the start of a step of the year: "2027-03-21T18:02+01:00" (seconds shown
// when steps are not whole minutes).
std::string localTimeText(int year, std::int64_t seconds_of_year, double utc_offset_h,
                          bool with_seconds);
// The same instant (given in local standard seconds of the year) in local civil time under the
// report's daylight-saving rule: "2027-07-01T13:02+02:00".
std::string civilTimeText(const HazardReport& report, std::int64_t seconds_of_year,
                          bool with_seconds);

// "faces 180° (S), tilt 30.0°, 72.0 m²": which way the front looks, so that a polygon listed
// the wrong way round shows.
std::string arrayFacingText(const ArrayPolygon& array);
// "UTC+01:00", "UTC-03:30".
std::string utcOffsetText(double utc_offset_h);

// The days (indices into minutes_per_day) with the most glare, most first (the earlier day first
// on a tie), at most `count`; days without glare never.
std::vector<std::size_t> worstDays(const ModelSummary& summary, std::size_t count);

// Every warning of the run, as stderr and hazard.json's "warnings" give them: the scene's (an
// array facing downward, an observer that never sees an array's front), each SIMULATED profile
// (made from stacks of the simulated camera: not a measurement), an unlikely --year, a weather
// file whose station lies farther than 50 km from the site.
std::vector<std::string> reportWarnings(const HazardReport& report);

nlohmann::json hazardJson(const HazardReport& report);
std::string eventsCsv(const HazardReport& report);
HazardChartContent chartContent(const HazardReport& report, std::size_t observer);
// Per pictured point (every observer, each route's and area's worst point) and model:
// minutes/year, days, largest day, each criterion's verdict; before it a SIMULATED line per
// simulated profile and each array's facing, tilt and area; after it each route and area with
// its number of points and its worst.
std::string summaryText(const HazardReport& report);

// Writes every output into `directory` (created if missing), each file atomically.
Status writeHazardOutputs(const HazardReport& report, const std::filesystem::path& directory);

}  // namespace glarecam::hazard
