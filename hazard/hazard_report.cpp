#include "hazard/hazard_report.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <tuple>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/json.h"
#include "core/version.h"
#include "hazard/hazard_geojson.h"
#include "hazard/obstruction.h"
#include "pipeline/sweep_table.h"

namespace glarecam::hazard {
namespace {

using nlohmann::json;

std::string offsetText(double utc_offset_h) {
  const long minutes = std::lround(std::abs(utc_offset_h) * 60);
  char text[48];
  std::snprintf(text, sizeof text, "%c%02ld:%02ld", utc_offset_h < 0 ? '-' : '+', minutes / 60,
                minutes % 60);
  return text;
}

std::string timeOfDayText(int seconds_of_day, bool with_seconds) {
  char text[16];
  if (with_seconds) {
    std::snprintf(text, sizeof text, "%02d:%02d:%02d", seconds_of_day / 3600,
                  seconds_of_day / 60 % 60, seconds_of_day % 60);
  } else {
    std::snprintf(text, sizeof text, "%02d:%02d", seconds_of_day / 3600, seconds_of_day / 60 % 60);
  }
  return text;
}

// Code points, for aligning columns of UTF-8 text.
std::size_t displayWidth(const std::string& text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  }));
}

std::string formatNumber(const char* format, double value) {
  char text[48];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

// The profiles made from stacks of the simulated camera, each once: "module "M" (PATH), for
// array "roof-north"".
std::vector<std::string> simulatedProfiles(const HazardReport& report) {
  std::vector<std::string> profiles;
  for (std::size_t a = 0; a < report.profiles.size(); ++a) {
    const ProfileTable& profile = *report.profiles[a];
    if (!profile.simulated()) continue;
    bool first_use = true;
    for (std::size_t earlier = 0; earlier < a; ++earlier)
      first_use = first_use && report.profiles[earlier] != &profile;
    if (!first_use) continue;
    std::string arrays;
    for (std::size_t user = a; user < report.profiles.size(); ++user) {
      if (report.profiles[user] != &profile) continue;
      arrays += (arrays.empty() ? "\"" : ", \"") + report.scene->arrays[user].name + "\"";
    }
    profiles.push_back("module \"" + profile.module() + "\" (" + profile.path().string() +
                       "), for array" + (arrays.find(',') == std::string::npos ? " " : "s ") +
                       arrays);
  }
  return profiles;
}

bool anySimulated(const HazardReport& report) {
  return std::any_of(report.profiles.begin(), report.profiles.end(),
                     [](const ProfileTable* profile) { return profile->simulated(); });
}

}  // namespace

std::string arrayFacingText(const ArrayPolygon& array) {
  constexpr std::array<const char*, 8> kCompass = {"N", "NE", "E", "SE", "S", "SW", "W", "NW"};
  const std::optional<double> azimuth_deg = facingAzimuthDeg(array);
  const double tilt_deg = tiltDeg(array);
  std::string faces;
  if (azimuth_deg) {
    const auto point = static_cast<std::size_t>(std::lround(*azimuth_deg / 45)) % kCompass.size();
    faces = formatNumber("%.0f°", *azimuth_deg) + " (" + kCompass[point] + ")";
  } else {
    faces = tilt_deg < 90 ? "up (level)" : "down (level)";
  }
  return "faces " + faces + ", tilt " + formatNumber("%.1f°", tilt_deg) + ", " +
         formatNumber("%.1f m²", array.area_m2);
}

std::string utcOffsetText(double utc_offset_h) { return "UTC" + offsetText(utc_offset_h); }

std::vector<std::size_t> worstDays(const ModelSummary& summary, std::size_t count) {
  std::vector<std::size_t> days;
  for (std::size_t d = 0; d < summary.minutes_per_day.size(); ++d)
    if (summary.minutes_per_day[d] > 0) days.push_back(d);
  std::stable_sort(days.begin(), days.end(), [&summary](std::size_t a, std::size_t b) {
    return summary.minutes_per_day[a] > summary.minutes_per_day[b];
  });
  if (days.size() > count) days.resize(count);
  return days;
}

