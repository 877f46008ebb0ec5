// glarecam hazard: glare minutes at a neighbour's window from the measured glare profile, beside
// what a circular-cone tool would say (docs/hazard.md).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/glarecam/commands.h"
#include "hazard/criteria.h"
#include "hazard/glare_model.h"
#include "hazard/hazard_run.h"

namespace glarecam::apps {
namespace {

struct HazardArgs {
  std::string scene;
  std::optional<std::string> profile;
  std::string out;
  int year = 0;
  int step_s = 60;
  std::string models = "ellipse,circle";
  std::string criteria = "lai,ch";
  std::vector<std::string> sun = {"clear-sky"};
  bool sun_given = false;
  std::string daylight_saving = "none";
  std::optional<std::string> report;
  unsigned threads = 0;
  bool json = false;
  bool no_progress = false;
};

Status runHazardCommand(const HazardArgs& args) {
  hazard::HazardRunOptions options;
  options.scene = args.scene;
  if (args.profile) options.profile = *args.profile;
  if (args.report) options.report = *args.report;
  options.out = args.out;
  options.hazard.year = args.year;
  options.hazard.step_s = args.step_s;
  options.hazard.threads = args.threads;
  options.show_progress = !args.no_progress;
  GLARECAM_ASSIGN(options.hazard.models, hazard::parseModels(args.models, "--models"));
  GLARECAM_ASSIGN(options.hazard.criteria, hazard::parseCriteria(args.criteria, "--criteria"));
  GLARECAM_ASSIGN(options.hazard.sun, hazard::parseSunBrightness(args.sun));
  options.sun_by_default = !args.sun_given;
  GLARECAM_ASSIGN(options.daylight_saving,
                  hazard::parseDaylightSaving(args.daylight_saving, "--daylight-saving"));
  hazard::HazardRunSummary summary;
  GLARECAM_ASSIGN(summary, hazard::runHazard(options));
  for (const std::string& warning : summary.warnings)
    std::fprintf(stderr, "warning: %s\n", warning.c_str());
  if (args.json) {
    printJson(summary.document);
  } else {
    std::printf("%s", summary.table.c_str());
  }
  return {};
}

}  // namespace

void addHazardCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<HazardArgs>();
  CLI::App* sub = app.add_subcommand(
      "hazard",
      "Glare minutes per day and year at observers (windows, terraces) from a module's glare "
      "profile and a scene of arrays, by the measured elliptical spread beside the circular cone "
      "(docs/hazard.md)");
  sub->add_option("SCENE", args->scene,
                  "scene file, glarecam.hazard-scene/1 or /2 (docs/hazard.md): arrays, observers, "
                  "routes, areas, obstructions; or drawn on a map: GeoJSON (.geojson, a "
                  "FeatureCollection with a \"glarecam\" member) or Google Earth KML (.kml)")
      ->required();
  sub->add_option("--profile", args->profile,
                  "glare-profile.json (glarecam datasheet) for every array without its own "
                  "\"profile\" in the scene");
  sub->add_option("--year", args->year, "the year to compute, in local standard time")->required();
  sub->add_option("--out", args->out, "output directory: hazard.json, events.csv, pictures")
      ->required();
  sub->add_option("--models", args->models,
                  "glare regions to compare, comma-separated: ellipse (the measured spread), "
                  "circle (its equal-solid-angle cone: this module's, not SGHAT's default), "
                  "cone:DEG (one constant full angle), sigma:MRAD (SGHAT's cone for a slope "
                  "error: 2 (4.65 mrad + MRAD))")
      ->capture_default_str();
  sub->add_option("--step-s", args->step_s,
                  "time step in seconds (divides a day; sampled at its middle)")
      ->capture_default_str();
  sub->add_option("--criteria", args->criteria,
                  "assessment criteria, comma-separated: lai (Germany, 30 min/day, 30 h/year), ch "
                  "(Switzerland, 30 min/day, 50 h/year)")
      ->capture_default_str();
  sub->add_option(
         "--sun", args->sun,
         "the sun's brightness at each step: clear-sky (a clear sky's direct normal "
         "illuminance: the possible glare), reference (every step as bright as the "
         "profile's reference illuminance), weather FILE.epw (an EnergyPlus weather file: the "
         "expected glare). Not given: clear-sky, or reference (warned) for a profile "
         "without a contour ladder")
      ->expected(1, 2)
      ->capture_default_str();
  sub->add_option("--daylight-saving", args->daylight_saving,
                  "also give clock times in local civil time: none, eu (last Sunday of March to "
                  "last Sunday of October), us (second Sunday of March to first Sunday of "
                  "November); counting stays in standard time")
      ->capture_default_str();
  sub->add_option("--report", args->report,
                  "also write the report as one PDF (A4): the scene in plan view, the inputs and "
                  "profiles, the results beside what a circular-cone tool would say, the method, "
                  "and per receptor its chart, months, worst days, ocular hazard and verdicts "
                  "(docs/hazard-report.md)")
      ->type_name("FILE.pdf");
  sub->add_option("--threads", args->threads, "worker threads (default: one per core)");
  sub->add_flag("--json", args->json, "print hazard.json on stdout instead of the table");
  sub->add_flag("--no-progress", args->no_progress, "no progress on stderr");
  sub->callback([args, sub, &action] {
    args->sun_given = sub->count("--sun") > 0;
    action = [args] { return runHazardCommand(*args); };
  });
}

}  // namespace glarecam::apps
