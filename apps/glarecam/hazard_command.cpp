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
  double max_distance_m = hazard::kDefaultMaxDistanceM;
  bool screen = false;
  std::optional<std::string> shard;
};

struct HazardMergeArgs {
  std::vector<std::string> shards;
  std::string out;
  std::optional<std::string> scene;
  bool json = false;
};

void printHazardSummary(const hazard::HazardRunSummary& summary, bool json) {
  for (const std::string& warning : summary.warnings)
    std::fprintf(stderr, "warning: %s\n", warning.c_str());
  if (json) {
    printJson(summary.document);
  } else {
    std::printf("%s", summary.table.c_str());
  }
}

Status runMergeCommand(const HazardMergeArgs& args) {
  hazard::HazardMergeOptions options;
  for (const std::string& shard : args.shards) options.shards.emplace_back(shard);
  options.out = args.out;
  if (args.scene) options.scene = *args.scene;
  hazard::HazardRunSummary summary;
  GLARECAM_ASSIGN(summary, hazard::runHazardMerge(options));
  printHazardSummary(summary, args.json);
  return {};
}

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
  options.hazard.max_distance_m = args.max_distance_m;
  options.screen = args.screen;
  if (args.shard) GLARECAM_ASSIGN(options.shard, hazard::parseShard(*args.shard, "--shard"));
  GLARECAM_ASSIGN(options.hazard.models, hazard::parseModels(args.models, "--models"));
  GLARECAM_ASSIGN(options.hazard.criteria, hazard::parseCriteria(args.criteria, "--criteria"));
  GLARECAM_ASSIGN(options.hazard.sun, hazard::parseSunBrightness(args.sun));
  options.sun_by_default = !args.sun_given;
  GLARECAM_ASSIGN(options.daylight_saving,
                  hazard::parseDaylightSaving(args.daylight_saving, "--daylight-saving"));
  hazard::HazardRunSummary summary;
  GLARECAM_ASSIGN(summary, hazard::runHazard(options));
  printHazardSummary(summary, args.json);
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
                  "FeatureCollection with a \"glarecam\" member) or Google Earth KML (.kml)");
  sub->add_option("--profile", args->profile,
                  "glare-profile.json (glarecam datasheet) for every array without its own "
                  "\"profile\" in the scene");
  sub->add_option("--year", args->year, "the year to compute, in local standard time (required)");
  sub->add_option("--out", args->out,
                  "output directory (required): hazard.json, events.csv, pictures, "
                  "hazard.geojson; with --screen screen.json, receptors.csv, hazard.geojson; "
                  "with --shard shard.json");
  sub->add_option("--max-distance", args->max_distance_m,
                  "metres: receptor points farther than this from an array's polygon are not "
                  "computed against it (Germany's LAI guidance looks within 100 m; the outputs "
                  "state it); inf: every pair (not with --screen)")
      ->capture_default_str();
  sub->add_flag("--screen", args->screen,
                "screen a district: a row per receptor point (receptors.csv, hazard.geojson, "
                "screen.json) instead of charts and events, memory bounded however many "
                "receptors (docs/hazard.md, \"Screening a district\")");
  sub->add_option("--shard", args->shard,
                  "with --screen: compute only shard I of N (I from 0, a job array's index) "
                  "into OUT/shard.json; `glarecam hazard merge` combines them (docs/hazard.md, "
                  "\"Running on a cluster\")")
      ->type_name("I/N");
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
  auto merge_args = std::make_shared<HazardMergeArgs>();
  CLI::App* merge = sub->add_subcommand(
      "merge",
      "combine the shard directories of a screening (`glarecam hazard --screen --shard I/N`) "
      "into exactly the outputs one run writes");
  merge->add_option("SHARD_DIR", merge_args->shards, "shard directories (or their shard.json)")
      ->required();
  merge->add_option("--out", merge_args->out, "output directory")->required();
  merge->add_option("--scene", merge_args->scene,
                    "the scene, when it is no longer where the shards say (must be the same file)");
  merge->add_flag("--json", merge_args->json, "print screen.json on stdout instead of the table");
  merge->callback(
      [merge_args, &action] { action = [merge_args] { return runMergeCommand(*merge_args); }; });
  sub->callback([args, sub, merge, &action] {
    if (merge->parsed()) return;
    if (args->scene.empty()) throw CLI::RequiredError("SCENE (or the subcommand merge)");
    if (sub->count("--year") == 0) throw CLI::RequiredError("--year");
    if (sub->count("--out") == 0) throw CLI::RequiredError("--out");
    args->sun_given = sub->count("--sun") > 0;
    action = [args] { return runHazardCommand(*args); };
  });
}

}  // namespace glarecam::apps