std::vector<std::string> reportWarnings(const HazardReport& report) {
  std::vector<std::string> warnings = report.scene->warnings;
  for (const std::string& profile : simulatedProfiles(report))
    warnings.push_back("SIMULATED profile of " + profile + ": " + pipeline::kSimulatedNote);
  if (auto year = report.options->yearWarning()) warnings.push_back(std::move(*year));
  if (report.options->sun.weather) {
    if (auto far =
            sun::weatherSiteWarning(*report.options->sun.weather, report.scene->site.location))
      warnings.push_back(std::move(*far));
  }
  return warnings;
}

std::vector<Receptor> sceneReceptors(const Scene& scene) {
  if (!scene.receptors.empty()) return scene.receptors;
  std::vector<Receptor> receptors;
  for (std::size_t o = 0; o < scene.observers.size(); ++o)
    receptors.push_back(
        {.kind = ReceptorKind::kObserver, .name = scene.observers[o].name, .first = o, .count = 1});
  return receptors;
}

std::size_t worstPoint(const Receptor& receptor, const HazardResult& result) {
  std::size_t worst = receptor.first;
  for (std::size_t o = receptor.first; o < receptor.first + receptor.count; ++o) {
    const ModelSummary& a = result.observers[o].models.front();
    const ModelSummary& b = result.observers[worst].models.front();
    if (std::tie(a.minutes_per_year, a.max_minutes_per_day) >
        std::tie(b.minutes_per_year, b.max_minutes_per_day))
      worst = o;
  }
  return worst;
}

std::vector<std::string> pictureStems(const Scene& scene, const HazardResult& result) {
  std::vector<std::string> stems = pictureStems(scene);
  std::vector<bool> pictured(scene.observers.size(), scene.receptors.empty());
  for (const Receptor& receptor : scene.receptors) {
    if (receptor.kind == ReceptorKind::kObserver) {
      for (std::size_t o = receptor.first; o < receptor.first + receptor.count; ++o)
        pictured[o] = true;
    } else if (receptor.count > 0) {
      pictured[worstPoint(receptor, result)] = true;
    }
  }
  for (std::size_t o = 0; o < stems.size(); ++o)
    if (!pictured[o]) stems[o].clear();
  return stems;
}

std::array<double, 12> minutesPerMonth(const ModelSummary& summary, int year, int first_day) {
  std::array<double, 12> months{};
  const std::chrono::sys_days january_1{std::chrono::year{year} / 1 / 1};
  for (std::size_t d = 0; d < summary.minutes_per_day.size(); ++d) {
    const std::chrono::year_month_day date{january_1 +
                                           std::chrono::days(first_day + static_cast<int>(d))};
    months[static_cast<unsigned>(date.month()) - 1] += summary.minutes_per_day[d];
  }
  return months;
}

std::vector<std::string> pictureStems(const Scene& scene) {
  std::vector<std::string> stems;
  std::set<std::string> used;
  for (std::size_t o = 0; o < scene.observers.size(); ++o) {
    std::string slug;
    for (const char c : scene.observers[o].name) {
      const bool plain = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') ||
                         (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-';
      slug += plain ? c : '-';
    }
    std::string stem = "glare-" + slug;
    for (int n = 2; used.count(stem) != 0; ++n) stem = "glare-" + slug + "-" + std::to_string(n);
    used.insert(stem);
    stems.push_back(stem);
  }
  return stems;
}

std::string localTimeText(int year, std::int64_t seconds_of_year, double utc_offset_h,
                          bool with_seconds) {
  const std::chrono::sys_days day = std::chrono::sys_days{std::chrono::year{year} / 1 / 1} +
                                    std::chrono::days(seconds_of_year / 86400);
  const std::chrono::year_month_day date{day};
  char text[24];
  std::snprintf(text, sizeof text, "%04d-%02u-%02uT", static_cast<int>(date.year()),
                static_cast<unsigned>(date.month()), static_cast<unsigned>(date.day()));
  return text + timeOfDayText(static_cast<int>(seconds_of_year % 86400), with_seconds) +
         offsetText(utc_offset_h);
}

std::string civilTimeText(const HazardReport& report, std::int64_t seconds_of_year,
                          bool with_seconds) {
  const int year = report.result->year;
  const double standard_h = report.scene->site.utc_offset_h;
  const UtcTime utc = std::chrono::time_point_cast<std::chrono::microseconds>(
                          std::chrono::sys_days{std::chrono::year{year} / 1 / 1}) +
                      std::chrono::seconds(seconds_of_year) -
                      std::chrono::microseconds(std::llround(standard_h * 3600e6));
  const double civil_h = civilOffsetH(report.daylight_saving, utc, standard_h);
  const auto shift_s = static_cast<std::int64_t>(std::llround((civil_h - standard_h) * 3600));
  return localTimeText(year, seconds_of_year + shift_s, civil_h, with_seconds);
}

json hazardJson(const HazardReport& report) {
  const Scene& scene = *report.scene;
  const HazardOptions& options = *report.options;
  const HazardResult& result = *report.result;
  const bool with_seconds = result.step_s % 60 != 0;

  json profiles = json::array();
  for (std::size_t a = 0; a < scene.arrays.size(); ++a) {
    json entry = report.profiles[a]->identity();
    entry["array"] = scene.arrays[a].name;
    entry["path"] = report.profiles[a]->path().string();
    profiles.push_back(entry);
  }
  json models = json::array();
  for (const GlareModel& model : options.models) models.push_back(model.name());
  json criteria = json::object();
  for (const Criterion& criterion : options.criteria)
    criteria[criterion.id] = criterionJson(criterion);
  const sun::SiteLocation& location = scene.site.location;
  json arrays = json::array();
  for (const ArrayPolygon& array : scene.arrays) {
    arrays.push_back({{"name", array.name},
                      {"area_m2", array.area_m2},
                      {"normal", {array.normal.x, array.normal.y, array.normal.z}},
                      {"facing_azimuth_deg", jsonOrNull(facingAzimuthDeg(array))},
                      {"tilt_deg", tiltDeg(array)}});
  }

  json observers = json::array();
  for (std::size_t o = 0; o < scene.observers.size(); ++o) {
    const Observer& observer = scene.observers[o];
    json by_model = json::object();
    for (std::size_t m = 0; m < options.models.size(); ++m) {
      const ModelSummary& summary = result.observers[o].models[m];
      json first_last = json::array();
      for (const auto& steps : summary.first_last_step) {
        if (!steps) {
          first_last.push_back(nullptr);
          continue;
        }
        first_last.push_back({timeOfDayText(steps->first * result.step_s, with_seconds),
                              timeOfDayText((steps->second + 1) * result.step_s, with_seconds)});
      }
      json verdicts = json::object();
      for (std::size_t c = 0; c < options.criteria.size(); ++c) {
        const Verdict& verdict = summary.verdicts[c];
        verdicts[options.criteria[c].id] = {{"verdict", verdict.text},
                                            {"exceeded", verdict.exceeded},
                                            {"day_limit_exceeded", verdict.day_exceeded},
                                            {"year_limit_exceeded", verdict.year_exceeded}};
      }
      by_model[options.models[m].name()] = {
          {"minutes_per_day", summary.minutes_per_day},
          {"minutes_per_year", summary.minutes_per_year},
          {"hours_per_year", summary.hours_per_year},
          {"days_with_glare", summary.days_with_glare},
          {"max_minutes_per_day", summary.max_minutes_per_day},
          {"first_last_per_day", first_last},
          {"steps_beyond_method", summary.steps_beyond_method},
          {"steps_unknown_spread", summary.steps_unknown_spread},
          {"verdicts", verdicts},
          {"minutes_per_month", minutesPerMonth(summary, result.year, result.first_day)},
          {"ocular_minutes",
           {{"green", summary.ocular_minutes[0]},
            {"yellow", summary.ocular_minutes[1]},
            {"red", summary.ocular_minutes[2]},
            {"unclassified", summary.unclassified_minutes}}}};
    }
    const std::string& stem = report.picture_stems[o];
    json entry = {
        {"name", observer.name},
        {"position_m", {observer.position_m.x, observer.position_m.y, observer.position_m.z}},
        {"hours", {observer.from_h, observer.to_h}},
        {"models", by_model},
        {"picture", stem.empty() ? json(nullptr)
                                 : json{{"png", stem + ".png"},
                                        {"svg", stem + ".svg"},
                                        {"ocular_png", "ocular-" + stem + ".png"},
                                        {"ocular_svg", "ocular-" + stem + ".svg"}}}};
    if (!scene.receptors.empty()) {
      const Receptor& receptor = scene.receptors[observer.receptor];
      entry["receptor"] = receptor.name;
      entry["kind"] = receptorKindName(receptor.kind);
    }
    if (!observer.view_azimuths_deg.empty()) {
      entry["view_azimuths_deg"] = observer.view_azimuths_deg;
      entry["field_of_view_deg"] = observer.field_of_view_deg;
    }
    observers.push_back(entry);
  }
  json receptors = json::array();
  for (const Receptor& receptor : scene.receptors) {
    const std::size_t worst = worstPoint(receptor, result);
    json worst_models = json::object();
    for (std::size_t m = 0; m < options.models.size(); ++m) {
      const ModelSummary& summary = result.observers[worst].models[m];
      json verdicts = json::object();
      for (std::size_t c = 0; c < options.criteria.size(); ++c)
        verdicts[options.criteria[c].id] = summary.verdicts[c].text;
      worst_models[options.models[m].name()] = {
          {"minutes_per_year", summary.minutes_per_year},
          {"max_minutes_per_day", summary.max_minutes_per_day},
          {"days_with_glare", summary.days_with_glare},
          {"verdicts", verdicts}};
    }
    receptors.push_back({{"name", receptor.name},
                         {"kind", receptorKindName(receptor.kind)},
                         {"points", receptor.count},
                         {"worst_point", scene.observers[worst].name},
                         {"worst", worst_models}});
  }
  json obstructions = json::array();
  for (const Obstruction& obstruction : scene.obstructions)
    obstructions.push_back({{"name", obstruction.name}, {"faces", obstruction.faces.size()}});
  json sun = {{"kind", options.sun.name()}, {"description", options.sun.description()}};
  sun["minutes"] = options.sun.kind == SunKind::kWeather
                       ? "expected: with the weather file's direct sun, not the clear sky"
                       : "possible: the sun is taken to shine at every step it is up";
  if (options.sun.weather) {
    const sun::EpwLocation& station = options.sun.weather->location;
    sun["weather_file"] = {{"path", options.sun.weather->path.string()},
                           {"station", station.city},
                           {"latitude_deg", station.latitude_deg},
                           {"longitude_deg", station.longitude_deg},
                           {"distance_km", sun::distanceKm(station, scene.site.location)}};
  }
  const EyeParameters& eye = options.eye;

  return {{"schema", kHazardSchema},
          {"generator", {{"name", "glarecam"}, {"version", kVersion}}},
          {"inputs",
           {{"scene", scene.path.string()},
            {"site",
             {{"latitude_deg", location.latitude_deg},
              {"longitude_deg", location.longitude_deg},
              {"elevation_m", location.altitude_m},
              {"pressure_hpa", location.pressure_hpa},
              {"temperature_c", location.temperature_c},
              {"utc_offset_h", scene.site.utc_offset_h}}},
            {"frame", sceneFrameJson(scene)},
            {"local_time",
             "UTC" + offsetText(scene.site.utc_offset_h) + " (standard time, no daylight saving)"},
            {"daylight_saving", daylightSavingName(report.daylight_saving)},
            {"arrays", arrays},
            {"profiles", profiles},
            {"year", result.year},
            {"days", result.days},
            {"step_s", result.step_s},
            {"max_distance_m", maxDistanceJson(options)},
            {"models", models},
            {"criteria", criteria},
            {"scene_schema", scene.version},
            {"obstructions", obstructions},
            {"sun", sun},
            {"eye",
             {{"pupil_diameter_m", eye.pupil_diameter_m},
              {"focal_length_m", eye.focal_length_m},
              {"ocular_transmission", eye.ocular_transmission},
              {"luminous_efficacy_lm_w", eye.luminous_efficacy_lm_w}}}}},
          {"warnings", reportWarnings(report)},
          {"receptors", receptors},
          {"observers", observers},
          {"events", {{"count", result.events.size()}, {"csv", kEventsCsv}}}};
}

std::string eventsCsv(const HazardReport& report) {
  const Scene& scene = *report.scene;
  const HazardResult& result = *report.result;
  const bool with_seconds = result.step_s % 60 != 0;
  std::string csv =
      "observer,array,model,start_local,end_local,duration_min,alpha_min_deg,alpha_max_deg,"
      "peak_luminance_cd_m2,simulated,peak_local,glare_azimuth_deg,glare_elevation_deg,"
      "distance_m,sun_azimuth_deg,sun_elevation_deg,source_illuminance_lx,ocular_class,"
      "retinal_irradiance_w_cm2,subtended_angle_mrad,start_civil,end_civil\n";
  for (const GlareEvent& event : result.events) {
    const std::int64_t start_s = event.first_step * result.step_s;
    const std::int64_t end_s = event.end_step * result.step_s;
    csv += quoteCsvField(scene.observers[event.observer].name) + "," +
           quoteCsvField(scene.arrays[event.array].name) + "," +
           quoteCsvField(report.options->models[event.model].name()) + "," +
           localTimeText(result.year, start_s, scene.site.utc_offset_h, with_seconds) + "," +
           localTimeText(result.year, end_s, scene.site.utc_offset_h, with_seconds) + "," +
           formatNumber("%g", static_cast<double>(end_s - start_s) / 60.0) + "," +
           formatNumber("%.2f", event.alpha_min_deg) + "," +
           formatNumber("%.2f", event.alpha_max_deg) + "," +
           (event.peak_luminance_cd_m2 ? formatNumber("%.4g", *event.peak_luminance_cd_m2) : "") +
           (report.profiles[event.array]->simulated() ? ",true," : ",false,");
    const GlareSighting& peak = event.peak;
    csv += localTimeText(result.year, peak.step * result.step_s, scene.site.utc_offset_h,
                         with_seconds) +
           "," + formatNumber("%.2f", peak.glare_azimuth_deg) + "," +
           formatNumber("%.2f", peak.glare_elevation_deg) + "," +
           formatNumber("%.1f", peak.distance_m) + "," +
           formatNumber("%.2f", peak.sun_azimuth_deg) + "," +
           formatNumber("%.2f", peak.sun_elevation_deg) + "," +
           (peak.source_illuminance_lx ? formatNumber("%.0f", *peak.source_illuminance_lx) : "") +
           "," + (event.worst_class ? std::string(ocularClassName(*event.worst_class)) : "") + "," +
           (peak.ocular ? formatNumber("%.4g", peak.ocular->retinal_irradiance_w_cm2) : "") + "," +
           (peak.ocular ? formatNumber("%.4g", peak.ocular->subtended_angle_mrad) : "") + "," +
           civilTimeText(report, start_s, with_seconds) + "," +
           civilTimeText(report, end_s, with_seconds) + "\n";
  }
  return csv;
}

HazardChartContent chartContent(const HazardReport& report, std::size_t o) {
  const Scene& scene = *report.scene;
  const HazardResult& result = *report.result;
  const HazardOptions& options = *report.options;
  HazardChartContent content;
  const Observer& observer = scene.observers[o];
  content.title = "Glare at " + observer.name + ", " + std::to_string(result.year);
  std::string profiles;
  std::set<std::string> modules;
  for (const ProfileTable* profile : report.profiles)
    modules.insert(profile->module() + (profile->simulated() ? " (SIMULATED)" : ""));
  for (const std::string& module : modules) profiles += (profiles.empty() ? "" : ", ") + module;
  char site[160];
  std::snprintf(site, sizeof site, "%.4f°, %.4f°", scene.site.location.latitude_deg,
                scene.site.location.longitude_deg);
  if (anySimulated(report)) {
    content.mark = "SIMULATED";
    content.mark_note = pipeline::kSimulatedNote;
  }
  const std::string simulated =
      anySimulated(report) ? std::string("SIMULATED: ") + pipeline::kSimulatedNote + " · " : "";
  content.subtitle =
      simulated + scene.path.filename().string() + " · " + profiles + " · " + site +
      " · local standard time UTC" + offsetText(scene.site.utc_offset_h) + " · " +
      std::to_string(result.step_s) + "-s steps · sun: " + options.sun.name() +
      (options.sun.kind == SunKind::kWeather ? " (expected minutes)" : " (possible minutes)");
  content.year = result.year;
  content.days = result.days;
  content.steps_per_day = result.steps_per_day;
  const std::size_t shown = std::min<std::size_t>(options.models.size(), 2);
  for (std::size_t m = 0; m < shown; ++m) {
    content.models.push_back(
        {options.models[m].name(), result.observers[o].models[m].minutes_per_day});
  }
  double day_limit = 0;
  for (const Criterion& criterion : options.criteria)
    day_limit = day_limit == 0 ? criterion.max_minutes_per_day
                               : std::min(day_limit, criterion.max_minutes_per_day);
  content.threshold_minutes_per_day = day_limit > 0 ? day_limit : 30;
  for (const Criterion& criterion : options.criteria) {
    std::string label = criterion.id;
    std::transform(label.begin(), label.end(), label.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    if (criterion.max_hours_per_year > 0)
      content.yearly_limits.push_back({label, criterion.max_hours_per_year});
  }
  const std::vector<std::uint8_t>& steps = result.observers[o].steps;
  content.cells.resize(steps.size());
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const std::uint8_t mask = steps[i];
    HazardCell cell = HazardCell::kNone;
    if (mask & kSunDownBit) {
      cell = HazardCell::kSunDown;
    } else if (mask & kOutsideHoursBit) {
      cell = HazardCell::kOutsideHours;
    } else {
      const bool first = (mask & 1u) != 0, second = shown > 1 && (mask & 2u) != 0;
      cell = first && second ? HazardCell::kBoth
             : first         ? HazardCell::kFirstOnly
             : second        ? HazardCell::kSecondOnly
                             : HazardCell::kNone;
    }
    content.cells[i] = cell;
  }
  return content;
}

OcularPlotContent ocularContent(const HazardReport& report, std::size_t o) {
  const Scene& scene = *report.scene;
  const HazardResult& result = *report.result;
  const HazardOptions& options = *report.options;
  OcularPlotContent content;
  content.title =
      "Ocular hazard at " + scene.observers[o].name + ", " + std::to_string(result.year);
  const EyeParameters& eye = options.eye;
  char subtitle[256];
  std::snprintf(subtitle, sizeof subtitle,
                "each glare event at its brightest step · sun: %s · pupil %.1f mm, focal length "
                "%.0f mm, transmission %.2f, %.0f lm/W (SGHAT's defaults)",
                options.sun.name().c_str(), eye.pupil_diameter_m * 1e3, eye.focal_length_m * 1e3,
                eye.ocular_transmission, eye.luminous_efficacy_lm_w);
  content.subtitle = subtitle;
  if (anySimulated(report)) {
    content.mark = "SIMULATED";
    content.mark_note = pipeline::kSimulatedNote;
  }
  const std::size_t shown = std::min<std::size_t>(options.models.size(), kOcularPlotMaxSeries);
  for (std::size_t m = 0; m < shown; ++m) {
    OcularPlotSeries series{.label = options.models[m].name(), .points = {}};
    for (const GlareEvent& event : result.events) {
      if (event.observer != o || event.model != m || !event.peak.ocular) continue;
      series.points.push_back(
          {event.peak.ocular->subtended_angle_mrad, event.peak.ocular->retinal_irradiance_w_cm2});
    }
    content.series.push_back(std::move(series));
  }
  return content;
}

std::string summaryText(const HazardReport& report) {
  const Scene& scene = *report.scene;
  const HazardOptions& options = *report.options;
  const HazardResult& result = *report.result;
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> heading{"observer", "model", "min/year",
                                   "h/year",   "days",  "max min/day"};
  for (const Criterion& criterion : options.criteria) heading.push_back(criterion.id);
  rows.push_back(heading);
  // The pictured points only: every observer, each route's and area's worst point (the others
  // are in hazard.json).
  const auto pictured = [&](std::size_t o) {
    return report.picture_stems.size() != scene.observers.size() ||
           !report.picture_stems[o].empty();
  };
  for (std::size_t o = 0; o < scene.observers.size(); ++o) {
    if (!pictured(o)) continue;
    for (std::size_t m = 0; m < options.models.size(); ++m) {
      const ModelSummary& summary = result.observers[o].models[m];
      std::vector<std::string> row{scene.observers[o].name,
                                   options.models[m].name(),
                                   formatNumber("%.0f", summary.minutes_per_year),
                                   formatNumber("%.1f", summary.hours_per_year),
                                   std::to_string(summary.days_with_glare),
                                   formatNumber("%g", summary.max_minutes_per_day)};
      for (const Verdict& verdict : summary.verdicts) row.push_back(verdict.text);
      rows.push_back(row);
    }
  }
  std::vector<std::size_t> widths(heading.size(), 0);
  for (const auto& row : rows)
    for (std::size_t c = 0; c < row.size(); ++c)
      widths[c] = std::max(widths[c], displayWidth(row[c]));
  // A simulated profile's mark first, then the arrays: which way each faces, so that a reversed
  // polygon is obvious.
  std::string text;
  for (const std::string& profile : simulatedProfiles(report))
    text += "SIMULATED profile of " + profile + ": " + pipeline::kSimulatedNote + "\n";
  for (const ArrayPolygon& array : scene.arrays)
    text += "array " + array.name + ": " + arrayFacingText(array) + "\n";
  if (!scene.arrays.empty()) text += "\n";
  for (const auto& row : rows) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c) {
      const std::string pad(widths[c] - displayWidth(row[c]), ' ');
      // Names and verdicts left-aligned, numbers right-aligned.
      const bool left = c < 2 || c >= 6;
      line += (c ? "  " : "") + (left ? row[c] + pad : pad + row[c]);
    }
    line.erase(line.find_last_not_of(' ') + 1);
    text += line + "\n";
  }
  for (const Receptor& receptor : scene.receptors) {
    if (receptor.kind == ReceptorKind::kObserver) continue;
    text += std::string(receptorKindName(receptor.kind)) + " " + receptor.name + ": " +
            std::to_string(receptor.count) + " points, the worst " +
            scene.observers[worstPoint(receptor, result)].name + " (every point in " + kHazardJson +
            ")\n";
  }
  for (std::size_t o = 0; o < scene.observers.size(); ++o) {
    if (!pictured(o)) continue;
    for (std::size_t m = 0; m < options.models.size(); ++m) {
      const ModelSummary& summary = result.observers[o].models[m];
      if (summary.steps_unknown_spread > 0 || summary.steps_beyond_method > 0) {
        text += scene.observers[o].name + ", " + options.models[m].name() + ": " +
                std::to_string(summary.steps_beyond_method) +
                " steps beyond the method (α > 80°), " +
                std::to_string(summary.steps_unknown_spread) + " with an unknown spread\n";
      }
    }
  }
  return text;
}

Status writeHazardOutputs(const HazardReport& report, const std::filesystem::path& directory) {
  GLARECAM_CHECK(ensureDirectory(directory));
  for (std::size_t o = 0; o < report.scene->observers.size(); ++o) {
    const std::string& stem = report.picture_stems[o];
    if (stem.empty()) continue;
    GLARECAM_CHECK(writeHazardChart(chartContent(report, o), directory / (stem + ".png"),
                                    directory / (stem + ".svg")));
    GLARECAM_CHECK(writeOcularHazardPlot(ocularContent(report, o),
                                         directory / ("ocular-" + stem + ".png"),
                                         directory / ("ocular-" + stem + ".svg")));
  }
  GLARECAM_CHECK(writeFileAtomic(directory / kEventsCsv, eventsCsv(report)));
  const std::vector<ScreenedPoint> points = screenedPoints(*report.result);
  json geojson;
  GLARECAM_ASSIGN(geojson, hazardGeoJson({.scene = report.scene,
                                          .options = report.options,
                                          .points = &points,
                                          .to_lon_lat = sceneToLonLat(*report.scene),
                                          .results = kHazardJson}));
  GLARECAM_CHECK(writeFileAtomic(directory / kHazardGeoJson, geojson.dump() + "\n"));
  GLARECAM_CHECK(writeFileAtomic(directory / kHazardJson, jsonText(hazardJson(report))));
  return {};
}

}  // namespace glarecam::hazard
